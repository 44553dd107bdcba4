#include "cncc/backends/verification.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <limits>
#include <map>

namespace cncc::backends {

namespace {

struct Segment {
  Eigen::Vector3d start, end;
};

// The distance from a point to a segment, and where along the segment (0 to
// 1) the nearest point lies.
struct SegmentDistance {
  double distance;
  double fraction;
};

SegmentDistance distanceToSegment(const Eigen::Vector3d& point, const Segment& segment) {
  Eigen::Vector3d direction = segment.end - segment.start;
  double lengthSquared = direction.squaredNorm();
  double along = lengthSquared == 0
                     ? 0.0
                     : std::clamp((point - segment.start).dot(direction) / lengthSquared, 0.0, 1.0);
  return {(segment.start + along * direction - point).norm(), along};
}

// A path's segments in runs of a few, each run with its bounding box, so
// that a point is measured only against the runs that could hold a nearer
// segment than the nearest found so far (arcs flattened into thousands of
// chords make the plain search quadratic).
class SegmentPath {
public:
  void add(const Segment& segment) {
    if (runs_.empty() || runs_.back().segments.size() == segmentsPerRun) {
      runs_.emplace_back();
    }
    Run& run = runs_.back();
    run.segments.push_back(segment);
    run.lengthBefore.push_back(length_);
    length_ += (segment.end - segment.start).norm();
    run.box.extend(segment.start);
    run.box.extend(segment.end);
    box_.extend(segment.start);
    box_.extend(segment.end);
  }

  // The length of the path (its segments one after another).
  double length() const { return length_; }

  // At most the distance to the path; infinity for an empty path.
  double lowerBound(const Eigen::Vector3d& point) const {
    return runs_.empty() ? std::numeric_limits<double>::infinity() : box_.exteriorDistance(point);
  }

  // The distance from a point to the path and the path length up to the
  // nearest point. Consecutive queries walk along the path, so the run
  // nearest to the last point is measured first: its distance prunes most
  // other runs by box.
  struct Nearest {
    double distance = std::numeric_limits<double>::infinity();
    double along = 0;
  };
  Nearest nearest(const Eigen::Vector3d& point) const {
    if (runs_.empty()) {
      return {};
    }
    Nearest best = nearestInRun(runs_[nearestRun_], point);
    for (std::size_t i = 0; i < runs_.size(); ++i) {
      if (i == nearestRun_ || runs_[i].box.exteriorDistance(point) >= best.distance) {
        continue;
      }
      Nearest found = nearestInRun(runs_[i], point);
      if (found.distance < best.distance) {
        best = found;
        nearestRun_ = i;
      }
    }
    return best;
  }

  // How far a move is from the path: the farthest of its start, middle and
  // end from it. A move where two cuts meet (a plunge onto the end of a
  // helix) is told apart by where it starts. Nullopt when the path's box
  // shows it is not nearer than `better`.
  std::optional<double> distance(const Segment& move, double better) const {
    Eigen::Vector3d middle = (move.start + move.end) / 2.0;
    double bound = std::max({lowerBound(move.start), lowerBound(middle), lowerBound(move.end)});
    if (bound >= better) {
      return std::nullopt;
    }
    return std::max(
        {nearest(move.start).distance, nearest(middle).distance, nearest(move.end).distance});
  }

private:
  static constexpr std::size_t segmentsPerRun = 32;
  struct Run {
    std::vector<Segment> segments;
    std::vector<double> lengthBefore; // of the path, up to each segment
    Eigen::AlignedBox3d box;
  };

  static Nearest nearestInRun(const Run& run, const Eigen::Vector3d& point) {
    Nearest best;
    for (std::size_t k = 0; k < run.segments.size(); ++k) {
      SegmentDistance found = distanceToSegment(point, run.segments[k]);
      if (found.distance < best.distance) {
        const Segment& segment = run.segments[k];
        best = {found.distance,
                run.lengthBefore[k] + found.fraction * (segment.end - segment.start).norm()};
      }
    }
    return best;
  }

  std::vector<Run> runs_;
  Eigen::AlignedBox3d box_;
  double length_ = 0;
  mutable std::size_t nearestRun_ = 0;
};

// The reference's feed moves by cut, the cuts in the order they start.
struct ReferenceCuts {
  std::vector<std::size_t> order;
  std::map<std::size_t, SegmentPath> byCut;
  SegmentPath outsideCuts;

  explicit ReferenceCuts(const ExecutedPath& reference) {
    for (std::size_t i = 0; i < reference.moves.size(); ++i) {
      const ExecutedMove& move = reference.moves[i];
      if (move.rapid) {
        continue;
      }
      Segment segment{reference.startOf(i), move.end};
      if (!move.cut) {
        outsideCuts.add(segment);
        continue;
      }
      auto [found, isNew] = byCut.try_emplace(*move.cut);
      if (isNew) {
        order.push_back(*move.cut);
      }
      found->second.add(segment);
    }
  }
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
bool keepsToCut(const SegmentPath& cut, const Segment& move, double allowance) {
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
    Segment executed{path.startOf(i), move.end};
    double best = std::numeric_limits<double>::infinity();
    std::optional<std::size_t> chosen;
    if (current < cuts.order.size()) {
      std::size_t cut = cuts.order[current];
      if (keepsToCut(cuts.byCut[cut], executed,
                     cut < allowance.size() ? allowance[cut] : outsideAllowance)) {
        move.cut = cut;
        continue;
      }
    }
    std::size_t last = std::min(cuts.order.size(), current + kLookAhead + 1);
    for (std::size_t k = current; k < last; ++k) {
      std::optional<double> distance = cuts.byCut[cuts.order[k]].distance(executed, best - kTie);
      if (distance && *distance < best - kTie) {
        best = *distance;
        chosen = k;
      }
    }
    std::optional<double> outside = cuts.outsideCuts.distance(executed, best - kTie);
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
