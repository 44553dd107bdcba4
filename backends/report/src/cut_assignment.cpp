#include "cncc/backends/verification.h"

#include <algorithm>
#include <limits>
#include <map>

namespace cncc::backends {

namespace {

struct Segment {
  Eigen::Vector3d start, end;
};

double distanceToSegment(const Eigen::Vector3d& point, const Segment& segment) {
  Eigen::Vector3d direction = segment.end - segment.start;
  double lengthSquared = direction.squaredNorm();
  double along = lengthSquared == 0
                     ? 0.0
                     : std::clamp((point - segment.start).dot(direction) / lengthSquared, 0.0, 1.0);
  return (segment.start + along * direction - point).norm();
}

double distanceToPath(const Eigen::Vector3d& point, const std::vector<Segment>& segments) {
  double nearest = std::numeric_limits<double>::infinity();
  for (const Segment& segment : segments) {
    nearest = std::min(nearest, distanceToSegment(point, segment));
  }
  return nearest;
}

// How far a move is from a path: the farthest of its start, middle and end
// from it. A move where two cuts meet (a plunge onto the end of a helix) is
// told apart by where it starts.
double distanceToPath(const Segment& move, const std::vector<Segment>& segments) {
  Eigen::Vector3d middle = (move.start + move.end) / 2.0;
  return std::max({distanceToPath(move.start, segments), distanceToPath(middle, segments),
                   distanceToPath(move.end, segments)});
}

// The reference's feed moves by cut, the cuts in the order they start.
struct ReferenceCuts {
  std::vector<std::size_t> order;
  std::map<std::size_t, std::vector<Segment>> byCut;
  std::vector<Segment> outsideCuts;

  explicit ReferenceCuts(const ExecutedPath& reference) {
    for (std::size_t i = 0; i < reference.moves.size(); ++i) {
      const ExecutedMove& move = reference.moves[i];
      if (move.rapid) {
        continue;
      }
      Segment segment{reference.startOf(i), move.end};
      if (!move.cut) {
        outsideCuts.push_back(segment);
        continue;
      }
      auto [found, isNew] = byCut.try_emplace(*move.cut);
      if (isNew) {
        order.push_back(*move.cut);
      }
      found->second.push_back(segment);
    }
  }
};

// How many cuts ahead of the current one a move may belong to: a program
// that skips a cut is still followed (and the cut reported as missed).
constexpr std::size_t kLookAhead = 4;
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
    std::size_t last = std::min(cuts.order.size(), current + kLookAhead + 1);
    for (std::size_t k = current; k < last; ++k) {
      double distance = distanceToPath(executed, cuts.byCut[cuts.order[k]]);
      if (distance < best - kTie) {
        best = distance;
        chosen = k;
      }
    }
    double outside = distanceToPath(executed, cuts.outsideCuts);
    if (outside < best - kTie) {
      best = outside;
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
