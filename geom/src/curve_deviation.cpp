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
// neighbouring samples and returns the largest distance found. pointAt(i): from's
// point at parameters[i].
template <class PointAt>
CurveDistanceWitness refineMaxima(const Curve& from, const std::vector<double>& parameters,
                                  PointAt pointAt, const CurveProximity& target) {
  // Each closest point searched from the target's sample segment nearest
  // the sample before (or, refining, nearest the sample refined about):
  // the same points, found sooner.
  std::vector<double> distance;
  std::vector<std::size_t> nearestSegment;
  distance.reserve(parameters.size());
  nearestSegment.reserve(parameters.size());
  std::size_t hint = 0;
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    distance.push_back(target.closestPoint(pointAt(i), hint).distance);
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

CurveDistanceWitness refineMaxima(const Curve& from, const std::vector<double>& parameters,
                                  const CurveProximity& target) {
  return refineMaxima(
      from, parameters, [&](std::size_t i) { return from.point(parameters[i]); }, target);
}

// The curvature-adaptive samples a directed deviation from `curve` starts from.
std::vector<double> deviationSamples(const Curve& curve, double accuracy) {
  detail::SamplingRule rule;
  rule.initialIntervalsPerPiece = kMinSamplesPerPiece;
  rule.maxTurn = kMaxTurnBetweenSamples;
  rule.maxSagitta = accuracy;
  std::vector<double> parameters;
  detail::visitSamples(curve, rule,
                       [&](const detail::CurveSample& s) { parameters.push_back(s.t); });
  return parameters;
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
  if (!(options.accuracy > 0.0) || !std::isfinite(options.accuracy))
    throw GeometryError("the deviation accuracy must be positive");
  // The curve's samples and points first: they do not depend on the
  // approximation, so a budgeted curve (BudgetedCurve) is asked the same
  // points in all as in the order of the measurement, and one past its
  // budget ends before the approximation's samples and tree are built for
  // nothing.
  std::vector<double> curveParameters = deviationSamples(curve, options.accuracy);
  std::vector<Eigen::Vector3d> curvePoints;
  curvePoints.reserve(curveParameters.size());
  for (double s : curveParameters)
    curvePoints.push_back(curve.point(s));
  CurveProximity approximationProximity(approximation, options.accuracy);
  CurveDeviationReport report;
  report.approximationToCurve = refineMaxima(
      approximation, deviationSamples(approximation, options.accuracy), curveProximity);
  report.curveToApproximation = refineMaxima(
      curve, curveParameters, [&](std::size_t i) { return curvePoints[i]; },
      approximationProximity);
  return report;
}

} // namespace cncc::geom
