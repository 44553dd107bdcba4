#include "cncc/geom/segment_tree.h"

#include "cncc/geom/geometry_error.h"
#include "vector_math.h"

#include <algorithm>
#include <array>
#include <limits>
#include <utility>

namespace cncc::geom {

namespace {

constexpr std::size_t kLeafSize = 4;
// nearest(p, hint)'s bound above the hint's distance, relative to that
// distance and p's largest coordinate.
constexpr double kBoundMargin = 1e-9;

} // namespace

SegmentTree::SegmentTree(const std::vector<LineSegment>& segments) : SegmentTree({}, 2) {
  points_.reserve(2 * std::max<std::size_t>(segments.size(), 1));
  for (const LineSegment& segment : segments) {
    points_.push_back(segment.start);
    points_.push_back(segment.end);
  }
  if (points_.empty()) {
    points_.assign(2, Eigen::Vector3d::Zero());
  }
  segmentCount_ = points_.size() / 2;
  build(0, segmentCount_);
}

SegmentTree::SegmentTree(std::vector<Eigen::Vector3d> points, std::size_t stride)
    : points_(std::move(points)), stride_(stride) {}

SegmentTree SegmentTree::throughVertices(std::vector<Eigen::Vector3d> vertices) {
  if (vertices.empty()) {
    vertices.push_back(Eigen::Vector3d::Zero());
  }
  if (vertices.size() == 1) {
    vertices.push_back(vertices.front());
  }
  SegmentTree tree(std::move(vertices), 1);
  tree.segmentCount_ = tree.points_.size() - 1;
  tree.build(0, tree.segmentCount_);
  return tree;
}

int SegmentTree::build(std::size_t first, std::size_t count) {
  if (nodes_.empty()) {
    if (count > std::numeric_limits<std::uint32_t>::max()) {
      throw GeometryError("a segment tree holds fewer than 2^32 segments");
    }
    nodes_.reserve(2 * count / kLeafSize + 2);
  }
  Node node;
  node.first = static_cast<std::uint32_t>(first);
  node.count = static_cast<std::uint32_t>(count);
  node.box.setEmpty();
  int index = static_cast<int>(nodes_.size());
  nodes_.push_back(node);
  if (count <= kLeafSize) {
    Eigen::AlignedBox3d& box = nodes_[static_cast<std::size_t>(index)].box;
    for (std::size_t i = first; i < first + count; ++i) {
      box.extend(start(i));
      box.extend(end(i));
    }
    return index;
  }
  // A box is its children's together (the same smallest and largest
  // coordinates as of its segments', without reading them again at every
  // level).
  std::size_t half = count / 2;
  int left = build(first, half);
  int right = build(first + half, count - half);
  Node& built = nodes_[static_cast<std::size_t>(index)];
  built.right = right;
  built.box = nodes_[static_cast<std::size_t>(left)].box.merged(
      nodes_[static_cast<std::size_t>(right)].box);
  return index;
}

SegmentTree::Nearest SegmentTree::measure(const Eigen::Vector3d& p, std::size_t i) const {
  const Eigen::Vector3d& a = start(i);
  const Eigen::Vector3d& b = end(i);
  double f = detail::closestFractionOnSegment(p, a, b);
  Eigen::Vector3d q = a + f * (b - a);
  return {(p - q).norm(), i, f, q};
}

SegmentTree::Nearest SegmentTree::nearest(const Eigen::Vector3d& p) const {
  return searchBelow(p, 0, nodes_.front().box.exteriorDistance(p),
                     {std::numeric_limits<double>::infinity(), 0, 0.0, start(0)});
}

SegmentTree::Nearest SegmentTree::nearest(const Eigen::Vector3d& p, std::size_t hint) const {
  // nearest(p)'s search from the root, its best distance at the start not
  // infinity but a bound: the hint's distance and a margin far above
  // rounding (a box's distance may exceed that of a segment inside it by a
  // few units in the last place). The boxes nearer than the bound are
  // opened in the order nearest(p) opens them, and the segment it finds is
  // under them, so it wins here too; the boxes beyond, which nearest(p)
  // opens while its best is still far, are skipped. Nothing found under the
  // bound (rounding beyond the margin): nearest(p).
  double bound = measure(p, std::min(hint, segmentCount_ - 1)).distance;
  bound += kBoundMargin * (bound + p.cwiseAbs().maxCoeff());
  if (!(bound < std::numeric_limits<double>::infinity())) {
    return nearest(p);
  }
  Nearest none{bound, segmentCount_, 0.0, p};
  Nearest found = searchBelow(p, 0, nodes_.front().box.exteriorDistance(p), none);
  return found.segment < segmentCount_ ? found : nearest(p);
}

double SegmentTree::nearestDistance(const Eigen::Vector3d& p, std::size_t& hint) const {
  hint = std::min(hint, segmentCount_ - 1);
  // The leaf holding the hint, then, up from it, the other child of each
  // node on the way to the root: every segment is in one of them, and a
  // subtree whose box is no nearer than the best so far is skipped whole.
  std::array<int, 64> path;
  std::size_t depth = 0;
  int leaf = 0;
  while (nodes_[static_cast<std::size_t>(leaf)].right >= 0) {
    path[depth++] = leaf;
    const Node& left = nodes_[static_cast<std::size_t>(leaf + 1)];
    leaf = hint < std::size_t{left.first} + left.count
               ? leaf + 1
               : nodes_[static_cast<std::size_t>(leaf)].right;
  }
  Nearest best = searchBelow(p, leaf, 0.0, measure(p, hint));
  for (int node = leaf; depth > 0; node = path[--depth]) {
    int above = path[depth - 1];
    int other = node == above + 1 ? nodes_[static_cast<std::size_t>(above)].right : above + 1;
    best = searchBelow(p, other, nodes_[static_cast<std::size_t>(other)].box.exteriorDistance(p),
                       best);
  }
  // Every segment's distance is computed the same way whatever the order of
  // the search, so the smallest is nearest(p)'s (a tie may leave another
  // segment in `hint`).
  hint = best.segment;
  return best.distance;
}

SegmentTree::Nearest SegmentTree::searchBelow(const Eigen::Vector3d& p, int root,
                                              double rootDistance, Nearest best) const {
  // Depth-first, nearer box first; a box farther than the best segment so far is skipped.
  // The tree is balanced, so the stack never holds more than about 2 log2(n) entries.
  // Each entry keeps its box's distance, measured once when its parent was visited.
  struct Entry {
    int node;
    double distance;
  };
  std::array<Entry, 2 * 64> stack;
  std::size_t top = 0;
  stack[top++] = {root, rootDistance};
  while (top > 0) {
    Entry entry = stack[--top];
    if (entry.distance >= best.distance)
      continue;
    const Node& node = nodes_[static_cast<std::size_t>(entry.node)];
    if (node.right < 0) {
      segmentsMeasured_ += node.count;
      for (std::size_t i = node.first; i < std::size_t{node.first} + node.count; ++i) {
        Nearest candidate = measure(p, i);
        if (candidate.distance < best.distance)
          best = candidate;
      }
      continue;
    }
    Entry left{entry.node + 1,
               nodes_[static_cast<std::size_t>(entry.node + 1)].box.exteriorDistance(p)};
    Entry right{node.right, nodes_[static_cast<std::size_t>(node.right)].box.exteriorDistance(p)};
    bool leftFirst = left.distance <= right.distance;
    stack[top++] = leftFirst ? right : left;
    stack[top++] = leftFirst ? left : right;
  }
  return best;
}

std::optional<SegmentTree::Nearest>
SegmentTree::firstWithin(const Eigen::Vector3d& p, double radius, std::size_t from) const {
  // Depth-first, the earlier half first, so the first segment found is the
  // first in path order; a box wholly before `from` or farther than `radius`
  // is skipped.
  std::array<int, 2 * 64> stack;
  std::size_t top = 0;
  stack[top++] = 0;
  while (top > 0) {
    int index = stack[--top];
    const Node& node = nodes_[static_cast<std::size_t>(index)];
    std::size_t last = std::size_t{node.first} + node.count;
    if (last <= from || node.box.exteriorDistance(p) > radius) {
      continue;
    }
    if (node.right < 0) {
      std::size_t first = std::max<std::size_t>(node.first, from);
      segmentsMeasured_ += last - first;
      for (std::size_t i = first; i < last; ++i) {
        const Eigen::Vector3d& a = start(i);
        const Eigen::Vector3d& b = end(i);
        double f = detail::closestFractionOnSegment(p, a, b);
        Eigen::Vector3d q = a + f * (b - a);
        double d = (p - q).norm();
        if (d <= radius) {
          return Nearest{d, i, f, q};
        }
      }
      continue;
    }
    stack[top++] = node.right;
    stack[top++] = index + 1;
  }
  return std::nullopt;
}

} // namespace cncc::geom
