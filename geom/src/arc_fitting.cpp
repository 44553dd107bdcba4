#include "cncc/geom/arc_fitting.h"

#include "cncc/geom/curve_deviation.h"
#include "cncc/geom/deviation.h"
#include "cncc/geom/geometry_error.h"
#include "scalar_optimisation.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>
#include <numbers>

namespace cncc::geom {

namespace {

using Vector = Eigen::Vector3d;
using Point2 = Eigen::Vector2d;

constexpr double kPi = std::numbers::pi;
constexpr double kFlatSagitta = 1e-9;
constexpr double kSearchMargin = 0.995;
constexpr int kCurveSamples = 32;
constexpr int kSegmentSamples = 16;
constexpr int kBisectionSteps = 30;
constexpr int kGoldenSteps = 14;
// Leg ratios searched: beta / alpha in [1/kLegRatioRange, kLegRatioRange].
constexpr double kLegRatioRange = 8.0;
constexpr double kCornerAngle = 1e-6;
constexpr double kCurvatureJump = 1e-6;
constexpr double kPlanarTolerance = 1e-9;
// A last biarc shorter than this share of the one before is a sliver.
constexpr double kSliverFraction = 0.25;

double cross2(const Point2& a, const Point2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

Point2 leftNormal(const Point2& t) {
  return {-t.y(), t.x()};
}

// The move from `start` leaving along unit `tangent` to `end`: the arc tangent to it
// (at most 180 degrees), or a line where that arc would sag less than kFlatSagitta or
// its radius is over `largestRadius` (the fit's deviation check then decides).
std::optional<ArcSegment> tangentArc(const Vector& start, const Point2& tangent, const Vector& end,
                                     double largestRadius) {
  Point2 chord = (end - start).head<2>();
  double length = chord.norm();
  if (!(length > 0.0))
    return std::nullopt;
  double angle = std::atan2(cross2(tangent, chord), tangent.dot(chord)); // tangent to chord
  if (std::fabs(angle) > 0.5 * kPi)
    return std::nullopt;
  ArcSegment segment;
  segment.start = start;
  segment.end = end;
  double sagitta = 0.5 * length * std::tan(0.5 * std::fabs(angle));
  double radius = length / (2.0 * std::sin(std::fabs(angle)));
  if (sagitta < kFlatSagitta || !(radius <= largestRadius))
    return segment; // a line
  segment.kind = ArcSegmentKind::Arc;
  segment.radius = radius;
  segment.direction = angle > 0.0 ? ArcDirection::CounterClockwise : ArcDirection::Clockwise;
  segment.centre =
      start.head<2>() + (angle > 0.0 ? 1.0 : -1.0) * segment.radius * leftNormal(tangent);
  segment.sweep = 2.0 * angle;
  return segment;
}

double distanceToSegment(const Vector& p, const ArcSegment& segment) {
  if (segment.kind == ArcSegmentKind::Line) {
    Vector ab = segment.end - segment.start;
    double fraction = std::clamp((p - segment.start).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    return (p - (segment.start + fraction * ab)).norm();
  }
  Point2 fromCentre = p.head<2>() - segment.centre;
  Point2 startRay = segment.start.head<2>() - segment.centre;
  double turn = std::atan2(cross2(startRay, fromCentre), startRay.dot(fromCentre));
  if (segment.sweep < 0.0)
    turn = -turn;
  if (turn < 0.0)
    turn += 2.0 * kPi;
  double height = p.z() - segment.start.z();
  if (turn <= std::fabs(segment.sweep))
    return std::hypot(fromCentre.norm() - segment.radius, height);
  return std::min((p - segment.start).norm(), (p - segment.end).norm());
}

// The biarc from P0 (unit tangent T0) to P1 (unit tangent T1) whose tangent legs
// alpha, beta = ratio * alpha satisfy |(P1 - beta T1) - (P0 + alpha T0)| = alpha + beta;
// the arcs meet on the middle leg, dividing it as alpha : beta.
std::optional<std::vector<ArcSegment>> biarc(const Vector& p0, const Point2& t0, const Vector& p1,
                                             const Point2& t1, double ratio, double largestRadius) {
  Point2 v = (p1 - p0).head<2>();
  Point2 legSum = t0 + ratio * t1;
  double a = 2.0 * ratio * (t0.dot(t1) - 1.0);
  double b = -2.0 * v.dot(legSum);
  double c = v.squaredNorm();
  double alpha;
  if (std::fabs(a) < 1e-14) {
    if (!(b < 0.0))
      return std::nullopt;
    alpha = -c / b;
  } else {
    alpha = (-b - std::sqrt(b * b - 4.0 * a * c)) / (2.0 * a);
  }
  if (!(alpha > 0.0) || !std::isfinite(alpha))
    return std::nullopt;
  double beta = ratio * alpha;
  Point2 q0 = p0.head<2>() + alpha * t0;
  Point2 q1 = p1.head<2>() - beta * t1;
  Point2 middle = q1 - q0;
  Point2 junction2 = q0 + alpha / (alpha + beta) * middle;
  Point2 junctionTangent = middle.norm() > 0.0 ? Point2(middle.normalized()) : t0;
  Vector junction(junction2.x(), junction2.y(), p0.z());
  std::vector<ArcSegment> pieces;
  double scale = std::max(1.0, v.norm());
  if ((junction - p0).norm() > 1e-12 * scale) {
    std::optional<ArcSegment> first = tangentArc(p0, t0, junction, largestRadius);
    if (!first)
      return std::nullopt;
    pieces.push_back(*first);
  } else {
    junctionTangent = t0;
  }
  Vector start = pieces.empty() ? p0 : junction;
  if ((p1 - start).norm() > 1e-12 * scale) {
    std::optional<ArcSegment> second = tangentArc(start, junctionTangent, p1, largestRadius);
    if (!second)
      return std::nullopt;
    pieces.push_back(*second);
  }
  if (pieces.empty())
    return std::nullopt;
  return pieces;
}

bool isLocalMaximum(const std::vector<double>& values, std::size_t i) {
  bool aboveLeft = i == 0 || values[i] >= values[i - 1];
  bool aboveRight = i + 1 == values.size() || values[i] >= values[i + 1];
  return aboveLeft && aboveRight;
}

class ArcFitter {
public:
  ArcFitter(const Curve& curve, const ArcFitOptions& options)
      : curve_(curve), options_(options), proximity_(curve, options.tolerance * 1e-3),
        limit_(kSearchMargin * options.tolerance) {}

  ArcFit run() {
    std::vector<double> cuts = smoothPieceEnds();
    std::vector<ArcSegment> segments;
    for (std::size_t piece = 0; piece + 1 < cuts.size(); ++piece)
      fitPiece(cuts[piece], cuts[piece + 1], segments);
    ArcFit fit;
    fit.segments = merge(segments);
    fit.deviation =
        measureCurveDeviation(fit.path(), curve_, {options_.tolerance * 1e-3}).maxDeviation();
    return fit;
  }

private:
  // t0, the breakpoints where the tangent turns (corners) or the curvature jumps
  // (joins of lines and arcs, which are then kept as they are), t1.
  std::vector<double> smoothPieceEnds() {
    std::vector<double> cuts = curve_.breakpoints();
    std::vector<double> ends{cuts.front()};
    ParameterRange range = curve_.domain();
    for (std::size_t i = 1; i + 1 < cuts.size(); ++i) {
      Point2 before = leftTangent(cuts[i]), after = tangentAt(cuts[i]);
      if (std::atan2(std::fabs(cross2(before, after)), before.dot(after)) > kCornerAngle) {
        ends.push_back(cuts[i]);
        corners_.push_back(cuts[i]);
        continue;
      }
      double left = curve_.curvature(std::max(range.t0, cuts[i] - 1e-9 * range.length()));
      double right = curve_.curvature(cuts[i]);
      if (std::fabs(left - right) > kCurvatureJump * std::max({left, right, 1e-12}))
        ends.push_back(cuts[i]);
    }
    ends.push_back(cuts.back());
    return ends;
  }

  // Unit tangent in the plane of the piece that starts at t (the last piece at t1).
  Point2 tangentAt(double t) const {
    Point2 d = curve_.derivative(t).head<2>();
    if (d.norm() > 0.0)
      return d.normalized();
    // A stationary point: the direction to a nearby point instead.
    ParameterRange range = curve_.domain();
    double other = std::min(range.t1, t + 1e-6 * range.length());
    if (other == t)
      return -leftTangent(t);
    return (curve_.point(other) - curve_.point(t)).head<2>().normalized();
  }

  // Unit tangent of the piece that ends at t: its derivative just before t, carried to
  // t by one Taylor step (so the error is of second order in the offset).
  Point2 leftTangent(double t) const {
    ParameterRange range = curve_.domain();
    double before = std::max(range.t0, t - 1e-9 * range.length());
    CurveDerivatives d = curve_.derivatives(before);
    Point2 tangent = (d.first + (t - before) * d.second).head<2>();
    if (tangent.norm() > 0.0)
      return tangent.normalized();
    double other = std::max(range.t0, t - 1e-6 * range.length());
    return (curve_.point(t) - curve_.point(other)).head<2>().normalized();
  }

  // The tangent a biarc ending at t must match: the left one only at a corner.
  Point2 endTangent(double t) const {
    bool corner = std::find(corners_.begin(), corners_.end(), t) != corners_.end();
    return corner ? leftTangent(t) : tangentAt(t);
  }

  // Largest distance between the segments and the curve over [ua, ub], both ways;
  // stops early above the limit.
  double deviation(const std::vector<ArcSegment>& segments, double ua, double ub) const {
    auto toPath = [&](double u) {
      Vector p = curve_.point(u);
      double best = std::numeric_limits<double>::infinity();
      for (const ArcSegment& s : segments)
        best = std::min(best, distanceToSegment(p, s));
      return best;
    };
    std::vector<double> parameters, distances;
    for (int i = 0; i <= kCurveSamples; ++i) {
      parameters.push_back(ua + (ub - ua) * i / kCurveSamples);
      distances.push_back(toPath(parameters.back()));
    }
    double largest = *std::max_element(distances.begin(), distances.end());
    if (largest > limit_)
      return largest;
    for (std::size_t i = 0; i < parameters.size(); ++i) {
      if (!isLocalMaximum(distances, i) || distances[i] < 0.5 * largest)
        continue;
      double lo = parameters[i == 0 ? 0 : i - 1];
      double hi = parameters[std::min(i + 1, parameters.size() - 1)];
      largest = std::max(largest, detail::maximiseBrent(toPath, lo, hi).value);
      if (largest > limit_)
        return largest;
    }
    for (const ArcSegment& s : segments) {
      std::shared_ptr<const Curve> piece = s.curve();
      ParameterRange range = piece->domain();
      largest = std::max(
          largest,
          largestDistanceToCurve(*piece, range.t0, range.t1, proximity_, kSegmentSamples).distance);
      if (largest > limit_)
        return largest;
    }
    return largest;
  }

  // The biarc from ua to ub within the limit, trying equal legs first, then searching
  // the leg ratio; nothing if none is found.
  std::optional<std::vector<ArcSegment>> fittingBiarc(double ua, double ub) const {
    Vector p0 = curve_.point(ua), p1 = curve_.point(ub);
    Point2 t0 = tangentAt(ua), t1 = endTangent(ub);
    auto devationFor = [&](double logRatio, std::optional<std::vector<ArcSegment>>* out) {
      std::optional<std::vector<ArcSegment>> candidate =
          biarc(p0, t0, p1, t1, std::exp(logRatio), options_.largestRadius);
      if (!candidate)
        return std::numeric_limits<double>::infinity();
      double d = deviation(*candidate, ua, ub);
      if (out)
        *out = candidate;
      return d;
    };
    std::optional<std::vector<ArcSegment>> result;
    if (devationFor(0.0, &result) <= limit_)
      return result;
    // Golden section on log(ratio), stopping as soon as a ratio fits.
    double lo = -std::log(kLegRatioRange), hi = std::log(kLegRatioRange);
    const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
    double x1 = hi - golden * (hi - lo), x2 = lo + golden * (hi - lo);
    double f1 = devationFor(x1, &result);
    if (f1 <= limit_)
      return result;
    double f2 = devationFor(x2, &result);
    if (f2 <= limit_)
      return result;
    for (int step = 0; step < kGoldenSteps; ++step) {
      if (f1 < f2) {
        hi = x2, x2 = x1, f2 = f1;
        x1 = hi - golden * (hi - lo);
        f1 = devationFor(x1, &result);
        if (f1 <= limit_)
          return result;
      } else {
        lo = x1, x1 = x2, f1 = f2;
        x2 = lo + golden * (hi - lo);
        f2 = devationFor(x2, &result);
        if (f2 <= limit_)
          return result;
      }
    }
    return std::nullopt;
  }

  struct Biarc {
    double from;
    double to;
    std::vector<ArcSegment> segments;
  };

  // The farthest-reaching biarc from u (at most to b): doubling from `step`, then
  // bisection.
  Biarc reachFrom(double u, double b, double step) const {
    double lo = u, hi = std::min(b, u + step);
    std::optional<std::vector<ArcSegment>> best = fittingBiarc(u, hi);
    if (best) {
      lo = hi;
      while (lo < b) {
        double next = std::min(b, u + 2.0 * (lo - u));
        std::optional<std::vector<ArcSegment>> candidate = fittingBiarc(u, next);
        if (!candidate) {
          hi = next;
          break;
        }
        lo = next, best = candidate;
      }
    } else {
      double minimumStep = 1e-9 * (b - u);
      while (!best) {
        double next = u + 0.5 * (hi - u);
        if (next - u < minimumStep) // nothing fits (a cusp): a chord keeps the path going
          return {u, next, {lineBetween(u, next)}};
        best = fittingBiarc(u, next);
        (best ? lo : hi) = next;
      }
    }
    for (int i = 0; lo < b && i < kBisectionSteps && hi - lo > 1e-7 * (lo - u); ++i) {
      double middle = 0.5 * (lo + hi);
      std::optional<std::vector<ArcSegment>> candidate = fittingBiarc(u, middle);
      if (candidate)
        lo = middle, best = candidate;
      else
        hi = middle;
    }
    return {u, lo, *best};
  }

  ArcSegment lineBetween(double ua, double ub) const {
    ArcSegment line;
    line.start = curve_.point(ua);
    line.end = curve_.point(ub);
    return line;
  }

  void fitPiece(double a, double b, std::vector<ArcSegment>& out) const {
    std::vector<Biarc> biarcs;
    double step = (b - a) / 16.0;
    for (double u = a; u < b;) {
      biarcs.push_back(reachFrom(u, b, step));
      step = biarcs.back().to - u;
      u = biarcs.back().to;
    }
    balanceLastTwo(biarcs);
    for (const Biarc& biarc : biarcs)
      out.insert(out.end(), biarc.segments.begin(), biarc.segments.end());
  }

  // A greedy walk often ends with a sliver; two biarcs over the last two spans split
  // in the middle usually fit as well and leave no tiny moves.
  void balanceLastTwo(std::vector<Biarc>& biarcs) const {
    if (biarcs.size() < 2)
      return;
    Biarc& previous = biarcs[biarcs.size() - 2];
    const Biarc& last = biarcs.back();
    if (last.to - last.from >= kSliverFraction * (previous.to - previous.from))
      return;
    double middle = 0.5 * (previous.from + last.to);
    std::optional<std::vector<ArcSegment>> first = fittingBiarc(previous.from, middle);
    std::optional<std::vector<ArcSegment>> second = fittingBiarc(middle, last.to);
    if (!first || !second)
      return;
    double end = last.to;
    previous = {previous.from, middle, *first};
    biarcs.back() = {middle, end, *second};
  }

  static bool sameCircle(const ArcSegment& a, const ArcSegment& b) {
    double scale = std::max(1.0, a.radius);
    return a.kind == ArcSegmentKind::Arc && b.kind == ArcSegmentKind::Arc &&
           a.direction == b.direction && (a.centre - b.centre).norm() <= 1e-9 * scale &&
           std::fabs(a.radius - b.radius) <= 1e-9 * scale && std::fabs(a.sweep + b.sweep) <= kPi;
  }

  static bool sameLine(const ArcSegment& a, const ArcSegment& b) {
    if (a.kind != ArcSegmentKind::Line || b.kind != ArcSegmentKind::Line)
      return false;
    Vector da = a.end - a.start, db = b.end - b.start;
    return da.dot(db) > 0.0 && da.cross(db).norm() <= 1e-12 * da.norm() * db.norm();
  }

  static std::vector<ArcSegment> merge(const std::vector<ArcSegment>& segments) {
    std::vector<ArcSegment> merged;
    for (const ArcSegment& s : segments) {
      if (!merged.empty() && (sameCircle(merged.back(), s) || sameLine(merged.back(), s))) {
        merged.back().end = s.end;
        merged.back().sweep += s.sweep;
        continue;
      }
      merged.push_back(s);
    }
    return merged;
  }

  const Curve& curve_;
  const ArcFitOptions& options_;
  CurveProximity proximity_;
  double limit_;
  std::vector<double> corners_;
};

} // namespace

double ArcSegment::length() const {
  if (kind == ArcSegmentKind::Line)
    return (end - start).norm();
  return radius * std::fabs(sweep);
}

std::shared_ptr<const Curve> ArcSegment::curve() const {
  if (kind == ArcSegmentKind::Line)
    return std::make_shared<LineCurve>(start, end);
  Point2 startRay = start.head<2>() - centre;
  return std::make_shared<ArcCurve>(centre, radius, std::atan2(startRay.y(), startRay.x()), sweep,
                                    start.z(), end.z() - start.z());
}

std::size_t ArcFit::arcCount() const {
  return std::size_t(std::count_if(segments.begin(), segments.end(), [](const ArcSegment& s) {
    return s.kind == ArcSegmentKind::Arc;
  }));
}

std::size_t ArcFit::lineCount() const {
  return segments.size() - arcCount();
}

CompositeCurve ArcFit::path() const {
  std::vector<std::shared_ptr<const Curve>> pieces;
  for (const ArcSegment& s : segments)
    pieces.push_back(s.curve());
  return CompositeCurve(std::move(pieces), 1e-7);
}

std::optional<std::string> findArcFittingProblem(const Curve& curve) {
  ParameterRange range = curve.domain();
  double z = curve.point(range.t0).z();
  constexpr int kChecks = 64;
  for (int i = 0; i <= kChecks; ++i) {
    Vector p = curve.point(range.t0 + range.length() * i / kChecks);
    if (!p.allFinite())
      return "the curve has a point that is not finite";
    if (std::fabs(p.z() - z) > kPlanarTolerance)
      return "arcs can replace only a curve in a plane z = const (G17); this one changes z";
  }
  if ((curve.point(range.t1) - curve.point(range.t0)).norm() == 0.0 &&
      (curve.point(range.t0 + 0.5 * range.length()) - curve.point(range.t0)).norm() == 0.0)
    return "the curve has no length";
  return std::nullopt;
}

ArcFit fitArcs(const Curve& curve, const ArcFitOptions& options) {
  if (!(options.tolerance > 0.0) || !std::isfinite(options.tolerance))
    throw GeometryError("the arc fitting tolerance must be positive");
  if (std::optional<std::string> problem = findArcFittingProblem(curve))
    throw GeometryError(*problem);
  return ArcFitter(curve, options).run();
}

} // namespace cncc::geom
