#include "cncc/geom/spline_knot_placement.h"

#include "cncc/geom/curve_deviation.h"
#include "cncc/geom/deviation.h"
#include "cncc/geom/geometry_error.h"
#include "interpolating_splines_detail.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace cncc::geom {

namespace {

using Vector = Eigen::Vector3d;

// The searches aim slightly inside the tolerance so that the final, finer measurement
// does not find a sampled peak a little higher.
constexpr double kSearchMargin = 0.995;
constexpr int kSamplesPerSegment = 32;
constexpr int kBisectionSteps = 30;
constexpr int kMaxRepairRounds = 40;
constexpr int kCleanupPasses = 2;
// Points before the newest that a search rebuilds from (their tangents are kept).
constexpr std::size_t kCSplineHistory = 2;
constexpr std::size_t kAkimaHistory = 4;
// Predicted points after a candidate: the A spline's segment reaches three points
// ahead, the C spline's window w points.
constexpr int kAkimaLookahead = 3;

class KnotPlacer {
public:
  KnotPlacer(const Curve& curve, const SplineKnotPlacementOptions& options)
      : curve_(curve), options_(options), domain_(curve.domain()),
        proximity_(curve, options.tolerance * 1e-3), limit_(kSearchMargin * options.tolerance) {
    transitions_ = options.transitions;
    if (transitions_.start == SplineEndCondition::Tangent && !transitions_.startDirection)
      transitions_.startDirection = curve.derivative(domain_.t0);
    if (transitions_.end == SplineEndCondition::Tangent && !transitions_.endDirection)
      transitions_.endDirection = curve.derivative(domain_.t1);
  }

  SplineKnots run() {
    placeGreedily();
    repair();
    for (int pass = 0; pass < kCleanupPasses; ++pass) {
      bool removed = cleanup();
      repair();
      if (!removed)
        break;
    }
    return finish();
  }

private:
  bool isCSpline() const { return options_.kind == InterpolatingSplineKind::CSpline; }
  std::size_t lookahead() const {
    int window = options_.cSpline.windowBlocks;
    return std::size_t(isCSpline() ? (window > 0 ? window : 2 * kDefaultCubicSplineWindow)
                                   : kAkimaLookahead);
  }

  std::vector<Vector> pointsAt(const std::vector<double>& parameters) const {
    std::vector<Vector> points;
    for (double u : parameters)
      points.push_back(curve_.point(u));
    return points;
  }

  // Tangents of the spline through `points`, which start at chosen point `first`
  // (keeping that point's tangent for a C spline) and end at the curve's end or not.
  std::vector<Vector> tangentsOf(const std::vector<Vector>& points, std::size_t first,
                                 bool reachesEnd) const {
    SplineTransitions transitions = transitions_;
    if (!reachesEnd)
      transitions.end = isCSpline() ? SplineEndCondition::Natural : SplineEndCondition::Auto;
    if (!isCSpline()) {
      if (first > 0)
        transitions.start = SplineEndCondition::Auto;
      return akimaTangents(points, transitions);
    }
    std::optional<Vector> start;
    if (first > 0)
      start = tangents_[first];
    return detail::cSplineTangentsFrom(points, transitions, options_.cSpline, start);
  }

  double segmentDeviation(const PiecewisePolynomialCurve& spline, std::size_t segment) const {
    const PolynomialSpan& span = spline.spans()[segment];
    return largestDistanceToCurve(spline, span.t0, span.t1, proximity_, kSamplesPerSegment)
        .distance;
  }

