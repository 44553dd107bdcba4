#include "cncc/geom/offset_clearance.h"

#include "cncc/geom/deviation.h"
#include "cncc/geom/evaluation_budget.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/geom/offset_curve.h"

#include "curve_sampling.h"
#include "scalar_optimisation.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace cncc::geom {

namespace {

constexpr int kMinimumSamplesPerPiece = 64;
constexpr int kTotalSamples = 4096;
constexpr int kMaximumCrossingChords = 4096;
// The chord pairs the crossing finder tests at most (a curve that runs over
// itself many times puts many chords in one cell).
constexpr std::size_t kMaximumCrossingTests = 20'000'000;
// The crossing finder's chords turn at most this much (rad), and the
// points it asks of the offset to place them are bounded.
constexpr double kCrossingSampleTurn = 0.1;
constexpr std::size_t kMaximumCrossingEvaluations = 2'000'000;
// The tool centres the clearance check measures at most.
constexpr int kMaximumClearanceSamples = 20'000;

// Parameters sampling each smooth piece of the curve, ends included.
std::vector<double> sampleParameters(const Curve& curve, int perPiece, int total) {
  std::vector<double> breaks = curve.breakpoints();
  ParameterRange domain = curve.domain();
  std::vector<double> parameters;
  for (std::size_t p = 0; p + 1 < breaks.size(); ++p) {
    double length = breaks[p + 1] - breaks[p];
    int count = std::max(perPiece, static_cast<int>(total * length / domain.length()));
    for (int i = 0; i < count; ++i) {
      parameters.push_back(breaks[p] + length * i / count);
    }
  }
  parameters.push_back(domain.t1);
  return parameters;
}

// The tightest bend where `bend(t)` (a curvature, positive on the side
// looked at) is largest: sampled, each local largest refined.
template <class Bend>
CurvatureExtreme tightest(const Curve& curve, const std::vector<double>& parameters,
                          const Bend& bend) {
  std::vector<double> values;
  values.reserve(parameters.size());
  for (double t : parameters) {
    values.push_back(bend(t));
  }
  CurvatureExtreme found;
  double largest = 0.0;
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    bool peak = values[i] > 0 && (i == 0 || values[i] >= values[i - 1]) &&
                (i + 1 == values.size() || values[i] >= values[i + 1]);
    if (!peak) {
      continue;
    }
    double t = parameters[i];
    double value = values[i];
    double low = parameters[i == 0 ? 0 : i - 1];
    double high = parameters[std::min(i + 1, parameters.size() - 1)];
    if (high > low) {
      detail::ScalarExtremum refined =
          detail::minimiseBrent([&](double s) { return -bend(s); }, low, high);
      if (-refined.value > value) {
        t = refined.t;
        value = -refined.value;
      }
    }
    if (value > largest) {
      largest = value;
      found = {t, curve.point(t), 1.0 / value};
    }
  }
  return found;
}

bool chordsCross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                 const Eigen::Vector2d& d, Eigen::Vector2d& at) {
  Eigen::Vector2d r = b - a;
  Eigen::Vector2d s = d - c;
  double denominator = r.x() * s.y() - r.y() * s.x();
  if (denominator == 0) {
    return false;
  }
  Eigen::Vector2d q = c - a;
  double u = (q.x() * s.y() - q.y() * s.x()) / denominator;
  double v = (q.x() * r.y() - q.y() * r.x()) / denominator;
  if (u <= 0 || u >= 1 || v <= 0 || v >= 1) {
    return false;
  }
  at = a + u * r;
  return true;
}

// Chords of a polyline in a uniform grid of about as many cells as chords,
// each chord in the cells its segment passes through: two chords can cross
// only where they share a cell, so the pairs tested grow with the chords
// met in one place, not with the square of all of them.
class ChordGrid {
public:
  explicit ChordGrid(const std::vector<Eigen::Vector2d>& points) : points_(points) {
    Eigen::AlignedBox2d box;
    for (const Eigen::Vector2d& point : points) {
      box.extend(point);
    }
    std::size_t chords = points.size() - 1;
    side_ = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(std::sqrt(chords))));
    origin_ = box.min();
    double extent = std::max(box.sizes().maxCoeff(), 1e-12);
    cell_ = extent / static_cast<double>(side_) * (1 + 1e-9);
    cells_.resize(side_ * side_);
    for (std::size_t i = 0; i < chords; ++i) {
      insert(i);
    }
  }

  // Calls `test(i, j)`, i < j, for each two chords sharing a cell (past
  // kMaximumCrossingTests pairs throws EvaluationBudgetExceeded).
  template <class Test> void forEachNearPair(const Test& test) const {
    std::size_t tested = 0;
    for (const std::vector<std::size_t>& cell : cells_) {
      for (std::size_t a = 0; a < cell.size(); ++a) {
        for (std::size_t b = a + 1; b < cell.size(); ++b) {
          if (++tested > kMaximumCrossingTests) {
            throw EvaluationBudgetExceeded(kMaximumCrossingTests);
          }
          test(std::min(cell[a], cell[b]), std::max(cell[a], cell[b]));
        }
      }
    }
  }

