#include "cncc/geom/segment_tree.h"

#include "vector_math.h"

#include <algorithm>
#include <array>
#include <limits>

namespace cncc::geom {

namespace {

constexpr std::size_t kLeafSize = 4;

} // namespace

SegmentTree::SegmentTree(std::vector<LineSegment> segments) : segments_(std::move(segments)) {
  if (segments_.empty())
    segments_.push_back({Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()});
  nodes_.reserve(2 * segments_.size() / kLeafSize + 2);
  build(0, segments_.size());
}

SegmentTree SegmentTree::throughVertices(const std::vector<Eigen::Vector3d>& vertices) {
  std::vector<LineSegment> segments;
  segments.reserve(std::max<std::size_t>(vertices.size(), 2) - 1);
  if (vertices.size() == 1)
    segments.push_back({vertices.front(), vertices.front()});
  for (std::size_t i = 0; i + 1 < vertices.size(); ++i)
    segments.push_back({vertices[i], vertices[i + 1]});
  return SegmentTree(std::move(segments));
}

int SegmentTree::build(std::size_t first, std::size_t count) {
  Node node;
  node.first = first;
  node.count = count;
  node.box.setEmpty();
  int index = static_cast<int>(nodes_.size());
  nodes_.push_back(node);
  if (count <= kLeafSize) {
    Eigen::AlignedBox3d& box = nodes_[static_cast<std::size_t>(index)].box;
    for (std::size_t i = first; i < first + count; ++i) {
      box.extend(segments_[i].start);
      box.extend(segments_[i].end);
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
  built.left = left;
  built.right = right;
  built.box = nodes_[static_cast<std::size_t>(left)].box.merged(
      nodes_[static_cast<std::size_t>(right)].box);
  nodes_[static_cast<std::size_t>(left)].parent = index;
  nodes_[static_cast<std::size_t>(right)].parent = index;
  return index;
}

SegmentTree::Nearest SegmentTree::measure(const Eigen::Vector3d& p, std::size_t i) const {
  const Eigen::Vector3d& a = segments_[i].start;
  const Eigen::Vector3d& b = segments_[i].end;
  double f = detail::closestFractionOnSegment(p, a, b);
  Eigen::Vector3d q = a + f * (b - a);
  return {(p - q).norm(), i, f, q};
}

SegmentTree::Nearest SegmentTree::nearest(const Eigen::Vector3d& p) const {
  return search(p, {std::numeric_limits<double>::infinity(), 0, 0.0, segments_.front().start});
}

double SegmentTree::nearestDistance(const Eigen::Vector3d& p, std::size_t& hint) const {
  hint = std::min(hint, segments_.size() - 1);
  // The leaf holding the hint, then, up from it, the other child of each
  // node on the way to the root: every segment is in one of them, and a
  // subtree whose box is no nearer than the best so far is skipped whole.
  int leaf = 0;
  while (nodes_[static_cast<std::size_t>(leaf)].left >= 0) {
    const Node& node = nodes_[static_cast<std::size_t>(leaf)];
    const Node& left = nodes_[static_cast<std::size_t>(node.left)];
    leaf = hint < left.first + left.count ? node.left : node.right;
  }
  Nearest best = searchBelow(p, leaf, 0.0, measure(p, hint));
  for (int node = leaf; node != 0;) {
    int parent = nodes_[static_cast<std::size_t>(node)].parent;
    const Node& above = nodes_[static_cast<std::size_t>(parent)];
    int other = above.left == node ? above.right : above.left;
    best = searchBelow(p, other, nodes_[static_cast<std::size_t>(other)].box.exteriorDistance(p),
                       best);
    node = parent;
  }
  // Every segment's distance is computed the same way whatever the order of
  // the search, so the smallest is nearest(p)'s (a tie may leave another
  // segment in `hint`).
  hint = best.segment;
  return best.distance;
}

SegmentTree::Nearest SegmentTree::search(const Eigen::Vector3d& p, Nearest best) const {
  return searchBelow(p, 0, nodes_.front().box.exteriorDistance(p), best);
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
    if (node.left < 0) {
      segmentsMeasured_ += node.count;
      for (std::size_t i = node.first; i < node.first + node.count; ++i) {
        Nearest candidate = measure(p, i);
        if (candidate.distance < best.distance)
          best = candidate;
      }
      continue;
    }
    Entry left{node.left, nodes_[static_cast<std::size_t>(node.left)].box.exteriorDistance(p)};
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
    const Node& node = nodes_[static_cast<std::size_t>(stack[--top])];
    if (node.first + node.count <= from || node.box.exteriorDistance(p) > radius) {
      continue;
    }
    if (node.left < 0) {
      std::size_t first = std::max(node.first, from);
      segmentsMeasured_ += node.first + node.count - first;
      for (std::size_t i = first; i < node.first + node.count; ++i) {
        const Eigen::Vector3d& a = segments_[i].start;
        const Eigen::Vector3d& b = segments_[i].end;
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
    stack[top++] = node.left;
  }
  return std::nullopt;
}

} // namespace cncc::geom