  // Whether the point at u after the last chosen one keeps the segments it fixes or
  // changes within the limit (all of them, or only the new one when !strict).
  bool feasible(double u, bool strict, std::vector<Vector>* tangentsOut = nullptr) const {
    std::size_t k = chosen_.size() - 1;
    std::size_t history = isCSpline() ? kCSplineHistory : kAkimaHistory;
    std::size_t first = k > history ? k - history : 0;
    std::vector<double> parameters(chosen_.begin() + std::ptrdiff_t(first), chosen_.end());
    parameters.push_back(u);
    double step = u - chosen_.back();
    bool reachesEnd = u >= domain_.t1;
    for (std::size_t j = 1; j <= lookahead() && !reachesEnd; ++j) {
      double v = u + double(j) * step;
      if (v >= domain_.t1 - 0.25 * step) {
        v = domain_.t1;
        reachesEnd = true;
      }
      parameters.push_back(v);
    }
    std::vector<Vector> points = pointsAt(parameters);
    if (findSplinePointsProblem(points))
      return false;
    std::vector<Vector> tangents = tangentsOf(points, first, reachesEnd);
    if (tangentsOut)
      tangentsOut->assign(tangents.begin(), tangents.end());
    PiecewisePolynomialCurve spline(hermiteSpans(points, chordLengthParameters(points), tangents));
    std::size_t newest = k - first;
    std::size_t from = strict ? (newest > 2 ? newest - 2 : 0) : newest;
    for (std::size_t segment = from; segment <= newest; ++segment)
      if (segmentDeviation(spline, segment) > limit_)
        return false;
    return true;
  }

  // The farthest parameter after the last chosen point that `feasible` accepts.
  double reach(double initialStep, bool strict) const {
    double start = chosen_.back();
    double minimumStep = 1e-9 * domain_.length();
    double lo = start;
    double hi = std::min(domain_.t1, start + initialStep);
    if (feasible(hi, strict)) {
      lo = hi;
      while (lo < domain_.t1) {
        double next = std::min(domain_.t1, start + 2.0 * (lo - start));
        if (!feasible(next, strict)) {
          hi = next;
          break;
        }
        lo = next;
      }
      if (lo >= domain_.t1)
        return domain_.t1;
    } else {
      while (lo == start) {
        double next = start + 0.5 * (hi - start);
        if (next - start < minimumStep)
          return -1.0; // nothing feasible
        if (feasible(next, strict))
          lo = next;
        else
          hi = next;
      }
    }
    for (int i = 0; i < kBisectionSteps && hi - lo > 1e-7 * (lo - start); ++i) {
      double middle = 0.5 * (lo + hi);
      (feasible(middle, strict) ? lo : hi) = middle;
    }
    return lo;
  }

  void placeGreedily() {
    chosen_ = {domain_.t0};
    tangents_.clear();
    double step = domain_.length() / 32.0;
    while (chosen_.back() < domain_.t1) {
      double next = reach(step, true);
      if (next < 0.0)
        next = reach(step, false);
      if (next < 0.0) // the curve is degenerate here; take a small step anyway
        next = std::min(domain_.t1, chosen_.back() + 1e-6 * domain_.length());
      // A sliver left before the end would make two points almost coincide,
      // which the printed coordinates cannot resolve: split the rest evenly.
      double reached = next - chosen_.back();
      if (next < domain_.t1 && domain_.t1 - next < 0.5 * reached)
        next = chosen_.back() + 0.5 * (domain_.t1 - chosen_.back());
      std::vector<Vector> tangents;
      feasible(next, true, &tangents);
      step = next - chosen_.back();
      keepTangents(tangents, next);
      chosen_.push_back(next);
    }
  }

  // Records the tangents a search computed at the chosen points (the sub-problem
  // started `history` points back) as the estimates later searches start from.
  void keepTangents(const std::vector<Vector>& tangents, double next) {
    std::size_t k = chosen_.size() - 1;
    tangents_.resize(k + 2);
    if (tangents.empty()) { // no valid spline there: fall back to the curve's tangent
      tangents_[k + 1] = curve_.derivative(next).normalized();
      return;
    }
    std::size_t history = isCSpline() ? kCSplineHistory : kAkimaHistory;
    std::size_t first = k > history ? k - history : 0;
    for (std::size_t j = first; j <= k + 1; ++j)
      tangents_[j] = tangents[j - first];
  }

  PiecewisePolynomialCurve wholeSpline(const std::vector<double>& parameters) const {
    return modelSpline(options_.kind, pointsAt(parameters), transitions_, options_.cSpline);
  }