private:
  std::size_t index(double coordinate, double from) const {
    double at = std::floor((coordinate - from) / cell_);
    return static_cast<std::size_t>(std::clamp(at, 0.0, static_cast<double>(side_ - 1)));
  }

  // Into each column the chord crosses, the rows its part there spans.
  void insert(std::size_t chord) {
    Eigen::Vector2d a = points_[chord];
    Eigen::Vector2d b = points_[chord + 1];
    if (a.x() > b.x()) {
      std::swap(a, b);
    }
    std::size_t first = index(a.x(), origin_.x());
    std::size_t last = index(b.x(), origin_.x());
    for (std::size_t column = first; column <= last; ++column) {
      double left = std::max(a.x(), origin_.x() + cell_ * static_cast<double>(column));
      double right = std::min(b.x(), origin_.x() + cell_ * static_cast<double>(column + 1));
      auto yAt = [&](double x) {
        double span = b.x() - a.x();
        return span > 0 ? a.y() + (b.y() - a.y()) * std::clamp((x - a.x()) / span, 0.0, 1.0)
                        : a.y();
      };
      double low = std::min({yAt(left), yAt(right), span0(a, b)});
      double high = std::max({yAt(left), yAt(right), span1(a, b)});
      for (std::size_t row = index(low, origin_.y()); row <= index(high, origin_.y()); ++row) {
        cells_[row * side_ + column].push_back(chord);
      }
    }
  }

  // A vertical chord spans its whole height in its one column.
  static double span0(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() == b.x() ? std::min(a.y(), b.y()) : std::numeric_limits<double>::infinity();
  }
  static double span1(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() == b.x() ? std::max(a.y(), b.y()) : -std::numeric_limits<double>::infinity();
  }

  const std::vector<Eigen::Vector2d>& points_;
  std::size_t side_ = 1;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double cell_ = 1;
  std::vector<std::vector<std::size_t>> cells_;
};

// Parameters of the offset for the clearance check: every breakpoint and
// end, and between them steps of about half the radius along the curve
// (kMaximumClearanceSamples in all, spread by length).
std::vector<double> clearanceSamples(const Curve& offset, double radius) {
  std::vector<double> breaks = offset.breakpoints();
  std::vector<double> lengths;
  double total = 0;
  for (std::size_t p = 0; p + 1 < breaks.size(); ++p) {
    double length = 0;
    Eigen::Vector3d previous = offset.point(breaks[p]);
    for (int k = 1; k <= 16; ++k) {
      Eigen::Vector3d next = offset.point(breaks[p] + (breaks[p + 1] - breaks[p]) * k / 16);
      length += (next - previous).norm();
      previous = next;
    }
    lengths.push_back(length);
    total += length;
  }
  double spacing = std::max(radius / 2, total / kMaximumClearanceSamples);
  std::vector<double> parameters;
  for (std::size_t p = 0; p + 1 < breaks.size(); ++p) {
    int count = std::max(1, static_cast<int>(std::ceil(lengths[p] / spacing)));
    count = std::min(count, kMaximumClearanceSamples);
    for (int k = 0; k < count; ++k) {
      parameters.push_back(breaks[p] + (breaks[p + 1] - breaks[p]) * k / count);
    }
  }
  parameters.push_back(breaks.back());
  return parameters;
}

} // namespace

