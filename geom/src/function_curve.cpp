#include "cncc/geom/function_curve.h"

#include "cncc/geom/geometry_error.h"
#include "finite_difference.h"

#include <cmath>

namespace cncc::geom {

namespace {

void checkRange(ParameterRange range) {
  if (!std::isfinite(range.t0) || !std::isfinite(range.t1) || !(range.t0 < range.t1))
    throw GeometryError("the parameter range must be finite and increasing");
}

} // namespace

FunctionCurve::FunctionCurve(ParameterRange range, PointFunction position, PointFunction first,
                             PointFunction second)
    : range_(range), position_(std::move(position)), first_(std::move(first)),
      second_(std::move(second)) {
  checkRange(range_);
  if (!position_)
    throw GeometryError("a function curve needs a position function");
}

FunctionCurve FunctionCurve::fromCoordinates(ParameterRange range, ScalarFunction x,
                                             ScalarFunction y, ScalarFunction z) {
  if (!x || !y)
    throw GeometryError("a function curve needs x(t) and y(t)");
  return FunctionCurve(range, [x = std::move(x), y = std::move(y), z = std::move(z)](double t) {
    return Eigen::Vector3d(x(t), y(t), z ? z(t) : 0.0);
  });
}

Eigen::Vector3d FunctionCurve::point(double t) const {
  return position_(range_.clamp(t));
}

Eigen::Vector3d FunctionCurve::derivative(double t) const {
  t = range_.clamp(t);
  if (first_)
    return first_(t);
  return detail::firstDerivativeByDifferences(position_, t, range_);
}

Eigen::Vector3d FunctionCurve::secondDerivative(double t) const {
  t = range_.clamp(t);
  if (second_)
    return second_(t);
  return detail::secondDerivativeByDifferences(position_, t, range_);
}

PolarCurve::PolarCurve(ParameterRange range, ScalarFunction radius, ScalarFunction radiusDerivative,
                       ScalarFunction radiusSecondDerivative)
    : range_(range), radius_(std::move(radius)), radiusDerivative_(std::move(radiusDerivative)),
      radiusSecondDerivative_(std::move(radiusSecondDerivative)) {
  checkRange(range_);
  if (!radius_)
    throw GeometryError("a polar curve needs r(t)");
}

double PolarCurve::radiusDerivative(double t) const {
  if (radiusDerivative_)
    return radiusDerivative_(t);
  return detail::firstDerivativeByDifferences(radius_, t, range_);
}

double PolarCurve::radiusSecondDerivative(double t) const {
  if (radiusSecondDerivative_)
    return radiusSecondDerivative_(t);
  return detail::secondDerivativeByDifferences(radius_, t, range_);
}

Eigen::Vector3d PolarCurve::point(double t) const {
  t = range_.clamp(t);
  double r = radius_(t);
  return {r * std::cos(t), r * std::sin(t), 0.0};
}

// As derivatives(t).first (the same arithmetic), without the second
// derivative: an offset's point asks only the first, and by differences
// the second costs five more points of r.
Eigen::Vector3d PolarCurve::derivative(double t) const {
  return pointWithDerivative(t).first;
}

// point(t) and derivative(t) with r, its cosine and sine computed once.
PointWithDerivative PolarCurve::pointWithDerivative(double t) const {
  t = range_.clamp(t);
  double r = radius_(t), dr = radiusDerivative(t);
  double c = std::cos(t), s = std::sin(t);
  return {{r * c, r * s, 0.0}, {dr * c - r * s, dr * s + r * c, 0.0}};
}

Eigen::Vector3d PolarCurve::secondDerivative(double t) const {
  return derivatives(t).second;
}

CurveDerivatives PolarCurve::derivatives(double t) const {
  t = range_.clamp(t);
  double r = radius_(t), dr = radiusDerivative(t), ddr = radiusSecondDerivative(t);
  double c = std::cos(t), s = std::sin(t);
  return {{r * c, r * s, 0.0},
          {dr * c - r * s, dr * s + r * c, 0.0},
          {ddr * c - 2.0 * dr * s - r * c, ddr * s + 2.0 * dr * c - r * s, 0.0}};
}

} // namespace cncc::geom
