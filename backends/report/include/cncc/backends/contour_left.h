// The contour a cut beside its curve (side=left|right) leaves: the tool's
// centre runs on the offset of the drawn curve by the tool radius r, so the
// material left at a point C(t) of the drawn curve is d(C(t), path) - r, the
// path being the executed tool-centre path of the cut in plan view. Positive:
// material left (undercut); negative: the tool cut into the part (gouge).
// Where the exact offset itself cannot reach the curve (the inside of a sharp
// corner), what it leaves is not counted as an undercut.
#pragma once

#include "cncc/ir/cut_geometry.h"

#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace cncc::backends {

struct ContourLeft {
  std::size_t cut = 0;
  double tolerance = 0; // NaN: samples= or spacing= chose the points
  double toolRadius = 0;
  // Material left beyond what the exact offset leaves (>= 0), and the point
  // of the drawn curve where it is largest (in XY).
  double largestUndercut = 0;
  Eigen::Vector3d undercutAt = Eigen::Vector3d::Zero();
  // How far the tool cut past the drawn curve (>= 0), and where.
  double largestGouge = 0;
  Eigen::Vector3d gougeAt = Eigen::Vector3d::Zero();
  std::size_t samples = 0; // points of the drawn curve measured

  bool withinTolerance() const {
    return !(largestUndercut > tolerance) && !(largestGouge > tolerance);
  }
};

// The most points of a drawn curve measured: each is a nearest-segment
// query of the path's tree (a few microseconds).
inline constexpr std::size_t maximumContourSamples = 1'000'000;

// Measures the contour `cut` (which has a drawnCurve) leaves where the tool
// centre runs along `polylines` (the cut's feed moves in XY, cutPolylines).
// The drawn curve is sampled a quarter of the tolerance apart along its
// length (at most maximumContourSamples), and the largest gouge and
// undercut refined between the samples, to within `accuracy`.
ContourLeft measureContourLeft(std::size_t cutIndex, const ir::CutGeometry& cut,
                               const std::vector<std::vector<Eigen::Vector3d>>& polylines,
                               double accuracy);

} // namespace cncc::backends
