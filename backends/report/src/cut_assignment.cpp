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

  // A place on the path: how far along it, and on which segment.
  struct Place {
    double along = 0;
    std::size_t segment = 0;
  };
  // The first place at or after `from` within `radius` of the point.
  std::optional<Place> firstWithin(const Eigen::Vector3d& point, double radius,
                                   const Place& from) const {
    if (isEmpty_) {
      return std::nullopt;
    }
    std::optional<geom::SegmentTree::Nearest> found =
        tree_.firstWithin(point, radius, from.segment);
    if (!found) {
      return std::nullopt;
    }
    double along = lengthBefore_[found->segment] + found->fraction * segmentLength(found->segment);
    return Place{std::max(along, from.along), found->segment};
  }

  // Where the path ends (the origin for an empty path).
  Eigen::Vector3d end() const { return tree_.segment(tree_.segmentCount() - 1).end; }

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
// A move keeps to the current cut without a look at the next ones when it
// is within the cut's allowance and at most this far from its path.
constexpr double kKeepAtMost = 1.0;
// Distances this close are ties, which the earlier cut wins (unless the
// program has finished it).
constexpr double kTie = 1e-9;
// A move ends where its cut ends when the ends are this close, or within the
// rounding of the program's coordinates.
constexpr double kSameEnd = 1e-6;

// Follows the program through the reference's cuts, in their order. Where
// it has got to in the current cut is remembered: a program runs a cut's
// moves in order, so a move's place on the cut's path is looked for at or
// after the last one's. The nearest point alone is ambiguous where a cut's
// path passes one place twice (the plunge onto a rising helix runs through
// the helix's top end): it kept the next cut's plunge and first moves with
// the finished helix, whose measurement then lacked the whole helix.
class CutFollower {
public:
  CutFollower(const ExecutedPath& reference, const std::vector<double>& allowance,
              double outsideAllowance)
      : cuts_(reference), allowance_(allowance), outsideAllowance_(outsideAllowance) {}

  // Gives the feed move its cut, or none; adds it to `stray` when it is
  // farther than its allowance from the reference path.
  void assign(ExecutedMove& move, const LineSegment& executed, StrayMoves& stray) {
    if (keepsToCurrentCut(executed)) {
      move.cut = cuts_.order[current_];
      return;
    }
    Nearest nearest = nearestCut(executed);
    double best = nearest.distance;
    double limit = outsideAllowance_;
    move.cut.reset();
    if (nearest.cut) {
      follow(*nearest.cut, executed.end);
      move.cut = cuts_.order[current_];
      limit = allowanceOf(*move.cut);
    }
    if (!(best <= limit)) {
      ++stray.count;
      if (!(best <= stray.largestDistance)) {
        stray.largestDistance = best;
        stray.where = executed.end;
      }
    }
  }

private:
  double allowanceOf(std::size_t cut) const {
    return cut < allowance_.size() ? allowance_[cut] : outsideAllowance_;
  }

  // Whether the move keeps to the current cut, before the end of its path:
  // it stays with that cut, even where a later cut runs over the same place
  // (overlapping pockets). Only a move that leaves the current cut, or
  // reaches its end, may start the next.
  bool keepsToCurrentCut(const LineSegment& executed) {
    if (current_ >= cuts_.order.size()) {
      return false;
    }
    const SegmentPath& path = cuts_.cut(current_);
    // Within a millimetre at most: a tolerance as large as the part (1e9)
    // would keep every later cut's moves with this one.
    double allowance = std::min(allowanceOf(cuts_.order[current_]), kKeepAtMost);
    std::optional<SegmentPath::Place> place = path.firstWithin(executed.end, allowance, progress_);
    if (!place || !(place->along < path.length() - kEndOfCut)) {
      return false;
    }
    std::optional<double> distance =
        path.distance(executed, std::numeric_limits<double>::infinity());
    if (!distance || !(*distance <= allowance)) {
      return false;
    }
    progress_ = *place;
    return true;
  }

  // The nearest to the move of the current cut and the next few (an index
  // in their order), or none when a reference move outside every cut is
  // nearer. A tie goes to the earlier cut, but not to a current cut the
  // program has finished: a move that lies on both it and the next cut (a
  // plunge onto the next cut's start) is the next cut's.
  struct Nearest {
    double distance = std::numeric_limits<double>::infinity();
    std::optional<std::size_t> cut;
  };
  Nearest nearestCut(const LineSegment& executed) const {
    double best = std::numeric_limits<double>::infinity();
    std::size_t chosen = kNoCut;
    std::size_t last = std::min(cuts_.order.size(), current_ + kLookAhead + 1);
    // Distances the rounding of the printed coordinates could swap are ties
    // too: a helix that starts a hair (1e-6 rad) past where the next cut
    // plunges is the earlier cut, though the rounded plunge lies on the
    // later one exactly.
    double tie = std::max(kTie, outsideAllowance_ / 2);
    for (std::size_t k = current_; k < last; ++k) {
      bool finishedHolder = chosen == current_ && finishedCurrent_;
      double better = finishedHolder ? best + tie : best - tie;
      std::optional<double> distance = cuts_.cut(k).distance(executed, better);
      if (distance && (finishedHolder ? *distance <= better : *distance < better)) {
        best = *distance;
        chosen = k;
      }
    }
    std::optional<double> outside = cuts_.outsideCuts->distance(executed, best - tie);
    if (outside && *outside < best - tie) {
      return {*outside, std::nullopt};
    }
    if (chosen == kNoCut) {
      return {best, std::nullopt};
    }
    return {best, chosen};
  }

  // Moves on to cut `k` (or stays in the current one) and records how far
  // along it a move ending at `end` has got, and whether it ends where the
  // cut ends.
  void follow(std::size_t k, const Eigen::Vector3d& end) {
    if (k != current_) {
      current_ = k;
      progress_ = {};
      finishedCurrent_ = false;
    }
    const SegmentPath& path = cuts_.cut(current_);
    std::optional<SegmentPath::Place> place =
        path.firstWithin(end, allowanceOf(cuts_.order[current_]), progress_);
    if (!place) {
      return;
    }
    progress_ = *place;
    finishedCurrent_ =
        finishedCurrent_ || (place->along >= path.length() - kEndOfCut &&
                             (path.end() - end).norm() <= std::max(kSameEnd, outsideAllowance_));
  }

  static constexpr std::size_t kNoCut = std::numeric_limits<std::size_t>::max();

  ReferenceCuts cuts_;
  const std::vector<double>& allowance_;
  double outsideAllowance_;
  std::size_t current_ = 0;      // in the order of the cuts
  SegmentPath::Place progress_;  // in the current cut
  bool finishedCurrent_ = false; // a move has ended where the current cut ends
};

} // namespace

StrayMoves assignCuts(ExecutedPath& path, const ExecutedPath& reference,
                      const std::vector<double>& allowance, double outsideAllowance) {
  CutFollower follower(reference, allowance, outsideAllowance);
  StrayMoves stray;
  for (std::size_t i = 0; i < path.moves.size(); ++i) {
    ExecutedMove& move = path.moves[i];
    if (!move.rapid) {
      follower.assign(move, {path.startOf(i), move.end}, stray);
    }
  }
  return stray;
}

} // namespace cncc::backends