OffsetClearance offsetClearance(const Curve& curve, double distance) {
  if (!(distance != 0) || !std::isfinite(distance)) {
    throw GeometryError("an offset needs a finite non-zero distance");
  }
  double side = distance > 0 ? 1.0 : -1.0;
  std::vector<double> parameters = sampleParameters(curve, kMinimumSamplesPerPiece, kTotalSamples);
  auto curvature = [&](double t) { return signedCurvatureOf(curve.derivatives(t)); };
  OffsetClearance clearance;
  clearance.concave = tightest(curve, parameters, [&](double t) { return side * curvature(t); });
  clearance.convex = tightest(curve, parameters, [&](double t) { return -side * curvature(t); });
  return clearance;
}

std::optional<Eigen::Vector3d> offsetSelfCrossing(const Curve& offset, int samplesPerPiece) {
  std::size_t pieces = std::max<std::size_t>(offset.breakpoints().size() - 1, 1);
  std::vector<double> parameters;
  if (pieces * 4 <= kMaximumCrossingChords) {
    int perPiece =
        std::max(4, std::min(samplesPerPiece, kMaximumCrossingChords / static_cast<int>(pieces)));
    parameters = sampleParameters(offset, perPiece, 0);
  } else {
    // Too many pieces for four chords each: equal steps over the whole curve.
    ParameterRange domain = offset.domain();
    for (int i = 0; i <= kMaximumCrossingChords; ++i) {
      parameters.push_back(domain.t0 + domain.length() * i / kMaximumCrossingChords);
    }
  }
  // And wherever the offset turns more than kCrossingSampleTurn between
  // them: chords of a many-turn spiral a few to the turn would cross the
  // next turn's where the offsets do not.
  BudgetedCurve counted(offset, kMaximumCrossingEvaluations);
  detail::SamplingRule rule;
  rule.maxTurn = kCrossingSampleTurn;
  for (const detail::CurveSample& sample : detail::sampleCurve(counted, rule)) {
    parameters.push_back(sample.t);
  }
  std::sort(parameters.begin(), parameters.end());
  double last = parameters.back();
  double apart = 1e-9 * offset.domain().length();
  parameters.erase(std::unique(parameters.begin(), parameters.end(),
                               [&](double a, double b) { return b - a <= apart; }),
                   parameters.end());
  parameters.back() = last; // the end itself, where a closed curve meets its start
  std::vector<Eigen::Vector2d> points;
  for (double t : parameters) {
    points.push_back(offset.point(t).head<2>());
  }
  bool closed = (points.front() - points.back()).norm() < 1e-9;
  ChordGrid grid(points);
  // The first crossing along the curve: of the pair whose earlier chord,
  // then later chord, comes first.
  std::optional<std::pair<std::size_t, std::size_t>> first;
  std::optional<Eigen::Vector3d> found;
  grid.forEachNearPair([&](std::size_t i, std::size_t j) {
    if (j < i + 2 || (closed && i == 0 && j + 2 == points.size())) {
      return; // neighbours, and the closing chord, meet at an end
    }
    Eigen::Vector2d at;
    if ((!first || std::pair{i, j} < *first) &&
        chordsCross(points[i], points[i + 1], points[j], points[j + 1], at)) {
      first = std::pair{i, j};
      found = Eigen::Vector3d(at.x(), at.y(), 0.0);
    }
  });
  return found;
}

std::optional<ClearanceViolation> offsetClearanceViolation(const Curve& offset,
                                                           const CurveProximity& part,
                                                           double radius, double slack) {
  if (!(radius > 0) || !(slack > 0) || !std::isfinite(radius) || !std::isfinite(slack)) {
    throw GeometryError("a clearance check needs a positive radius and slack");
  }
  // The nearest sample chord is at most a quarter of the slack nearer than
  // the curve, so a centre on the offset (at the radius from its own foot)
  // is never taken for one too near.
  double accuracy = slack / 4;
  std::optional<ClearanceViolation> worst;
  for (double t : clearanceSamples(offset, radius)) {
    Eigen::Vector3d centre = offset.point(t);
    if (!(part.sampledDistance(centre) < radius - slack + accuracy)) {
      continue;
    }
    CurveProximity::ClosestPoint nearest = part.closestPoint(centre);
    if (nearest.distance < radius - slack && (!worst || nearest.distance < worst->distance)) {
      worst = ClearanceViolation{t, centre, nearest.point, nearest.distance};
    }
  }
  return worst;
}

std::optional<ClearanceViolation> offsetClearanceViolation(const Curve& offset, const Curve& base,
                                                           double radius, double slack) {
  CurveProximity part(base, slack / 4);
  return offsetClearanceViolation(offset, part, radius, slack);
}

} // namespace cncc::geom
