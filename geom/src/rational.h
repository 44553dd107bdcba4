#pragma once

// Derivatives of a rational curve C = A / w from those of its homogeneous form
// (The NURBS Book eq. 4.8 specialised to orders 0..2). Internal helper.

#include "cncc/geom/curve.h"

#include <Eigen/Core>

namespace cncc::geom::detail {

inline CurveDerivatives rationalDerivatives(const Eigen::Vector4d& h0, const Eigen::Vector4d& h1,
                                            const Eigen::Vector4d& h2) {
  double w = h0.w();
  CurveDerivatives d;
  d.point = h0.head<3>() / w;
  d.first = (h1.head<3>() - h1.w() * d.point) / w;
  d.second = (h2.head<3>() - 2.0 * h1.w() * d.first - h2.w() * d.point) / w;
  return d;
}

} // namespace cncc::geom::detail
