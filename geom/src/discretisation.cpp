#include "cncc/geom/discretisation.h"

#include "cncc/geom/arc_length.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/geom/offset_curve.h"
#include "scalar_optimisation.h"
#include "vector_math.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

namespace cncc::geom {

namespace {

constexpr int kInitialDeviationSamples = 16;
constexpr int kMaxDeviationSamples = 4096;
// Neighbouring samples whose chords turn by more than this are too far apart to bracket
// the deviation's peaks reliably; the arc is then sampled four times as densely.
constexpr double kMaxTurnBetweenDeviationSamples = 0.2;
// Bisection on the chord's end stops at this fraction of the domain's length.
constexpr double kReachResolution = 1e-13;

// Distances of an arc's samples from its chord, and the sampled points; kept
// between the checks of a walk (their memory reused, not allocated again).
struct ArcSamples {
  std::vector<double> t;
  std::vector<double> distance;
  std::vector<Eigen::Vector3d> points;
};

double largestTurn(const std::vector<Eigen::Vector3d>& points) {
  double turn = 0.0;
  for (std::size_t i = 1; i + 1 < points.size(); ++i)
    turn =
        std::max(turn, detail::angleBetween(points[i] - points[i - 1], points[i + 1] - points[i]));
  return turn;
}

// Distances of the arc's samples from the chord [a, b], into `samples`. Stops early,
// with the samples so far, once one is beyond `limit`: a chord that fails needs no
// finer look.
void sampleArcDistances(const Curve& curve, double ta, double tb, const Eigen::Vector3d& a,
                        const Eigen::Vector3d& b, double limit, ArcSamples& samples) {
  for (int n = kInitialDeviationSamples;; n *= 4) {
    samples.t.clear();
    samples.distance.clear();
    samples.points.clear();
    for (int i = 0; i <= n; ++i) {
      double t = i == n ? tb : ta + (tb - ta) * i / n;
      Eigen::Vector3d p = i == 0 ? a : (i == n ? b : curve.point(t));
      samples.t.push_back(t);
      samples.distance.push_back(detail::distanceToSegment(p, a, b));
      samples.points.push_back(p);
      if (samples.distance.back() > limit)
        return;
    }
    if (n >= kMaxDeviationSamples || largestTurn(samples.points) <= kMaxTurnBetweenDeviationSamples)
      return;
  }
}

// chordDeviation, except that it may return early with any sampled distance beyond
// `limit` (a lower bound of the deviation, enough to reject the chord).
// `breaks`: the curve's breakpoints, sorted; a corner among them inside the
// chord is measured where it is (its peak can lie between two samples that
// turn too little to be sampled more finely, near the chord's end).
double chordDeviationBeyond(const Curve& curve, double ta, double tb, double limit,
                            ArcSamples& samples, std::span<const double> breaks) {
  if (ta == tb)
    return 0.0;
  if (ta > tb)
    std::swap(ta, tb);
  Eigen::Vector3d a = curve.point(ta), b = curve.point(tb);
  sampleArcDistances(curve, ta, tb, a, b, limit, samples);
  double largest = *std::max_element(samples.distance.begin(), samples.distance.end());
  for (auto it = std::upper_bound(breaks.begin(), breaks.end(), ta);
       it != breaks.end() && *it < tb && largest <= limit; ++it)
    largest = std::max(largest, detail::distanceToSegment(curve.point(*it), a, b));
  if (largest > limit)
    return largest;
  auto distance = [&](double t) { return detail::distanceToSegment(curve.point(t), a, b); };
  std::size_t n = samples.t.size();
  for (std::size_t i = 1; i + 1 < n; ++i) {
    bool peak = samples.distance[i] >= samples.distance[i - 1] &&
                samples.distance[i] >= samples.distance[i + 1];
    if (!peak)
      continue;
    // Every sampled peak is refined: the highest sample need not be the highest peak.
    auto refined = detail::maximiseBrent(distance, samples.t[i - 1], samples.t[i + 1]);
    largest = std::max(largest, refined.value);
  }
  return largest;
}

// Deviations are computed from coordinates that carry rounding errors of a few ulp of
// their magnitude (3e-14 mm at 150 mm); a chord is accepted only if it meets the
// tolerance by this many ulp more, so that no independent measurement of the result,
// with its own rounding, finds the tolerance exceeded.
constexpr double kRoundingMarginUlps = 64.0;

// Whether the chord from `from` to `to` meets the tolerance.
class ChordFeasibility {
public:
  ChordFeasibility(const Curve& curve, double tolerance)
      : curve_(curve), tolerance_(tolerance), breaks_(curve.breakpoints()) {}
  bool operator()(double from, double to) const {
    double magnitude = std::max(curve_.point(from).lpNorm<Eigen::Infinity>(),
                                curve_.point(to).lpNorm<Eigen::Infinity>());
    double margin = kRoundingMarginUlps * std::numeric_limits<double>::epsilon() * magnitude;
    double allowed = tolerance_ - margin;
    return chordDeviationBeyond(curve_, from, to, allowed, samples_, breaks_) <= allowed;
  }

private:
  const Curve& curve_;
  double tolerance_;
  std::vector<double> breaks_;
  mutable ArcSamples samples_;
};

// A first guess of how far a chord reaches: the sagitta of a circle of the local
// curvature, c^2 k / 8 = tolerance, converted to a parameter step.
double reachGuess(const Curve& curve, double t, double tolerance, double remaining) {
  CurveDerivatives d = curve.derivatives(t);
  double speed = d.first.norm();
  double k = curvatureOf(d);
  if (speed == 0.0 || k == 0.0)
    return remaining;
  return std::min(remaining, std::sqrt(8.0 * tolerance / k) / speed);
}

// The farthest parameter in (from, end] whose chord from `from` meets the tolerance:
// grow the step by doubling until a chord fails, then bisect between the last chord
// that passed and the first that failed.
double farthestReach(const Curve& curve, const ChordFeasibility& feasible, double from, double end,
                     double tolerance, double resolution) {
  if (feasible(from, end))
    return end;
  double step = reachGuess(curve, from, tolerance, end - from);
  double good = from, bad = end;
  if (feasible(from, from + step)) {
    good = from + step;
    for (step *= 2.0; from + step < end; step *= 2.0) {
      if (!feasible(from, from + step)) {
        bad = from + step;
        break;
      }
      good = from + step;
    }
  } else {
    bad = from + step;
    for (step *= 0.5;; step *= 0.5) {
      if (step < resolution)
        throw GeometryError("no chord from t = " + std::to_string(from) +
                            " meets the tolerance (is the curve broken there?)");
      if (feasible(from, from + step)) {
        good = from + step;
        break;
      }
      bad = from + step;
    }
  }
  while (bad - good > resolution) {
    double middle = 0.5 * (good + bad);
    (feasible(from, middle) ? good : bad) = middle;
  }
  return good;
}

CurveSamples samplesAt(const Curve& curve, std::vector<double> parameters) {
  CurveSamples samples;
  samples.points.reserve(parameters.size());
  for (double t : parameters)
    samples.points.push_back(curve.point(t));
  samples.parameters = std::move(parameters);
  return samples;
}

// The chords per unit of the parameter at a sample: sqrt(k / (8 tolerance))
// times the speed, of the curve, or of its offset by `offset` in XY, whose
// curvature is k / (1 - offset k) and speed |C'| |1 - offset k| (k signed).
double chordDensity(const CurveDerivatives& d, double tolerance, double offset) {
  if (offset == 0.0)
    return std::sqrt(curvatureOf(d) / (8.0 * tolerance)) * d.first.norm();
  double k = signedCurvatureOf(d);
  return std::sqrt(std::fabs(k * (1.0 - offset * k)) / (8.0 * tolerance)) * d.first.norm();
}

} // namespace

double chordDeviation(const Curve& curve, double ta, double tb) {
  std::vector<double> breaks = curve.breakpoints();
  return chordDeviation(curve, ta, tb, breaks);
}

double chordDeviation(const Curve& curve, double ta, double tb, std::span<const double> breaks) {
  ArcSamples samples;
  return chordDeviationBeyond(curve, ta, tb, std::numeric_limits<double>::infinity(), samples,
                              breaks);
}

ChordLimitExceeded::ChordLimitExceeded(std::size_t limit)
    : GeometryError("the curve needs more than " + std::to_string(limit) +
                    " chords within its tolerance"),
      limit(limit) {}

CurveSamples discretiseByChordTolerance(const Curve& curve, double tolerance,
                                        std::size_t maximumChords) {
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    throw GeometryError("the chord tolerance must be positive");
  ParameterRange range = curve.domain();
  // Never finer than a few ulp of the parameter, or bisection could stall.
  double ulps = 8.0 * std::numeric_limits<double>::epsilon() *
                std::max(std::fabs(range.t0), std::fabs(range.t1));
  double resolution = std::max(kReachResolution * std::max(1.0, range.length()), ulps);
  ChordFeasibility feasible(curve, tolerance);
  std::vector<double> parameters{range.t0};
  while (parameters.back() < range.t1) {
    if (parameters.size() > maximumChords)
      throw ChordLimitExceeded(maximumChords);
    parameters.push_back(
        farthestReach(curve, feasible, parameters.back(), range.t1, tolerance, resolution));
  }
  return samplesAt(curve, std::move(parameters));
}

DiscretisationEstimate estimateDiscretisation(const Curve& curve, double tolerance, double offset) {
  std::vector<double> breaks = curve.breakpoints();
  std::size_t pieces = breaks.size() < 2 ? 1 : breaks.size() - 1;
  if (breaks.size() < 2)
    breaks = {curve.domain().t0, curve.domain().t1};
  // About a thousand samples in all, at least eight a piece.
  int perPiece = static_cast<int>(std::clamp<std::size_t>(1024 / pieces, 8, 256));
  bool counting = tolerance > 0.0 && std::isfinite(tolerance);
  DiscretisationEstimate estimate;
  for (std::size_t p = 0; p + 1 < breaks.size(); ++p) {
    double step = (breaks[p + 1] - breaks[p]) / perPiece;
    estimate.chords += counting ? 1.0 : 0.0;
    for (int i = 0; i <= perPiece; ++i) {
      CurveDerivatives d = curve.derivatives(i == perPiece ? breaks[p + 1] : breaks[p] + i * step);
      estimate.largestCoordinate =
          std::max(estimate.largestCoordinate, d.point.lpNorm<Eigen::Infinity>());
      if (!d.point.allFinite())
        estimate.largestCoordinate = std::numeric_limits<double>::infinity();
      // The midpoint rule: each sample stands for one step of the parameter.
      if (counting && i < perPiece)
        estimate.chords += chordDensity(d, tolerance, offset) * step;
    }
  }
  return estimate;
}

CurveSamples sampleUniformParameter(const Curve& curve, std::size_t count) {
  if (count < 2)
    throw GeometryError("uniform sampling needs at least 2 points");
  ParameterRange range = curve.domain();
  std::vector<double> parameters;
  for (std::size_t i = 0; i < count; ++i)
    parameters.push_back(i + 1 == count ? range.t1
                                        : range.t0 + range.length() * static_cast<double>(i) /
                                                         static_cast<double>(count - 1));
  return samplesAt(curve, std::move(parameters));
}

CurveSamples sampleEqualArcLength(const Curve& curve, double spacing) {
  if (!(spacing > 0.0) || !std::isfinite(spacing))
    throw GeometryError("the arc length spacing must be positive");
  ArcLengthTable table(curve);
  double total = table.totalLength();
  std::vector<double> parameters{curve.domain().t0};
  // k * spacing rather than a running sum, so rounding does not accumulate.
  for (double k = 1.0; k * spacing < total - 1e-9 * spacing; k += 1.0)
    parameters.push_back(table.parameterAt(k * spacing));
  parameters.push_back(curve.domain().t1);
  return samplesAt(curve, std::move(parameters));
}

} // namespace cncc::geom
