// A curve seen from +z: its points and derivatives with z = 0. What the
// deviation "in XY" is measured against, so that a cut whose curve climbs
// or descends (a helix, a floor pass at its depth) is measured as its path's
// plan view is, like every planar cut.
#pragma once

#include "cncc/geom/curve.h"

namespace cncc::backends {

class PlaneProjection final : public geom::Curve {
public:
  // Keeps a reference to `curve`, which must outlive the projection.
  explicit PlaneProjection(const geom::Curve& curve) : curve_(curve) {}
  PlaneProjection(const geom::Curve&& curve) = delete; // would dangle

  geom::ParameterRange domain() const override { return curve_.domain(); }
  Eigen::Vector3d point(double t) const override { return flat(curve_.point(t)); }
  Eigen::Vector3d derivative(double t) const override { return flat(curve_.derivative(t)); }
  Eigen::Vector3d secondDerivative(double t) const override {
    return flat(curve_.secondDerivative(t));
  }
  geom::CurveDerivatives derivatives(double t) const override {
    geom::CurveDerivatives all = curve_.derivatives(t);
    return {flat(all.point), flat(all.first), flat(all.second)};
  }
  std::vector<double> breakpoints() const override { return curve_.breakpoints(); }

private:
  static Eigen::Vector3d flat(const Eigen::Vector3d& v) { return {v.x(), v.y(), 0.0}; }

  const geom::Curve& curve_;
};

} // namespace cncc::backends
