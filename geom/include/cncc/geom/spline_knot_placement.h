#pragma once

// Choosing the points a CSPLINE / ASPLINE program lists: points on the true curve,
// denser where it bends, such that the controller's spline through them (as modelled
// in interpolating_splines.h) stays within a tolerance of the curve, with as few
// points as the search finds.

#include "cncc/geom/curve.h"
#include "cncc/geom/interpolating_splines.h"

#include <Eigen/Core>

#include <vector>

namespace cncc::geom {

enum class InterpolatingSplineKind { CSpline, ASpline };

struct SplineKnotPlacementOptions {
  InterpolatingSplineKind kind = InterpolatingSplineKind::CSpline;
  /// Largest allowed distance between the modelled spline and the curve (mm), > 0.
  double tolerance = 0.01;
  /// Transitions the program will ask for. A Tangent end without a direction gets the
  /// curve's own tangent there (the program must then arrive / leave along it).
  SplineTransitions transitions;
  CSplineOptions cSpline;
};

struct SplineKnots {
  /// Curve parameters of the points, first t0 and last t1.
  std::vector<double> parameters;
  std::vector<Eigen::Vector3d> points;
  /// The transitions used, with the directions filled in.
  SplineTransitions transitions;
  /// Both directed deviations between the modelled spline and the curve, measured by
  /// measureCurveDeviation at 1e-3 of the tolerance.
  double deviation = 0.0;
};

/// Points for the modelled spline of `options.kind` through which it stays within the
/// tolerance of `curve`.
///
/// 1. Greedy farthest reach: from the last point P_k the next is the farthest curve
///    point (doubling, then bisection) for which the modelled segments that the new
///    point already fixes or changes stay within the tolerance, the points not yet
///    chosen being predicted at the same parameter step along the curve.
/// 2. Repair: every segment of the whole modelled spline is measured against the
///    curve; a segment that strays gets the curve point at its middle parameter.
/// 3. Cleanup: each point in turn is dropped if the segments it influences stay
///    within the tolerance without it; then repair again.
/// The search is a heuristic (the deviation is not monotone in the spacing), so the
/// count is small, not proven minimal. Throws GeometryError for a tolerance <= 0.
SplineKnots placeSplineKnots(const Curve& curve, const SplineKnotPlacementOptions& options);

/// The modelled spline of `kind` through `points` (cSpline or aSpline).
PiecewisePolynomialCurve modelSpline(InterpolatingSplineKind kind,
                                     const std::vector<Eigen::Vector3d>& points,
                                     const SplineTransitions& transitions,
                                     const CSplineOptions& cSplineOptions = {});

} // namespace cncc::geom
