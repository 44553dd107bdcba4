#pragma once

#include "cncc/geom/curve.h"
#include "cncc/geom/nurbs_curve.h"

#include <Eigen/Core>

#include <vector>

namespace cncc::geom {

/// One knot span of a (rational) spline as a polynomial in the power basis: the form
/// the compiler emits to controllers (Sinumerik POLY, macro Horner loops).
///
/// The local parameter is NORMALISED: u = (t - t0) / (t1 - t0), u in [0, 1].
/// coefficients[k] holds the coefficient of u^k (ascending powers, k = 0..degree) of
/// the homogeneous numerator and weight, (X, Y, Z, W):
///
///     x(u) = X(u) / W(u),  X(u) = sum_k coefficients[k].x() u^k,  likewise y, z,
///     W(u) = sum_k coefficients[k].w() u^k.
///
/// For a non-rational span W(u) = 1: coefficients[0].w() = 1, the other w() are 0,
/// and X, Y, Z are the coordinates themselves.
struct PolynomialSpan {
  double t0 = 0.0;
  double t1 = 1.0;
  std::vector<HomogeneousPoint> coefficients;

  int degree() const { return static_cast<int>(coefficients.size()) - 1; }
  bool isRational() const;
  /// (X, Y, Z, W) at u by Horner's rule.
  HomogeneousPoint homogeneousAt(double u) const;
  /// The curve point at u (one division when rational).
  Eigen::Vector3d pointAt(double u) const;
  /// Point and first two derivatives with respect to u (divide by (t1 - t0)^k for t).
  CurveDerivatives derivativesAt(double u) const;
};

/// The same span in Bernstein (Bezier) form over the same normalised u in [0, 1]:
/// controlPoints[j] are the homogeneous (w x, w y, w z, w) Bezier points, so
/// x(u) = sum_j B_{j,p}(u) X_j / sum_j B_{j,p}(u) W_j.
struct BezierSpan {
  double t0 = 0.0;
  double t1 = 1.0;
  std::vector<HomogeneousPoint> controlPoints;

  int degree() const { return static_cast<int>(controlPoints.size()) - 1; }
  /// The curve point at u by de Casteljau's algorithm.
  Eigen::Vector3d pointAt(double u) const;
};

/// One PolynomialSpan per non-empty knot span, in order. Coefficients are the Taylor
/// coefficients of the span's polynomial piece at t0 scaled to the normalised u.
std::vector<PolynomialSpan> toPowerBasis(const NurbsCurve& curve);
/// One BezierSpan per non-empty knot span, in order.
std::vector<BezierSpan> toBezierSpans(const NurbsCurve& curve);

PolynomialSpan toPowerBasis(const BezierSpan& span);
BezierSpan toBezier(const PolynomialSpan& span);

/// A curve made of consecutive polynomial spans (each t1 equals the next t0),
/// evaluated by Horner's rule. It is what a controller that receives the spans
/// executes, so the virtual controller and the benchmarks use it.
class PiecewisePolynomialCurve : public Curve {
public:
  /// Throws GeometryError if spans is empty, a span is empty or of degree > kMaxDegree,
  /// or spans do not follow one another in parameter.
  explicit PiecewisePolynomialCurve(std::vector<PolynomialSpan> spans);

  const std::vector<PolynomialSpan>& spans() const { return spans_; }
  /// Index of the span holding t (the later one at a shared end).
  std::size_t spanIndex(double t) const;

  ParameterRange domain() const override;
  Eigen::Vector3d point(double t) const override;
  Eigen::Vector3d derivative(double t) const override;
  Eigen::Vector3d secondDerivative(double t) const override;
  CurveDerivatives derivatives(double t) const override;
  std::vector<double> breakpoints() const override;

private:
  std::vector<PolynomialSpan> spans_;
};

} // namespace cncc::geom
