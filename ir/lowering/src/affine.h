// The transforms of translate, rotate and scale, composed into one map of
// the XY plane (z is only scaled), and a curve seen through such a map.
#pragma once

#include "cncc/geom/curve.h"

#include <Eigen/Core>

#include <memory>

namespace cncc::ir::lowering {

// p -> (linear * p.xy + offset, zScale * p.z).
struct Affine {
  Eigen::Matrix2d linear = Eigen::Matrix2d::Identity();
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();
  double zScale = 1;

  static Affine translation(double dx, double dy);
  static Affine rotation(double angle);
  // Uniform scaling about the origin, z included.
  static Affine scaling(double factor);

  // This map applied after `inner`.
  Affine after(const Affine& inner) const;
  bool isIdentity() const;
  // The most it lengthens a vector: the largest singular value of the
  // plane's map, or the z scale's magnitude.
  double stretch() const;
  Eigen::Vector3d apply(const Eigen::Vector3d& point) const;
  // A direction (derivative) is mapped without the offset.
  Eigen::Vector3d applyToDirection(const Eigen::Vector3d& direction) const;
};

// `curve` mapped by `transform`, in the same parameter.
class TransformedCurve : public geom::Curve {
public:
  TransformedCurve(std::shared_ptr<const geom::Curve> curve, const Affine& transform)
      : curve_(std::move(curve)), transform_(transform) {}

  geom::ParameterRange domain() const override { return curve_->domain(); }
  Eigen::Vector3d point(double t) const override;
  Eigen::Vector3d derivative(double t) const override;
  Eigen::Vector3d secondDerivative(double t) const override;
  geom::CurveDerivatives derivatives(double t) const override;
  std::vector<double> breakpoints() const override { return curve_->breakpoints(); }

private:
  std::shared_ptr<const geom::Curve> curve_;
  Affine transform_;
};

} // namespace cncc::ir::lowering
