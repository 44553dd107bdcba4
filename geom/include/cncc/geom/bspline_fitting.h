#pragma once

// Least-squares B-spline approximation of any curve within a tolerance: the spline a
// NURBS-capable controller (Sinumerik BSPLINE, Fanuc G06.2) is given in place of the
// curve.

#include "cncc/geom/curve.h"
#include "cncc/geom/nurbs_curve.h"

namespace cncc::geom {

/// How samples of the curve get their parameter in the fitted spline.
///
/// Which needs fewer control points depends on the curve. The curve's own parameter
/// wins where the coordinates are smooth functions of it: the polar contour's x(t),
/// y(t) are trigonometric polynomials of degree 9 in the angle, while in arc length
/// they carry the uneven speed sqrt(r^2 + r'^2) as well (0.01 mm: 43 control points in
/// the angle, 67 in arc length); a spline given in its own parameter is reproduced
/// exactly. Arc length wins where the parameter runs very unevenly (a speed that
/// vanishes or jumps, a rational curve with strong weights). So the default fits both
/// and keeps the smaller.
enum class FitParameterisation {
  /// The fitted spline's parameter is arc length along the curve, t in [0, length]
  /// (chord length of infinitely dense samples); its speed is then about 1.
  ArcLength,
  /// The curve's own parameter, t in the curve's domain.
  CurveParameter,
  /// Both, keeping the fit with fewer control points (arc length on a tie).
  FewestControlPoints,
};

struct BSplineFitOptions {
  /// 2 or 3.
  int degree = 3;
  /// Largest allowed distance between the spline and the curve (mm), > 0.
  double tolerance = 0.01;
  FitParameterisation parameterisation = FitParameterisation::FewestControlPoints;
  /// Rounds of parameter correction per fit: each sample's parameter is moved to its
  /// closest point on the fitted spline and the spline is fitted again, which lets the
  /// least-squares error become the geometric one.
  int parameterCorrections = 2;
};

struct BSplineFit {
  /// Clamped, unit weights; its first and last control points are the curve's ends.
  NurbsCurve spline;
  /// Both directed deviations between spline and curve (measureCurveDeviation at 1e-3
  /// of the tolerance), <= tolerance.
  double deviation = 0.0;
  /// Least-squares solves the search made.
  int fits = 0;
};

/// The clamped B-spline of the given degree with the fewest control points the search
/// finds whose deviation from `curve` stays within the tolerance.
///
/// Each fit samples the curve (16 samples per knot span, at equal steps of the fit
/// parameter), fixes the first and last control points to the curve's ends and finds
/// the others by linear least squares on the samples (the normal equations are banded
/// and, with samples in every span, well conditioned: sparse LDL^T), then corrects the
/// sample parameters (parameterCorrections). Knots are placed by equidistribution:
/// the measured error e_i of span i (length h_i) behaves like c_i h_i^(p+1), so the
/// spans needed are about sum_i (e_i / tol)^(1/(p+1)) and the next knots split the
/// integral of the density (e_i / tol)^(1/(p+1)) / h_i evenly. The count grows until
/// a fit passes, then shrinks while one still passes; every pass is confirmed by the
/// full measurement against the curve. Throws GeometryError for a degree other than 2
/// or 3 or a tolerance <= 0.
BSplineFit fitBSpline(const Curve& curve, const BSplineFitOptions& options = {});

} // namespace cncc::geom
