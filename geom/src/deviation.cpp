#include "cncc/geom/deviation.h"

#include "cncc/geom/geometry_error.h"
#include "cncc/geom/segment_tree.h"
#include "curve_sampling.h"
#include "scalar_optimisation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace cncc::geom {

namespace {

constexpr double kMaxTurnBetweenSamples = 0.1;
constexpr int kMaxSamplesPerSegment = 1 << 16;
constexpr int kNewtonIterations = 8;
constexpr double kNewtonStepResolution = 1e-9;
// Samples per block of smallestRadiusBetween's block minima.
constexpr std::size_t kRadiusBlock = 256;
// Times a polyline segment is sampled again for a tighter bend its samples
// found near them, before it takes the curve's tightest.
constexpr int kResamplings = 3;

bool isLocalMaximum(const std::vector<double>& values, std::size_t i) {
  bool aboveLeft = i == 0 || values[i] >= values[i - 1];
  bool aboveRight = i + 1 == values.size() || values[i] >= values[i + 1];
  return aboveLeft && aboveRight;
}

// Sampled local maxima worth refining: refinement can lift a sample by about the
// sampling accuracy, or more where the samples are coarse relative to the peak;
// `margin` is four times the accuracy, six where the samples themselves are off by
// up to the accuracy.
bool worthRefining(double value, double largestSample, double margin) {
  return value >= std::min(0.5 * largestSample, largestSample - margin);
}

// The sampled local maxima worth refining (indices into `values`), largest first.
std::vector<std::size_t> peaksLargestFirst(const std::vector<double>& values, double margin) {
  double largestSample = *std::max_element(values.begin(), values.end());
  std::vector<std::size_t> peaks;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (isLocalMaximum(values, i) && worthRefining(values[i], largestSample, margin))
      peaks.push_back(i);
  }
  std::stable_sort(peaks.begin(), peaks.end(),
                   [&](std::size_t a, std::size_t b) { return values[a] > values[b]; });
  return peaks;
}

// Refines `peaks` in order (largest sampled distance first) until one's sample
// is no more than `accuracy` above the largest distance refined so far: a peak
// the samples put that low could lift the result by about the sampling accuracy
// at most, so on a path that keeps an even distance from its curve (every
// sample a local maximum) a few refinements serve instead of thousands.
template <class Refine>
void refineLargestFirst(const std::vector<std::size_t>& peaks, const std::vector<double>& values,
                        double accuracy, const DeviationWitness& worst, Refine refine) {
  // The largest is always refined: an accuracy larger than the distances
  // (a tolerance as large as the part) would otherwise leave no witness.
  bool first = true;
  for (std::size_t i : peaks) {
    if (!first && values[i] <= worst.distance + accuracy)
      return;
    first = false;
    refine(i);
  }
}

} // namespace

struct CurveProximity::Index {
  SegmentTree tree;
};

CurveProximity::CurveProximity(const Curve& curve, double accuracy) : curve_(curve) {
  if (!(accuracy > 0.0) || !std::isfinite(accuracy))
    throw GeometryError("the deviation accuracy must be positive");
  detail::SamplingRule rule;
  rule.maxTurn = kMaxTurnBetweenSamples;
  rule.maxSagitta = accuracy;
  double largestCurvature = 0.0;
  std::vector<Eigen::Vector3d> points;
  // Visited rather than kept: a fine accuracy makes millions of samples.
  detail::visitSamples(curve, rule, [&](const detail::CurveSample& s) {
    parameters_.push_back(s.t);
    points.push_back(s.d.point);
    double curvature = curvatureOf(s.d);
    largestCurvature = std::max(largestCurvature, curvature);
    radii_.push_back(curvature > 0.0 ? 1.0 / curvature : std::numeric_limits<double>::infinity());
  });
  smallestRadius_ =
      largestCurvature > 0.0 ? 1.0 / largestCurvature : std::numeric_limits<double>::infinity();
  for (std::size_t first = 0; first < radii_.size(); first += kRadiusBlock) {
    auto end = radii_.begin() + std::ptrdiff_t(std::min(first + kRadiusBlock, radii_.size()));
    blockRadii_.push_back(*std::min_element(radii_.begin() + std::ptrdiff_t(first), end));
  }
  // The tree keeps the points (a curve gives at least two samples), no copy.
  index_ = std::make_unique<Index>(Index{SegmentTree::throughVertices(std::move(points))});
}

