// Geometry kernel benchmarks: evaluating the S-profile NURBS (reference case 1) by de
// Boor and by its per-span power-basis polynomials (Horner), and the chord
// discretisation of the polar contour (reference case 3) at 0.001 mm.

#include "cncc/geom/discretisation.h"
#include "cncc/geom/function_curve.h"
#include "cncc/geom/nurbs_curve.h"
#include "cncc/geom/polynomial_span.h"

#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>

namespace {

using namespace cncc::geom;

constexpr int kPointsPerIteration = 1000;

NurbsCurve sProfile(std::vector<double> weights) {
  std::vector<Eigen::Vector3d> points{{25, 50, 0},
                                      {42.8735, 24.1467, 0},
                                      {70.5832, 72.3597, 0},
                                      {86.6080, 165.3624, 0},
                                      {112.4532, 38.3852, 0},
                                      {132.4671, 35.1148, 0},
                                      {175, 150, 0}};
  return NurbsCurve(KnotVector({0, 0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1, 1}, 3), points, weights);
}

// Argument 0: unit weights (polynomial); 1: w6 = 3 (rational).
NurbsCurve benchmarkCurve(const benchmark::State& state) {
  return state.range(0) == 0 ? sProfile({1, 1, 1, 1, 1, 1, 1}) : sProfile({1, 1, 1, 1, 1, 3, 1});
}

void evaluateByDeBoor(benchmark::State& state) {
  NurbsCurve curve = benchmarkCurve(state);
  for (auto _ : state) {
    for (int i = 0; i < kPointsPerIteration; ++i)
      benchmark::DoNotOptimize(curve.point(i / double(kPointsPerIteration - 1)));
  }
  state.SetItemsProcessed(state.iterations() * kPointsPerIteration);
}
BENCHMARK(evaluateByDeBoor)->Arg(0)->Arg(1);

void evaluateByPowerBasisHorner(benchmark::State& state) {
  // As a controller would: find the span, then one Horner evaluation (and one division
  // when rational).
  PiecewisePolynomialCurve curve(toPowerBasis(benchmarkCurve(state)));
  for (auto _ : state) {
    for (int i = 0; i < kPointsPerIteration; ++i)
      benchmark::DoNotOptimize(curve.point(i / double(kPointsPerIteration - 1)));
  }
  state.SetItemsProcessed(state.iterations() * kPointsPerIteration);
}
BENCHMARK(evaluateByPowerBasisHorner)->Arg(0)->Arg(1);

void evaluateOneSpanByHorner(benchmark::State& state) {
  // The inner loop of a macro program: the span is known, only Horner remains.
  PolynomialSpan span = toPowerBasis(benchmarkCurve(state))[1];
  for (auto _ : state) {
    for (int i = 0; i < kPointsPerIteration; ++i)
      benchmark::DoNotOptimize(span.pointAt(i / double(kPointsPerIteration - 1)));
  }
  state.SetItemsProcessed(state.iterations() * kPointsPerIteration);
}
BENCHMARK(evaluateOneSpanByHorner)->Arg(0)->Arg(1);

void discretisePolarContour(benchmark::State& state) {
  PolarCurve contour(
      {0.0, 2 * std::numbers::pi},
      [](double t) { return 18.0 + 4.0 * std::cos(2 * t) * std::cos(6 * t); },
      [](double t) {
        return 4.0 *
               (-2.0 * std::sin(2 * t) * std::cos(6 * t) - 6.0 * std::cos(2 * t) * std::sin(6 * t));
      },
      [](double t) {
        return 4.0 * (-40.0 * std::cos(2 * t) * std::cos(6 * t) +
                      24.0 * std::sin(2 * t) * std::sin(6 * t));
      });
  std::size_t chords = 0;
  for (auto _ : state) {
    CurveSamples samples = discretiseByChordTolerance(contour, 0.001);
    chords = samples.chordCount();
    benchmark::DoNotOptimize(samples.points.data());
  }
  state.counters["chords"] = static_cast<double>(chords);
}
BENCHMARK(discretisePolarContour)->Unit(benchmark::kMillisecond);

} // namespace

BENCHMARK_MAIN();
