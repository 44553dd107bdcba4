#pragma once

// The nearest of many line segments to a point: a bounding-box hierarchy over
// runs of consecutive segments. Consecutive segments of a tool path or of curve
// samples lie close together, so splitting by index gives tight boxes without
// sorting, and a query measures O(log n) segments where the path is not folded
// onto itself.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstddef>
#include <optional>
#include <vector>

namespace cncc::geom {

struct LineSegment {
  Eigen::Vector3d start;
  Eigen::Vector3d end;
};

class SegmentTree {
public:
  /// The segments in path order; none gives one degenerate segment at the origin.
  explicit SegmentTree(std::vector<LineSegment> segments);
  /// Segment i joins vertices i and i + 1; a single vertex is one degenerate segment.
  static SegmentTree throughVertices(const std::vector<Eigen::Vector3d>& vertices);

  struct Nearest {
    double distance;
    std::size_t segment;
    double fraction; // position on the segment, 0 at its start, 1 at its end
    Eigen::Vector3d point;
  };
  Nearest nearest(const Eigen::Vector3d& p) const;
  /// nearest(p).distance, searched from segment `hint` (any index) first, and
  /// the segment found left in `hint`: for queries along a path, whose
  /// nearest segment moves little from one to the next, the search starts
  /// from a close bound and skips most boxes.
  double nearestDistance(const Eigen::Vector3d& p, std::size_t& hint) const;
  /// The first segment in path order, at index `from` or later, that comes
  /// within `radius` of p, with its point nearest p; nullopt when none does.
  /// Where a path passes one place twice, this is the pass that comes first.
  std::optional<Nearest> firstWithin(const Eigen::Vector3d& p, double radius,
                                     std::size_t from) const;

  std::size_t segmentCount() const { return segments_.size(); }
  const LineSegment& segment(std::size_t i) const { return segments_[i]; }
  /// The box around every segment.
  const Eigen::AlignedBox3d& bounds() const { return nodes_.front().box; }
  /// Segments measured by nearest() so far: the work of the queries.
  std::size_t segmentsMeasured() const { return segmentsMeasured_; }

private:
  struct Node {
    Eigen::AlignedBox3d box;
    std::size_t first; // first segment
    std::size_t count; // number of segments
    int left = -1;     // child nodes, -1 for a leaf
    int right = -1;
    int parent = -1; // -1 for the root
  };
  int build(std::size_t first, std::size_t count);
  // The nearest segment, or `best` where none is nearer: of all, and of those
  // under node `root`, whose box is `rootDistance` from p.
  Nearest search(const Eigen::Vector3d& p, Nearest best) const;
  Nearest searchBelow(const Eigen::Vector3d& p, int root, double rootDistance, Nearest best) const;
  // Segment i's point nearest p.
  Nearest measure(const Eigen::Vector3d& p, std::size_t i) const;

  std::vector<LineSegment> segments_;
  std::vector<Node> nodes_;
  mutable std::size_t segmentsMeasured_ = 0;
};

} // namespace cncc::geom
