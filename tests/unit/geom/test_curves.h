#pragma once

// Curves shared by the geom tests: exact circles as NURBS, and the curves of the
// reference cases (shared/REFERENCE-CASES.md).

#include "cncc/geom/function_curve.h"
#include "cncc/geom/nurbs_curve.h"

#include <cmath>
#include <numbers>
#include <vector>

namespace cncc::geom::testing {

inline constexpr double kTwoPi = 2.0 * std::numbers::pi;

/// Rational quadratic quarter of the unit circle from (1, 0) to (0, 1).
inline NurbsCurve quarterCircle() {
  return NurbsCurve(KnotVector({0, 0, 0, 1, 1, 1}, 2), {{1, 0, 0}, {1, 1, 0}, {0, 1, 0}},
                    {1.0, std::sqrt(0.5), 1.0});
}

/// The whole unit circle from 9 control points (four quarter arcs, double knots).
inline NurbsCurve unitCircle() {
  double w = std::sqrt(0.5);
  return NurbsCurve(KnotVector({0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1}, 2),
                    {{1, 0, 0},
                     {1, 1, 0},
                     {0, 1, 0},
                     {-1, 1, 0},
                     {-1, 0, 0},
                     {-1, -1, 0},
                     {0, -1, 0},
                     {1, -1, 0},
                     {1, 0, 0}},
                    {1, w, 1, w, 1, w, 1, w, 1});
}

/// The part of `curve` over [a, b] as a curve of its own (same parameter).
inline FunctionCurve restrictTo(const Curve& curve, double a, double b) {
  return FunctionCurve(
      {a, b}, [&curve](double t) { return curve.point(t); },
      [&curve](double t) { return curve.derivative(t); },
      [&curve](double t) { return curve.secondDerivative(t); });
}

/// Evenly spaced parameters over a curve's domain, ends included.
inline std::vector<double> parameterGrid(const Curve& curve, int intervals) {
  ParameterRange range = curve.domain();
  std::vector<double> grid;
  for (int i = 0; i <= intervals; ++i)
    grid.push_back(i == intervals ? range.t1 : range.t0 + range.length() * i / intervals);
  return grid;
}

/// Case 3: r = 18 + 4 cos(2t) cos(6t), t in [0, 2 pi], with exact r' and r''.
inline PolarCurve polarContour() {
  return PolarCurve(
      {0.0, kTwoPi}, [](double t) { return 18.0 + 4.0 * std::cos(2 * t) * std::cos(6 * t); },
      [](double t) {
        return 4.0 *
               (-2.0 * std::sin(2 * t) * std::cos(6 * t) - 6.0 * std::cos(2 * t) * std::sin(6 * t));
      },
      [](double t) {
        return 4.0 * (-40.0 * std::cos(2 * t) * std::cos(6 * t) +
                      24.0 * std::sin(2 * t) * std::sin(6 * t));
      });
}

/// Case 2: r = 1 + 2t, t in [0, 2 pi], with exact r' and r''.
inline PolarCurve archimedeanSpiral() {
  return PolarCurve(
      {0.0, kTwoPi}, [](double t) { return 1.0 + 2.0 * t; }, [](double) { return 2.0; },
      [](double) { return 0.0; });
}

/// Case 1: the S-profile, cubic, clamped uniform knots, weights as given.
inline NurbsCurve sProfile(std::vector<double> weights = std::vector<double>(7, 1.0)) {
  std::vector<Eigen::Vector3d> points{{25, 50, 0},
                                      {42.8735, 24.1467, 0},
                                      {70.5832, 72.3597, 0},
                                      {86.6080, 165.3624, 0},
                                      {112.4532, 38.3852, 0},
                                      {132.4671, 35.1148, 0},
                                      {175, 150, 0}};
  KnotVector knots({0, 0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1, 1}, 3);
  return NurbsCurve(std::move(knots), std::move(points), std::move(weights));
}

} // namespace cncc::geom::testing