  // Inserts the middle parameter of every segment that strays, until none does.
  void repair() {
    for (int round = 0; round < kMaxRepairRounds; ++round) {
      PiecewisePolynomialCurve spline = wholeSpline(chosen_);
      std::vector<double> inserted;
      for (std::size_t segment = 0; segment + 1 < chosen_.size(); ++segment)
        if (segmentDeviation(spline, segment) > limit_)
          inserted.push_back(0.5 * (chosen_[segment] + chosen_[segment + 1]));
      if (inserted.empty())
        return;
      chosen_.insert(chosen_.end(), inserted.begin(), inserted.end());
      std::sort(chosen_.begin(), chosen_.end());
    }
  }

  // The segments (after removing point j) whose shape depends on that point.
  std::pair<std::size_t, std::size_t> influencedSegments(std::size_t j,
                                                         std::size_t segments) const {
    std::size_t before = isCSpline() ? lookahead() + 1 : 4;
    std::size_t after = isCSpline() ? 3 : 2;
    return {j > before ? j - before : 0, std::min(segments - 1, j + after)};
  }

  bool cleanup() {
    bool removedAny = false;
    for (std::size_t j = 1; j + 1 < chosen_.size();) {
      std::vector<double> candidate = chosen_;
      candidate.erase(candidate.begin() + std::ptrdiff_t(j));
      std::vector<Vector> points = pointsAt(candidate);
      bool acceptable = !findSplinePointsProblem(points);
      if (acceptable) {
        PiecewisePolynomialCurve spline =
            modelSpline(options_.kind, points, transitions_, options_.cSpline);
        auto [first, last] = influencedSegments(j, candidate.size() - 1);
        for (std::size_t segment = first; segment <= last && acceptable; ++segment)
          acceptable = segmentDeviation(spline, segment) <= limit_;
      }
      if (acceptable) {
        chosen_ = std::move(candidate);
        removedAny = true;
      } else {
        ++j;
      }
    }
    return removedAny;
  }

  SplineKnots finish() {
    SplineKnots result;
    for (int attempt = 0; attempt < kMaxRepairRounds; ++attempt) {
      PiecewisePolynomialCurve spline = wholeSpline(chosen_);
      CurveDeviationReport report =
          measureCurveDeviation(spline, curve_, {options_.tolerance * 1e-3});
      result.deviation = report.maxDeviation();
      if (result.deviation <= options_.tolerance)
        break;
      // A stray peak the per-segment search missed: split the segment that holds it.
      const CurveDistanceWitness& worst =
          report.approximationToCurve.distance >= report.curveToApproximation.distance
              ? report.approximationToCurve
              : report.curveToApproximation;
      double splineParameter =
          &worst == &report.approximationToCurve ? worst.parameter : worst.targetParameter;
      std::size_t segment = spline.spanIndex(splineParameter);
      chosen_.push_back(0.5 * (chosen_[segment] + chosen_[segment + 1]));
      std::sort(chosen_.begin(), chosen_.end());
    }
    result.parameters = chosen_;
    result.points = pointsAt(chosen_);
    result.transitions = transitions_;
    return result;
  }

  const Curve& curve_;
  const SplineKnotPlacementOptions& options_;
  ParameterRange domain_;
  CurveProximity proximity_;
  double limit_;
  SplineTransitions transitions_;
  std::vector<double> chosen_;
  std::vector<Vector> tangents_; // estimated spline tangents at the chosen points
};

} // namespace

PiecewisePolynomialCurve modelSpline(InterpolatingSplineKind kind,
                                     const std::vector<Eigen::Vector3d>& points,
                                     const SplineTransitions& transitions,
                                     const CSplineOptions& cSplineOptions) {
  return kind == InterpolatingSplineKind::CSpline ? cSpline(points, transitions, cSplineOptions)
                                                  : aSpline(points, transitions);
}

SplineKnots placeSplineKnots(const Curve& curve, const SplineKnotPlacementOptions& options) {
  if (!(options.tolerance > 0.0) || !std::isfinite(options.tolerance))
    throw GeometryError("the spline tolerance must be positive");
  return KnotPlacer(curve, options).run();
}

} // namespace cncc::geom
