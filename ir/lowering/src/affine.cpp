#include "affine.h"

#include <Eigen/SVD>

#include <algorithm>
#include <cmath>

namespace cncc::ir::lowering {

Affine Affine::translation(double dx, double dy) {
  Affine result;
  result.offset = {dx, dy};
  return result;
}

Affine Affine::rotation(double angle) {
  Affine result;
  result.linear << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  return result;
}

Affine Affine::scaling(double factor) {
  Affine result;
  result.linear *= factor;
  result.zScale = factor;
  return result;
}

Affine Affine::after(const Affine& inner) const {
  Affine result;
  result.linear = linear * inner.linear;
  result.offset = linear * inner.offset + offset;
  result.zScale = zScale * inner.zScale;
  return result;
}

double Affine::stretch() const {
  Eigen::JacobiSVD<Eigen::Matrix2d> decomposition(linear);
  return std::max(decomposition.singularValues()(0), std::abs(zScale));
}

bool Affine::isIdentity() const {
  return linear == Eigen::Matrix2d::Identity() && offset == Eigen::Vector2d::Zero() && zScale == 1;
}

Eigen::Vector3d Affine::apply(const Eigen::Vector3d& point) const {
  Eigen::Vector2d xy = linear * point.head<2>() + offset;
  return {xy.x(), xy.y(), zScale * point.z()};
}

Eigen::Vector3d Affine::applyToDirection(const Eigen::Vector3d& direction) const {
  Eigen::Vector2d xy = linear * direction.head<2>();
  return {xy.x(), xy.y(), zScale * direction.z()};
}

Eigen::Vector3d TransformedCurve::point(double t) const {
  return transform_.apply(curve_->point(t));
}

Eigen::Vector3d TransformedCurve::derivative(double t) const {
  return transform_.applyToDirection(curve_->derivative(t));
}

Eigen::Vector3d TransformedCurve::secondDerivative(double t) const {
  return transform_.applyToDirection(curve_->secondDerivative(t));
}

geom::CurveDerivatives TransformedCurve::derivatives(double t) const {
  geom::CurveDerivatives inner = curve_->derivatives(t);
  return {transform_.apply(inner.point), transform_.applyToDirection(inner.first),
          transform_.applyToDirection(inner.second)};
}

} // namespace cncc::ir::lowering
