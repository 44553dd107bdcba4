#include "cncc/geom/composite_curve.h"

#include "cncc/geom/geometry_error.h"

#include <fmt/format.h>

#include <algorithm>

namespace cncc::geom {

CompositeCurve::CompositeCurve(std::vector<std::shared_ptr<const Curve>> pieces,
                               double joinTolerance)
    : pieces_(std::move(pieces)) {
  if (pieces_.empty())
    throw GeometryError("a path needs at least one curve");
  starts_.push_back(0.0);
  for (std::size_t i = 0; i < pieces_.size(); ++i) {
    if (!pieces_[i])
      throw GeometryError("path piece " + std::to_string(i) + " is missing");
    ParameterRange range = pieces_[i]->domain();
    if (i > 0) {
      ParameterRange previous = pieces_[i - 1]->domain();
      double gap = (pieces_[i]->point(range.t0) - pieces_[i - 1]->point(previous.t1)).norm();
      if (gap > joinTolerance)
        throw GeometryError(fmt::format("path piece {} starts {:.3g} mm away from where piece {} "
                                        "ends",
                                        i, gap, i - 1));
    }
    starts_.push_back(starts_.back() + range.length());
  }
}

std::pair<std::size_t, double> CompositeCurve::locate(double t) const {
  t = domain().clamp(t);
  auto after = std::upper_bound(starts_.begin(), starts_.end() - 1, t);
  std::size_t i = static_cast<std::size_t>(after - starts_.begin());
  i = std::clamp<std::size_t>(i, 1, pieces_.size()) - 1;
  ParameterRange range = pieces_[i]->domain();
  return {i, range.clamp(range.t0 + (t - starts_[i]))};
}

Eigen::Vector3d CompositeCurve::point(double t) const {
  auto [i, local] = locate(t);
  return pieces_[i]->point(local);
}

Eigen::Vector3d CompositeCurve::derivative(double t) const {
  auto [i, local] = locate(t);
  return pieces_[i]->derivative(local);
}

Eigen::Vector3d CompositeCurve::secondDerivative(double t) const {
  auto [i, local] = locate(t);
  return pieces_[i]->secondDerivative(local);
}

CurveDerivatives CompositeCurve::derivatives(double t) const {
  auto [i, local] = locate(t);
  return pieces_[i]->derivatives(local);
}

std::vector<double> CompositeCurve::breakpoints() const {
  std::vector<double> result{0.0};
  for (std::size_t i = 0; i < pieces_.size(); ++i) {
    ParameterRange range = pieces_[i]->domain();
    for (double b : pieces_[i]->breakpoints()) {
      double global = starts_[i] + (b - range.t0);
      if (global > result.back())
        result.push_back(global);
    }
  }
  result.back() = starts_.back();
  return result;
}

} // namespace cncc::geom
