#pragma once

// The nearest of many line segments to a point: a bounding-box hierarchy over
// runs of consecutive segments. Consecutive segments of a tool path or of curve
// samples lie close together, so splitting by index gives tight boxes without
// sorting, and a query measures O(log n) segments where the path is not folded
// onto itself.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstddef>
#include <cstdint>
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
  explicit SegmentTree(const std::vector<LineSegment>& segments);
  /// Segment i joins vertices i and i + 1; a single vertex is one degenerate
  /// segment, none one at the origin. The tree keeps the vertices themselves
  /// (points()), not a segment for each pair of them.
  static SegmentTree throughVertices(std::vector<Eigen::Vector3d> vertices);

  struct Nearest {
    double distance;
    std::size_t segment;
    double fraction; // position on the segment, 0 at its start, 1 at its end
    Eigen::Vector3d point;
  };
  Nearest nearest(const Eigen::Vector3d& p) const;
  /// nearest(p), the same segment and numbers to the bit, found sooner where
  /// segment `hint` (any index) is near p: its distance bounds the search from
  /// the start, so boxes farther than it are skipped without being opened.
  Nearest nearest(const Eigen::Vector3d& p, std::size_t hint) const;
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

  std::size_t segmentCount() const { return segmentCount_; }
  LineSegment segment(std::size_t i) const { return {start(i), end(i)}; }
  /// The points the segments join: throughVertices' vertices as given where
  /// there were two or more; each segment's start and end for the others.
  const std::vector<Eigen::Vector3d>& points() const { return points_; }
  /// The box around every segment.
  const Eigen::AlignedBox3d& bounds() const { return nodes_.front().box; }
  /// Segments measured by nearest() so far: the work of the queries.
  std::size_t segmentsMeasured() const { return segmentsMeasured_; }

private:
  // Segment i joins points_[stride * i] and points_[stride * i + 1].
  SegmentTree(std::vector<Eigen::Vector3d> points, std::size_t stride);

  // 64 bytes: the left child is the next node (the nodes are in depth-first
  // order), so only the right one is kept.
  struct Node {
    Eigen::AlignedBox3d box;
    std::uint32_t first = 0; // first segment
    std::uint32_t count = 0; // number of segments
    std::int32_t right = -1; // the right child, -1 for a leaf
  };
  int build(std::size_t first, std::size_t count);
  const Eigen::Vector3d& start(std::size_t i) const { return points_[stride_ * i]; }
  const Eigen::Vector3d& end(std::size_t i) const { return points_[stride_ * i + 1]; }
  // The nearest segment, or `best` where none is nearer: of those under node
  // `root`, whose box is `rootDistance` from p.
  Nearest searchBelow(const Eigen::Vector3d& p, int root, double rootDistance, Nearest best) const;
  // Segment i's point nearest p.
  Nearest measure(const Eigen::Vector3d& p, std::size_t i) const;

  std::vector<Eigen::Vector3d> points_;
  std::size_t stride_ = 1;
  std::size_t segmentCount_ = 0;
  std::vector<Node> nodes_;
  mutable std::size_t segmentsMeasured_ = 0;
};

} // namespace cncc::geom
