#include "cncc/geom/curve_deviation.h"

#include "cncc/geom/geometry_error.h"
#include "curve_sampling.h"
#include "scalar_optimisation.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace cncc::geom {

namespace {

constexpr double kMaxTurnBetweenSamples = 0.1;
constexpr int kMinSamplesPerPiece = 32;

bool isLocalMaximum(const std::vector<double>& values, std::size_t i) {
  bool aboveLeft = i == 0 || values[i] >= values[i - 1];
  bool aboveRight = i + 1 == values.size() || values[i] >= values[i + 1];
  return aboveLeft && aboveRight;
}

// Refines every sampled local maximum of at least half the largest sample between its
// neighbouring samples and returns the largest distance found.
CurveDistanceWitness refineMaxima(const Curve& from, const std::vector<double>& parameters,
                                  const CurveProximity& target) {
  // Each closest point searched from the target's sample segment nearest
  // the sample before (or, refining, nearest the sample refined about):
  // the same points, found sooner.
  std::vector<double> distance;
  std::vector<std::size_t> nearestSegment;
  distance.reserve(parameters.size());
  nearestSegment.reserve(parameters.size());
  std::size_t hint = 0;
  for (double s : parameters) {
    distance.push_back(target.closestPoint(from.point(s), hint).distance);
    nearestSegment.push_back(hint);
  }
  double largest = *std::max_element(distance.begin(), distance.end());

  CurveDistanceWitness worst;
  worst.distance = -1.0;
  auto record = [&](double s) {
    CurveProximity::ClosestPoint c = target.closestPoint(from.point(s), hint);
    if (c.distance > worst.distance)
      worst = {c.distance, s, c.parameter};
  };
  auto distanceAt = [&](double s) { return target.closestPoint(from.point(s), hint).distance; };
  std::size_t last = parameters.size() - 1;
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    if (!isLocalMaximum(distance, i) || distance[i] < 0.5 * largest)
      continue;
    hint = nearestSegment[i];
    record(parameters[i]);
    double lo = parameters[i == 0 ? 0 : i - 1];
    double hi = parameters[std::min(i + 1, last)];
    if (lo < hi)
      record(detail::maximiseBrent(distanceAt, lo, hi).t);
  }
  return worst;
}

CurveDistanceWitness directedDeviation(const Curve& from, const CurveProximity& target,
                                       double accuracy) {
  detail::SamplingRule rule;
  rule.initialIntervalsPerPiece = kMinSamplesPerPiece;
  rule.maxTurn = kMaxTurnBetweenSamples;
  rule.maxSagitta = accuracy;
  std::vector<double> parameters;
  detail::visitSamples(from, rule,
                       [&](const detail::CurveSample& s) { parameters.push_back(s.t); });
  return refineMaxima(from, parameters, target);
}

} // namespace

CurveDistanceWitness largestDistanceToCurve(const Curve& from, double a, double b,
                                            const CurveProximity& target, int samples) {
  if (!(a <= b) || samples < 1)
    throw GeometryError("largestDistanceToCurve needs a <= b and at least one sample");
  std::vector<double> parameters;
  for (int i = 0; i <= samples; ++i)
    parameters.push_back(i == samples ? b : a + (b - a) * i / samples);
  return refineMaxima(from, parameters, target);
}

double CurveDeviationReport::maxDeviation() const {
  return std::max(approximationToCurve.distance, curveToApproximation.distance);
}

CurveDeviationReport measureCurveDeviation(const Curve& approximation, const Curve& curve,
                                           const DeviationOptions& options) {
  CurveProximity curveProximity(curve, options.accuracy);
  return measureCurveDeviation(approximation, curve, curveProximity, options);
}

CurveDeviationReport measureCurveDeviation(const Curve& approximation, const Curve& curve,
                                           const CurveProximity& curveProximity,
                                           const DeviationOptions& options) {
  CurveProximity approximationProximity(approximation, options.accuracy);
  CurveDeviationReport report;
  report.approximationToCurve = directedDeviation(approximation, curveProximity, options.accuracy);
  report.curveToApproximation = directedDeviation(curve, approximationProximity, options.accuracy);
  return report;
}

} // namespace cncc::geom
