#include "cncc/geom/arc_length.h"

#include "cncc/geom/geometry_error.h"
#include "gauss_legendre.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace cncc::geom {

namespace {

// Each smooth piece starts as this many intervals, so that an interval and its halves
// cannot agree by accident on a curve that oscillates across the whole piece.
constexpr int kInitialIntervalsPerPiece = 8;
constexpr int kMaxDepth = 40;
// Splits one integration may make in all. A speed computed by finite
// differences (polar and param curves) carries noise far above a tight
// tolerance, and without a budget every interval would split to kMaxDepth
// (2^40 of them); past the budget the estimates so far are accepted, which
// on such a curve is as exact as its noise allows.
constexpr int kMaxSplits = 1 << 13;

double speedIntegral(const Curve& curve, double a, double b) {
  return detail::integrateGaussLegendre([&](double t) { return curve.derivative(t).norm(); }, a, b);
}

struct Interval {
  double start;
  double length;
};

// Splits [a, b] until an interval's estimate agrees with the sum over its halves within
// its share of the tolerance; appends the accepted halves in order.
void integrateAdaptively(const Curve& curve, double a, double b, double whole, double tolerance,
                         int depth, int& splitsLeft, std::vector<Interval>& accepted) {
  double middle = 0.5 * (a + b);
  double left = speedIntegral(curve, a, middle);
  double right = speedIntegral(curve, middle, b);
  double floor = 8.0 * std::numeric_limits<double>::epsilon() * std::fabs(left + right);
  bool converged = std::fabs(left + right - whole) <= std::max(tolerance, floor);
  if (converged || depth >= kMaxDepth || splitsLeft <= 0 || !(a < middle && middle < b)) {
    accepted.push_back({a, left});
    accepted.push_back({middle, right});
    return;
  }
  --splitsLeft;
  integrateAdaptively(curve, a, middle, left, 0.5 * tolerance, depth + 1, splitsLeft, accepted);
  integrateAdaptively(curve, middle, b, right, 0.5 * tolerance, depth + 1, splitsLeft, accepted);
}

std::vector<Interval> integrateRange(const Curve& curve, double ta, double tb, double tolerance) {
  std::vector<double> cuts{ta};
  for (double b : curve.breakpoints())
    if (b > ta && b < tb)
      cuts.push_back(b);
  cuts.push_back(tb);
  int count = static_cast<int>(cuts.size() - 1) * kInitialIntervalsPerPiece;
  double share = tolerance / count;
  std::vector<Interval> accepted;
  int splitsLeft = kMaxSplits;
  for (std::size_t piece = 0; piece + 1 < cuts.size(); ++piece) {
    double a = cuts[piece], b = cuts[piece + 1];
    for (int i = 0; i < kInitialIntervalsPerPiece; ++i) {
      double lo = a + (b - a) * i / kInitialIntervalsPerPiece;
      double hi = i + 1 == kInitialIntervalsPerPiece
                      ? b
                      : a + (b - a) * (i + 1) / kInitialIntervalsPerPiece;
      integrateAdaptively(curve, lo, hi, speedIntegral(curve, lo, hi), share, 0, splitsLeft,
                          accepted);
    }
  }
  return accepted;
}

void checkTolerance(double tolerance) {
  if (!(tolerance > 0.0))
    throw GeometryError("the arc length tolerance must be positive");
}

} // namespace

double arcLength(const Curve& curve, double ta, double tb, double tolerance) {
  checkTolerance(tolerance);
  ParameterRange range = curve.domain();
  ta = range.clamp(ta);
  tb = range.clamp(tb);
  if (ta == tb)
    return 0.0;
  double sign = 1.0;
  if (ta > tb) {
    std::swap(ta, tb);
    sign = -1.0;
  }
  double sum = 0.0;
  for (const Interval& interval : integrateRange(curve, ta, tb, tolerance))
    sum += interval.length;
  return sign * sum;
}

double arcLength(const Curve& curve, double tolerance) {
  ParameterRange range = curve.domain();
  return arcLength(curve, range.t0, range.t1, tolerance);
}

ArcLengthTable::ArcLengthTable(const Curve& curve, double tolerance) : curve_(curve) {
  checkTolerance(tolerance);
  ParameterRange range = curve.domain();
  cumulative_.push_back(0.0);
  for (const Interval& interval : integrateRange(curve, range.t0, range.t1, tolerance)) {
    starts_.push_back(interval.start);
    cumulative_.push_back(cumulative_.back() + interval.length);
  }
  starts_.push_back(range.t1);
}

double ArcLengthTable::lengthWithin(std::size_t interval, double t) const {
  double start = starts_[interval];
  if (t <= start)
    return 0.0;
  return speedIntegral(curve_, start, t);
}

double ArcLengthTable::lengthAt(double t) const {
  t = curve_.domain().clamp(t);
  auto after = std::upper_bound(starts_.begin(), starts_.end() - 1, t);
  std::size_t i = static_cast<std::size_t>(after - starts_.begin()) - 1;
  return cumulative_[i] + lengthWithin(i, t);
}

double ArcLengthTable::parameterAt(double s) const {
  if (s <= 0.0)
    return starts_.front();
  if (s >= totalLength())
    return starts_.back();
  auto after = std::upper_bound(cumulative_.begin(), cumulative_.end() - 1, s);
  std::size_t i = static_cast<std::size_t>(after - cumulative_.begin()) - 1;
  double target = s - cumulative_[i];
  double lo = starts_[i], hi = starts_[i + 1];
  double intervalLength = cumulative_[i + 1] - cumulative_[i];
  double t = lo + (hi - lo) * (intervalLength > 0.0 ? target / intervalLength : 0.5);
  // Newton on s(t) - target, kept inside the bracket [lo, hi] that shrinks each step.
  for (int iteration = 0; iteration < 60; ++iteration) {
    double residual = lengthWithin(i, t) - target;
    if (residual == 0.0)
      break;
    (residual < 0.0 ? lo : hi) = t;
    double speed = curve_.derivative(t).norm();
    double next = speed > 0.0 ? t - residual / speed : 0.5 * (lo + hi);
    if (!(next > lo && next < hi))
      next = 0.5 * (lo + hi);
    if (std::fabs(next - t) <=
        4.0 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::fabs(t)))
      return next;
    t = next;
  }
  return t;
}

std::vector<double> equalArcLengthParameters(const Curve& curve, std::size_t count) {
  if (count < 2)
    throw GeometryError("equal arc length sampling needs at least 2 points");
  ArcLengthTable table(curve);
  ParameterRange range = curve.domain();
  std::vector<double> parameters{range.t0};
  double total = table.totalLength();
  for (std::size_t k = 1; k + 1 < count; ++k)
    parameters.push_back(
        table.parameterAt(total * static_cast<double>(k) / static_cast<double>(count - 1)));
  parameters.push_back(range.t1);
  return parameters;
}

} // namespace cncc::geom
