#pragma once

#include "cncc/geom/curve.h"

namespace cncc::geom {

/// The tightest bend of a curve: largest curvature over the domain.
struct CurvatureExtreme {
  double parameter = 0.0;
  double curvature = 0.0;
  /// 1 / curvature, infinite for a straight curve.
  double radius = 0.0;
};

/// Largest curvature over the domain, ends included. Curvature is sampled densely on
/// every smooth piece (at least 64 samples per piece, more where the tangent turns),
/// and every sampled local maximum is refined by Brent's method, so a sharp peak
/// between samples is still found to full precision.
CurvatureExtreme minimumRadiusOfCurvature(const Curve& curve);

} // namespace cncc::geom