CurveProximity::~CurveProximity() = default;

double CurveProximity::smallestRadiusBetween(std::size_t first, std::size_t last) const {
  if (first > last) {
    std::swap(first, last);
  }
  // Segment s joins samples s and s + 1; the segments beside: s - 1 and s + 2.
  std::size_t low = first == 0 ? 0 : first - 1;
  std::size_t high = std::min(last + 2, radii_.size() - 1);
  double smallest = std::numeric_limits<double>::infinity();
  while (low <= high) {
    if (low % kRadiusBlock == 0 && low + kRadiusBlock - 1 <= high) {
      smallest = std::min(smallest, blockRadii_[low / kRadiusBlock]);
      low += kRadiusBlock;
    } else {
      smallest = std::min(smallest, radii_[low]);
      ++low;
    }
  }
  return smallest;
}

double CurveProximity::sampledDistance(const Eigen::Vector3d& p) const {
  return index_->tree.nearest(p).distance;
}

double CurveProximity::sampledDistance(const Eigen::Vector3d& p, std::size_t& hint) const {
  return index_->tree.nearestDistance(p, hint);
}

const std::vector<Eigen::Vector3d>& CurveProximity::samplePoints() const {
  return index_->tree.points();
}

CurveProximity::ClosestPoint CurveProximity::closestPoint(const Eigen::Vector3d& p) const {
  return closestPointNear(p, index_->tree.nearest(p));
}

CurveProximity::ClosestPoint CurveProximity::closestPoint(const Eigen::Vector3d& p,
                                                          std::size_t& hint) const {
  SegmentTree::Nearest near = index_->tree.nearest(p, hint);
  hint = near.segment;
  return closestPointNear(p, near);
}

CurveProximity::ClosestPoint
CurveProximity::closestPointNear(const Eigen::Vector3d& p, const SegmentTree::Nearest& near) const {
  // The nearest segment of the sample polyline locates the closest curve point to
  // within the sampling accuracy; the parameter is then refined between the samples
  // around it by Newton's method on C'(t).(C(t) - p) = 0, or by Brent's method on the
  // squared distance if Newton leaves the bracket without converging.
  std::size_t k = near.segment;
  std::size_t last = parameters_.size() - 1;
  double lo = parameters_[k == 0 ? 0 : k - 1];
  double hi = parameters_[std::min(k + 2, last)];
  std::size_t next = std::min(k + 1, last);
  double t = parameters_[k] + near.fraction * (parameters_[next] - parameters_[k]);

  ClosestPoint best{std::numeric_limits<double>::infinity(), t, p};
  auto consider = [&](double s, const Eigen::Vector3d& c) {
    double d = (c - p).norm();
    if (d < best.distance)
      best = {d, s, c};
  };
  consider(lo, curve_.point(lo));
  consider(hi, curve_.point(hi));
  bool converged = false;
  for (int iteration = 0; iteration < kNewtonIterations && !converged; ++iteration) {
    CurveDerivatives d = curve_.derivatives(t);
    Eigen::Vector3d r = d.point - p;
    consider(t, d.point);
    double slope = d.first.dot(r);
    double curvatureTerm = d.first.squaredNorm() + d.second.dot(r);
    if (!(curvatureTerm > 0.0))
      break;
    double nextT = std::clamp(t - slope / curvatureTerm, lo, hi);
    // Newton converges quadratically: after a step this small the next would be
    // below rounding, and the distance is stationary in t anyway.
    converged = std::fabs(nextT - t) <= kNewtonStepResolution * (hi - lo);
    t = nextT;
  }
  consider(t, curve_.point(t));
  if (!converged) {
    auto squared = [&](double s) { return (curve_.point(s) - p).squaredNorm(); };
    detail::ScalarExtremum m = detail::minimiseBrent(squared, lo, hi);
    consider(m.t, curve_.point(m.t));
  }
  return best;
}

