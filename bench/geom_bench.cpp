// Geometry kernel benchmarks: evaluating the S-profile NURBS (reference case 1) by de
// Boor and by its per-span power-basis polynomials (Horner), and the chord
// discretisation of the polar contour (reference case 3) at 0.001 mm.

#include "cncc/geom/arc_fitting.h"
#include "cncc/geom/bspline_fitting.h"
#include "cncc/geom/discretisation.h"
#include "cncc/geom/function_curve.h"
#include "cncc/geom/nurbs_curve.h"
#include "cncc/geom/polynomial_span.h"
#include "cncc/geom/spline_knot_placement.h"

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

// The polar contour of reference case 3, r = 18 + 4 cos(2t) cos(6t), exact derivatives.
PolarCurve polarContour() {
  return PolarCurve(
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
}

// Tolerance in micrometres from the benchmark argument.
double toleranceOf(const benchmark::State& state) {
  return static_cast<double>(state.range(0)) * 1e-3;
}

// Least-squares cubic B-spline of the polar contour; argument 1 selects the
// parameterisation (0 arc length, 1 the angle).
void fitPolarContourBSpline(benchmark::State& state) {
  PolarCurve contour = polarContour();
  BSplineFitOptions options;
  options.tolerance = toleranceOf(state);
  options.parameterisation =
      state.range(1) == 0 ? FitParameterisation::ArcLength : FitParameterisation::CurveParameter;
  std::size_t controlPoints = 0;
  double deviation = 0.0;
  for (auto _ : state) {
    BSplineFit fit = fitBSpline(contour, options);
    controlPoints = fit.spline.controlPoints().size();
    deviation = fit.deviation;
  }
  state.counters["controlPoints"] = static_cast<double>(controlPoints);
  state.counters["deviation_um"] = deviation * 1e3;
}
BENCHMARK(fitPolarContourBSpline)
    ->Args({10, 0})
    ->Args({10, 1})
    ->Args({1, 0})
    ->Args({1, 1})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// Adaptive CSPLINE (argument 1 = 0) / ASPLINE (1) points on the polar contour.
void placePolarContourSplineKnots(benchmark::State& state) {
  PolarCurve contour = polarContour();
  SplineKnotPlacementOptions options;
  options.tolerance = toleranceOf(state);
  options.kind =
      state.range(1) == 0 ? InterpolatingSplineKind::CSpline : InterpolatingSplineKind::ASpline;
  std::size_t points = 0;
  double deviation = 0.0;
  for (auto _ : state) {
    SplineKnots knots = placeSplineKnots(contour, options);
    points = knots.points.size();
    deviation = knots.deviation;
  }
  state.counters["points"] = static_cast<double>(points);
  state.counters["deviation_um"] = deviation * 1e3;
}
BENCHMARK(placePolarContourSplineKnots)
    ->Args({10, 0})
    ->Args({10, 1})
    ->Args({1, 0})
    ->Args({1, 1})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

// Biarcs: argument 1 selects the curve (0 spiral of case 2, 1 polar contour, 2 the
// S-profile with w6 = 3).
void fitArcsToReferenceCurve(benchmark::State& state) {
  PolarCurve spiral(
      {0.0, 2 * std::numbers::pi}, [](double t) { return 1.0 + 2.0 * t; },
      [](double) { return 2.0; }, [](double) { return 0.0; });
  PolarCurve contour = polarContour();
  NurbsCurve profile = sProfile({1, 1, 1, 1, 1, 3, 1});
  const Curve* curves[] = {&spiral, &contour, &profile};
  const Curve& curve = *curves[state.range(1)];
  std::size_t arcs = 0, lines = 0;
  double deviation = 0.0;
  for (auto _ : state) {
    ArcFit fit = fitArcs(curve, {toleranceOf(state)});
    arcs = fit.arcCount();
    lines = fit.lineCount();
    deviation = fit.deviation;
  }
  state.counters["arcs"] = static_cast<double>(arcs);
  state.counters["lines"] = static_cast<double>(lines);
  state.counters["deviation_um"] = deviation * 1e3;
}
BENCHMARK(fitArcsToReferenceCurve)
    ->Args({5, 0})
    ->Args({10, 1})
    ->Args({10, 2})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

} // namespace

BENCHMARK_MAIN();
