#include "cncc/backends/verification.h"
#include "cncc/geom/segment_tree.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <limits>
#include <map>
#include <optional>

namespace cncc::backends {

namespace {

using geom::LineSegment;

// A path's segments with a bounding-box tree over them, so that a point is
// measured against a few segments, not all (arcs flattened into thousands of
// chords made the plain search quadratic).
class SegmentPath {
public:
  explicit SegmentPath(std::vector<LineSegment> segments)
      : isEmpty_(segments.empty()), tree_(std::move(segments)) {
    for (std::size_t i = 0; i < tree_.segmentCount(); ++i) {
      lengthBefore_.push_back(length_);
      length_ += segmentLength(i);
    }
  }

  // The length of the path (its segments one after another).
  double length() const { return length_; }

  // At most the distance to the path; infinity for an empty path.
  double lowerBound(const Eigen::Vector3d& point) const {
    return isEmpty_ ? std::numeric_limits<double>::infinity()
                    : tree_.bounds().exteriorDistance(point);
  }

  // The distance from a point to the path and the path length up to the
  // nearest point.
  struct Nearest {
    double distance = std::numeric_limits<double>::infinity();
    double along = 0;
  };
  Nearest nearest(const Eigen::Vector3d& point) const {
    if (isEmpty_) {
      return {};
    }
    geom::SegmentTree::Nearest found = tree_.nearest(point);
    return {found.distance,
            lengthBefore_[found.segment] + found.fraction * segmentLength(found.segment)};
  }

  // How far a move is from the path: the farthest of its start, middle and
  // end from it. A move where two cuts meet (a plunge onto the end of a
  // helix) is told apart by where it starts. Nullopt when the path's box
  // shows it is not nearer than `better`.
  std::optional<double> distance(const LineSegment& move, double better) const {
    Eigen::Vector3d middle = (move.start + move.end) / 2.0;
    double bound = std::max({lowerBound(move.start), lowerBound(middle), lowerBound(move.end)});
    if (bound >= better) {
      return std::nullopt;
    }
    return std::max(
        {nearest(move.start).distance, nearest(middle).distance, nearest(move.end).distance});
  }

private:
  double segmentLength(std::size_t i) const {
    return (tree_.segment(i).end - tree_.segment(i).start).norm();
  }

  bool isEmpty_;
  geom::SegmentTree tree_;
  std::vector<double> lengthBefore_; // of the path, up to each segment
  double length_ = 0;
};

// The reference's feed moves by cut, the cuts in the order they start.
struct ReferenceCuts {
  std::vector<std::size_t> order;
  std::map<std::size_t, SegmentPath> byCut;
  std::optional<SegmentPath> outsideCuts;

  explicit ReferenceCuts(const ExecutedPath& reference) {
    std::map<std::size_t, std::vector<LineSegment>> segmentsByCut;
    std::vector<LineSegment> outside;
    for (std::size_t i = 0; i < reference.moves.size(); ++i) {
      const ExecutedMove& move = reference.moves[i];
      if (move.rapid) {
        continue;
      }
      LineSegment segment{reference.startOf(i), move.end};
      if (!move.cut) {
        outside.push_back(segment);
        continue;
      }
      auto [found, isNew] = segmentsByCut.try_emplace(*move.cut);
      if (isNew) {
        order.push_back(*move.cut);
      }
      found->second.push_back(segment);
    }
    for (auto& [cut, segments] : segmentsByCut) {
      byCut.emplace(cut, SegmentPath(std::move(segments)));
    }
    outsideCuts.emplace(std::move(outside));
  }

  const SegmentPath& cut(std::size_t k) const { return byCut.at(order[k]); }
};

// How many cuts ahead of the current one a move may belong to: a program
// that skips a cut is still followed (and the cut reported as missed).
constexpr std::size_t kLookAhead = 4;
// A move that ends this close to the end of its cut's path (mm, or inches in
// an inch part) may already belong to the next cut, which starts there.
constexpr double kEndOfCut = 1.0;

// Whether a move keeps to the current cut, before the end of its path: it
// stays with that cut, even where a later cut runs over the same place
// (overlapping pockets). Cuts are executed in order, so only a move that
// leaves the current cut, or reaches its end, may start the next.
bool keepsToCut(const SegmentPath& cut, const LineSegment& move, double allowance) {
  std::optional<double> distance = cut.distance(move, std::numeric_limits<double>::infinity());
  return distance && *distance <= allowance &&
         cut.nearest(move.end).along < cut.length() - kEndOfCut;
}
// Distances this close are ties, which the earlier cut wins.
constexpr double kTie = 1e-9;

} // namespace

StrayMoves assignCuts(ExecutedPath& path, const ExecutedPath& reference,
                      const std::vector<double>& allowance, double outsideAllowance) {
  ReferenceCuts cuts(reference);
  StrayMoves stray;
  std::size_t current = 0;
  for (std::size_t i = 0; i < path.moves.size(); ++i) {
    ExecutedMove& move = path.moves[i];
    if (move.rapid) {
      continue;
    }
    LineSegment executed{path.startOf(i), move.end};
    double best = std::numeric_limits<double>::infinity();
    std::optional<std::size_t> chosen;
    if (current < cuts.order.size()) {
      std::size_t cut = cuts.order[current];
      if (keepsToCut(cuts.cut(current), executed,
                     cut < allowance.size() ? allowance[cut] : outsideAllowance)) {
        move.cut = cut;
        continue;
      }
    }
    std::size_t last = std::min(cuts.order.size(), current + kLookAhead + 1);
    for (std::size_t k = current; k < last; ++k) {
      std::optional<double> distance = cuts.cut(k).distance(executed, best - kTie);
      if (distance && *distance < best - kTie) {
        best = *distance;
        chosen = k;
      }
    }
    std::optional<double> outside = cuts.outsideCuts->distance(executed, best - kTie);
    if (outside && *outside < best - kTie) {
      best = *outside;
      chosen.reset();
    }
    double limit = outsideAllowance;
    move.cut.reset();
    if (chosen) {
      current = *chosen;
      move.cut = cuts.order[current];
      limit = *move.cut < allowance.size() ? allowance[*move.cut] : outsideAllowance;
    }
    double distance = best;
    if (!(distance <= limit)) {
      ++stray.count;
      if (!(distance <= stray.largestDistance)) {
        stray.largestDistance = distance;
        stray.where = move.end;
      }
    }
  }
  return stray;
}

} // namespace cncc::backends