double DeviationReport::maxDeviation() const {
  return worst().distance;
}

const DeviationWitness& DeviationReport::worst() const {
  return polylineToCurve.distance >= curveToPolyline.distance ? polylineToCurve : curveToPolyline;
}

MeasurementTooLarge::MeasurementTooLarge(double limit)
    : GeometryError("measuring the deviation needs more than " +
                    std::to_string(static_cast<long long>(limit)) + " segment distances"),
      limit(limit) {}

std::size_t CurveProximity::segmentsMeasured() const {
  return index_->tree.segmentsMeasured();
}

namespace {

// The work of one measurement so far against its limit.
struct WorkBudget {
  const CurveProximity& proximity;
  const SegmentTree& path;
  double limit;

  void check() const {
    if (static_cast<double>(proximity.segmentsMeasured() + path.segmentsMeasured()) > limit)
      throw MeasurementTooLarge(limit);
  }
};

DeviationWitness curveToPolyline(const Curve& curve, const CurveProximity& proximity,
                                 const SegmentTree& path, double accuracy,
                                 const WorkBudget& budget) {
  const std::vector<double>& t = proximity.sampleParameters();
  std::vector<double> distance;
  distance.reserve(t.size());
  std::size_t hint = 0;
  for (const Eigen::Vector3d& c : proximity.samplePoints()) {
    distance.push_back(path.nearestDistance(c, hint));
    budget.check();
  }
  DeviationWitness worst;
  worst.distance = -1.0;
  auto record = [&](double s) {
    Eigen::Vector3d c = curve.point(s);
    SegmentTree::Nearest near = path.nearest(c);
    if (near.distance > worst.distance)
      worst = {near.distance, near.point, c, s, near.segment};
  };
  auto distanceAt = [&](double s) { return path.nearest(curve.point(s)).distance; };
  refineLargestFirst(peaksLargestFirst(distance, 4.0 * accuracy), distance, accuracy, worst,
                     [&](std::size_t i) {
                       budget.check();
                       record(t[i]);
                       double lo = t[i == 0 ? 0 : i - 1], hi = t[std::min(i + 1, t.size() - 1)];
                       if (lo < hi)
                         record(detail::maximiseBrent(distanceAt, lo, hi).t);
                     });
  return worst;
}

DeviationWitness polylineToCurve(const std::vector<Eigen::Vector3d>& polyline,
                                 const CurveProximity& proximity, double accuracy,
                                 const WorkBudget& budget) {
  std::size_t segments = polyline.size() > 1 ? polyline.size() - 1 : 1;
  auto pointOn = [&](std::size_t j, double u) {
    const Eigen::Vector3d& a = polyline[j];
    const Eigen::Vector3d& b = polyline[std::min(j + 1, polyline.size() - 1)];
    return Eigen::Vector3d(a + u * (b - a));
  };
  // Steps along segment j such that a sampled maximum misses the true one by
  // about `accuracy` where the distance bends like the curve (the sagitta of
  // the radius): the tightest radius near the segment, not the curve's
  // tightest anywhere (a cusp would make every segment take the most samples).
  auto intervalsFor = [&](std::size_t j, double radius) {
    double step = std::sqrt(8.0 * accuracy * std::min(radius, 1e12));
    double length = (pointOn(j, 1.0) - pointOn(j, 0.0)).norm();
    return static_cast<std::size_t>(
        std::clamp(std::ceil(length / step), 1.0, double(kMaxSamplesPerSegment)));
  };
  // The distance to the curve's sample polyline, within `accuracy` of the
  // distance to the curve: the maxima worth it are refined on the curve.
  // In order along the whole polyline, a vertex once (a peak of the distance
  // is refined once, not once per segment that ends at it): segment j's
  // samples k = 1 .. intervals[j] (and k = 0 for the first) are
  // along[firsts[j] + k - 1] (along[k] for the first).
  std::vector<std::size_t> intervals(segments);
  std::vector<std::size_t> firsts(segments);
  std::vector<double> along;
  std::vector<double> segmentAlong;
  std::size_t hint = 0; // the sample segment nearest the last point measured
  along.push_back(proximity.sampledDistance(pointOn(0, 0.0), hint));
  for (std::size_t j = 0; j < segments; ++j) {
    // The radius near the samples nearest the segment's ends, then near
    // those nearest its points, until they find no tighter bend (a path that
    // passes another part of the curve), at last the curve's tightest.
    // The segment's end is measured once, its last sample in every round.
    std::size_t startHint = hint;
    std::size_t endHint = hint;
    double endDistance = proximity.sampledDistance(pointOn(j, 1.0), endHint);
    double radius = proximity.smallestRadiusBetween(startHint, endHint);
    for (int round = 1;; ++round) {
      intervals[j] = intervalsFor(j, radius);
      double n = double(intervals[j]);
      std::size_t near = startHint;
      std::size_t low = std::min(startHint, endHint);
      std::size_t high = std::max(startHint, endHint);
      segmentAlong.clear();
      for (std::size_t k = 1; k < intervals[j]; ++k) {
        segmentAlong.push_back(proximity.sampledDistance(pointOn(j, double(k) / n), near));
        low = std::min(low, near);
        high = std::max(high, near);
      }
      segmentAlong.push_back(endDistance);
      budget.check();
      double seen = proximity.smallestRadiusBetween(low, high);
      if (intervalsFor(j, seen) <= intervals[j] || radius <= proximity.smallestSampledRadius()) {
        hint = endHint;
        break;
      }
      radius = round < kResamplings ? seen : proximity.smallestSampledRadius();
    }
    firsts[j] = along.size();
    along.insert(along.end(), segmentAlong.begin(), segmentAlong.end());
  }
  // Sample i of `along`: its segment and its k there.
  auto sampleAt = [&](std::size_t i) {
    if (i == 0) {
      return std::pair<std::size_t, std::size_t>{0, 0};
    }
    std::size_t j =
        std::size_t(std::upper_bound(firsts.begin(), firsts.end(), i) - firsts.begin()) - 1;
    return std::pair<std::size_t, std::size_t>{j, i - firsts[j] + 1};
  };

  DeviationWitness worst;
  worst.distance = -1.0;
  auto record = [&](std::size_t j, double u) {
    Eigen::Vector3d p = pointOn(j, u);
    CurveProximity::ClosestPoint c = proximity.closestPoint(p);
    if (c.distance > worst.distance)
      worst = {c.distance, p, c.point, c.parameter, j};
  };
  // Refines about sample k of segment j, within the samples beside it on that segment.
  auto refine = [&](std::size_t j, std::size_t k) {
    double n = double(intervals[j]);
    auto distanceAt = [&](double u) { return proximity.closestPoint(pointOn(j, u)).distance; };
    double lo = double(k == 0 ? 0 : k - 1) / n;
    double hi = double(std::min(k + 1, intervals[j])) / n;
    if (lo < hi)
      record(j, detail::maximiseBrent(distanceAt, lo, hi).t);
  };
  refineLargestFirst(peaksLargestFirst(along, 6.0 * accuracy), along, accuracy, worst,
                     [&](std::size_t i) {
                       budget.check();
                       auto [j, k] = sampleAt(i);
                       record(j, double(k) / double(intervals[j]));
                       refine(j, k);
                       // A vertex: the next segment's first samples too.
                       if (k == intervals[j] && j + 1 < segments)
                         refine(j + 1, 0);
                     });
  return worst;
}

} // namespace

DeviationReport measureDeviation(const std::vector<Eigen::Vector3d>& polyline, const Curve& curve,
                                 const DeviationOptions& options) {
  if (polyline.empty())
    throw GeometryError("deviation needs a polyline with at least one vertex");
  CurveProximity proximity(curve, options.accuracy);
  SegmentTree path = SegmentTree::throughVertices(polyline);
  DeviationReport report;
  WorkBudget budget{proximity, path, options.maximumWork};
  report.curveToPolyline = curveToPolyline(curve, proximity, path, options.accuracy, budget);
  report.polylineToCurve = polylineToCurve(polyline, proximity, options.accuracy, budget);
  return report;
}

} // namespace cncc::geom
