#pragma once

// Nearest segment of a polyline to a point (internal): a bounding-box hierarchy over
// runs of consecutive segments. Consecutive segments of a tool path or of curve
// samples lie close together, so splitting by index gives tight boxes without sorting.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstddef>
#include <vector>

namespace cncc::geom::detail {

class SegmentTree {
public:
  /// Segment i joins vertices i and i + 1; a single vertex is one degenerate segment.
  explicit SegmentTree(std::vector<Eigen::Vector3d> vertices);

  struct Nearest {
    double distance;
    std::size_t segment;
    double fraction; // position on the segment, 0 at vertex i, 1 at vertex i + 1
    Eigen::Vector3d point;
  };
  Nearest nearest(const Eigen::Vector3d& p) const;

  std::size_t segmentCount() const { return segmentCount_; }
  /// Segments measured by nearest() so far: the work of the queries.
  std::size_t segmentsMeasured() const { return segmentsMeasured_; }
  const Eigen::Vector3d& segmentStart(std::size_t i) const { return vertices_[i]; }
  const Eigen::Vector3d& segmentEnd(std::size_t i) const;

private:
  struct Node {
    Eigen::AlignedBox3d box;
    std::size_t first; // first segment
    std::size_t count; // number of segments
    int left = -1;     // child nodes, -1 for a leaf
    int right = -1;
  };
  int build(std::size_t first, std::size_t count);

  std::vector<Eigen::Vector3d> vertices_;
  std::size_t segmentCount_;
  std::vector<Node> nodes_;
  mutable std::size_t segmentsMeasured_ = 0;
};

} // namespace cncc::geom::detail
