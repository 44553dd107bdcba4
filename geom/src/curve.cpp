#include "cncc/geom/curve.h"

#include <Eigen/Geometry>

namespace cncc::geom {

CurveDerivatives Curve::derivatives(double t) const {
  return {point(t), derivative(t), secondDerivative(t)};
}

PointWithDerivative Curve::pointWithDerivative(double t) const {
  return {point(t), derivative(t)};
}

std::vector<double> Curve::breakpoints() const {
  ParameterRange range = domain();
  return {range.t0, range.t1};
}

double Curve::curvature(double t) const {
  return curvatureOf(derivatives(t));
}

double curvatureOf(const CurveDerivatives& d) {
  double speed = d.first.norm();
  if (speed == 0.0)
    return 0.0;
  return d.first.cross(d.second).norm() / (speed * speed * speed);
}

} // namespace cncc::geom
