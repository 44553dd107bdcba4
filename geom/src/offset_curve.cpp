#include "cncc/geom/offset_curve.h"

#include "cncc/geom/composite_curve.h"
#include "cncc/geom/line_arc_curves.h"

#include "finite_difference.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

namespace cncc::geom {

namespace {

// Offsets of joined pieces closer than this are one point (the pieces meet
// tangentially); farther apart they meet at a corner.
constexpr double kTangentJoin = 1e-7;

std::string placeText(const Eigen::Vector3d& place) {
  char text[64];
  std::snprintf(text, sizeof text, "(%.4f, %.4f)", place.x(), place.y());
  return text;
}

std::shared_ptr<const Curve> offsetOfPiece(const std::shared_ptr<const Curve>& piece,
                                           double distance) {
  if (const auto* line = dynamic_cast<const LineCurve*>(piece.get())) {
    ParameterRange domain = line->domain();
    Eigen::Vector3d shift = distance * leftNormalOf(line->derivative(domain.t0));
    return std::make_shared<LineCurve>(line->point(domain.t0) + shift,
                                       line->point(domain.t1) + shift);
  }
  if (const auto* arc = dynamic_cast<const ArcCurve*>(piece.get())) {
    // Counter-clockwise the left side is towards the centre.
    double radius = arc->sweep() > 0 ? arc->radius() - distance : arc->radius() + distance;
    if (!(radius > 0)) {
      Eigen::Vector3d start = arc->point(arc->domain().t0);
      throw OffsetError("the tool's radius " + std::to_string(std::fabs(distance)) +
                            " is not less than the radius " + std::to_string(arc->radius()) +
                            " of the arc it runs inside, at " + placeText(start),
                        start, arc->radius());
    }
    return std::make_shared<ArcCurve>(arc->centre(), radius, arc->startAngle(), arc->sweep(),
                                      arc->startZ(), arc->zChange());
  }
  return std::make_shared<OffsetCurve>(piece, distance);
}

// The arc about a convex corner (one the curve turns away from the tool's
// side at) from where one offset ends to where the next starts.
std::shared_ptr<const Curve> cornerArc(const Curve& before, double turn, double distance) {
  double end = before.domain().t1;
  Eigen::Vector3d corner = before.point(end);
  Eigen::Vector2d incoming = before.derivative(end).head<2>().normalized();
  double startAngle = std::atan2(incoming.x(), -incoming.y()); // the left normal's angle
  if (distance < 0) {
    startAngle += std::numbers::pi;
  }
  return std::make_shared<ArcCurve>(corner.head<2>(), std::fabs(distance), startAngle, turn,
                                    corner.z(), 0.0);
}

// A curve over part of its parameter range.
class TrimmedCurve : public Curve {
public:
  TrimmedCurve(std::shared_ptr<const Curve> curve, ParameterRange range)
      : curve_(std::move(curve)), range_(range) {}
  ParameterRange domain() const override { return range_; }
  Eigen::Vector3d point(double t) const override { return curve_->point(range_.clamp(t)); }
  Eigen::Vector3d derivative(double t) const override {
    return curve_->derivative(range_.clamp(t));
  }
  Eigen::Vector3d secondDerivative(double t) const override {
    return curve_->secondDerivative(range_.clamp(t));
  }
  CurveDerivatives derivatives(double t) const override {
    return curve_->derivatives(range_.clamp(t));
  }
  std::vector<double> breakpoints() const override {
    std::vector<double> inside{range_.t0};
    for (double t : curve_->breakpoints()) {
      if (t > range_.t0 && t < range_.t1) {
        inside.push_back(t);
      }
    }
    inside.push_back(range_.t1);
    return inside;
  }

private:
  std::shared_ptr<const Curve> curve_;
  ParameterRange range_;
};

// The part of a curve over [from, to]: a line or an arc stays one.
std::shared_ptr<const Curve> trimmed(const std::shared_ptr<const Curve>& curve, double from,
                                     double to) {
  if (const auto* line = dynamic_cast<const LineCurve*>(curve.get())) {
    return std::make_shared<LineCurve>(line->point(from), line->point(to));
  }
  if (const auto* arc = dynamic_cast<const ArcCurve*>(curve.get())) {
    double length = arc->length();
    return std::make_shared<ArcCurve>(
        arc->centre(), arc->radius(), arc->startAngle() + arc->sweep() * from / length,
        arc->sweep() * (to - from) / length, arc->startZ() + arc->zChange() * from / length,
        arc->zChange() * (to - from) / length);
  }
  return std::make_shared<TrimmedCurve>(curve, ParameterRange{from, to});
}

// At a concave corner the offsets of the two pieces overlap: each is cut
// back to where they cross (Newton's method in both parameters from the
// corner's ends). Throws when they do not cross within the pieces.
void trimAtCrossing(std::shared_ptr<const Curve>& before, std::shared_ptr<const Curve>& after,
                    const Eigen::Vector3d& corner) {
  ParameterRange first = before->domain();
  ParameterRange second = after->domain();
  double s = first.t1;
  double u = second.t0;
  for (int iteration = 0; iteration < 100; ++iteration) {
    Eigen::Vector2d gap = (before->point(s) - after->point(u)).head<2>();
    if (gap.norm() < 1e-11 && s < first.t1 && u > second.t0) {
      before = trimmed(before, first.t0, s);
      after = trimmed(after, u, second.t1);
      return;
    }
    Eigen::Matrix2d jacobian;
    jacobian.col(0) = before->derivative(s).head<2>();
    jacobian.col(1) = -after->derivative(u).head<2>();
    double determinant = jacobian(0, 0) * jacobian(1, 1) - jacobian(0, 1) * jacobian(1, 0);
    if (!(std::fabs(determinant) > 0)) {
      break;
    }
    Eigen::Matrix2d inverse;
    inverse << jacobian(1, 1), -jacobian(0, 1), -jacobian(1, 0), jacobian(0, 0);
    Eigen::Vector2d step = -(inverse / determinant) * gap;
    s = first.clamp(s + step.x());
    u = second.clamp(u + step.y());
  }
  throw OffsetError("the offsets of the pieces meeting at the corner at " + placeText(corner) +
                        " do not cross: a piece there is too short for the tool's radius",
                    corner, 0.0);
}

// The gap between where `before` ends and `after` starts.
double gapBetween(const Curve& before, const Curve& after) {
  return (after.point(after.domain().t0) - before.point(before.domain().t1)).norm();
}

// Joins `next` (an offset) to the offsets in `joined`: directly where they
// meet as closely as the pieces do, by an arc about a convex corner (its
// origin nullopt in `origins`), or both trimmed at a concave one.
void joinOffset(std::vector<std::shared_ptr<const Curve>>& joined,
                std::vector<std::optional<std::size_t>>& origins,
                std::shared_ptr<const Curve>& next, const Curve& baseBefore, const Curve& baseAfter,
                double distance) {
  if (gapBetween(*joined.back(), *next) <= gapBetween(baseBefore, baseAfter) + kTangentJoin) {
    return;
  }
  double turn = cornerTurn(baseBefore, baseAfter);
  // The tool is outside a turn away from its side: d > 0 (left) at a right turn.
  if (distance * turn < 0) {
    joined.push_back(cornerArc(baseBefore, turn, distance));
    origins.emplace_back(std::nullopt);
    return;
  }
  trimAtCrossing(joined.back(), next, baseBefore.point(baseBefore.domain().t1));
}

} // namespace

double cornerTurn(const Curve& before, const Curve& after) {
  Eigen::Vector2d incoming = before.derivative(before.domain().t1).head<2>().normalized();
  Eigen::Vector2d outgoing = after.derivative(after.domain().t0).head<2>().normalized();
  double cross = incoming.x() * outgoing.y() - incoming.y() * outgoing.x();
  return std::atan2(cross, incoming.dot(outgoing));
}

double signedCurvatureOf(const CurveDerivatives& d) {
  double speed = d.first.head<2>().norm();
  if (!(speed > 0)) {
    return 0.0;
  }
  double cross = d.first.x() * d.second.y() - d.first.y() * d.second.x();
  return cross / (speed * speed * speed);
}

Eigen::Vector3d leftNormalOf(const Eigen::Vector3d& tangent) {
  Eigen::Vector2d planar = tangent.head<2>();
  double length = planar.norm();
  if (!(length > 0)) {
    return Eigen::Vector3d::Zero();
  }
  return {-planar.y() / length, planar.x() / length, 0.0};
}

OffsetCurve::OffsetCurve(std::shared_ptr<const Curve> base, double distance)
    : base_(std::move(base)), distance_(distance) {
  if (!base_) {
    throw GeometryError("an offset needs a curve");
  }
  breakpoints_ = base_->breakpoints();
}

ParameterRange OffsetCurve::smoothPieceAt(double t) const {
  auto after = std::upper_bound(breakpoints_.begin(), breakpoints_.end(), t);
  if (after == breakpoints_.begin()) {
    return {breakpoints_.front(), breakpoints_[1]};
  }
  if (after == breakpoints_.end()) {
    return {breakpoints_[breakpoints_.size() - 2], breakpoints_.back()};
  }
  return {*(after - 1), *after};
}

Eigen::Vector3d OffsetCurve::point(double t) const {
  PointWithDerivative base = base_->pointWithDerivative(t);
  return base.point + distance_ * leftNormalOf(base.first);
}

Eigen::Vector3d OffsetCurve::derivative(double t) const {
  CurveDerivatives d = base_->derivatives(t);
  return d.first * (1.0 - distance_ * signedCurvatureOf(d));
}

Eigen::Vector3d OffsetCurve::secondDerivative(double t) const {
  ParameterRange piece = smoothPieceAt(domain().clamp(t));
  return detail::firstDerivativeByDifferences(
      [this](double s) -> Eigen::Vector3d { return derivative(s); }, t, piece);
}

CurveDerivatives OffsetCurve::derivatives(double t) const {
  CurveDerivatives d = base_->derivatives(t);
  return {d.point + distance_ * leftNormalOf(d.first),
          d.first * (1.0 - distance_ * signedCurvatureOf(d)), secondDerivative(t)};
}

std::shared_ptr<const Curve> offsetOfPieces(const std::vector<std::shared_ptr<const Curve>>& pieces,
                                            double distance) {
  return offsetOfPiecesWithOrigins(pieces, distance).curve;
}

PiecesOffset offsetOfPiecesWithOrigins(const std::vector<std::shared_ptr<const Curve>>& pieces,
                                       double distance) {
  if (pieces.empty()) {
    throw GeometryError("an offset needs a curve");
  }
  if (!(distance != 0) || !std::isfinite(distance)) {
    throw GeometryError("an offset needs a finite non-zero distance");
  }
  std::vector<std::shared_ptr<const Curve>> joined;
  std::vector<std::optional<std::size_t>> origins;
  double widestGap = 0; // between the pieces: their offsets' join may be as wide
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    std::shared_ptr<const Curve> offset = offsetOfPiece(pieces[i], distance);
    if (i > 0) {
      joinOffset(joined, origins, offset, *pieces[i - 1], *pieces[i], distance);
      widestGap = std::max(widestGap, gapBetween(*pieces[i - 1], *pieces[i]));
    }
    joined.push_back(std::move(offset));
    origins.emplace_back(i);
  }
  // A closed path's end meets its start: a corner there is joined too (a
  // single closed piece is taken as smooth where it closes).
  const Curve& first = *pieces.front();
  const Curve& last = *pieces.back();
  if (pieces.size() > 1 &&
      (last.point(last.domain().t1) - first.point(first.domain().t0)).norm() <= 1e-9) {
    std::shared_ptr<const Curve> start = joined.front();
    joinOffset(joined, origins, start, last, first, distance);
    joined.front() = start;
  }
  if (joined.size() == 1) {
    return {joined.front(), std::move(origins)};
  }
  return {std::make_shared<CompositeCurve>(std::move(joined), widestGap + 10 * kTangentJoin),
          std::move(origins)};
}

} // namespace cncc::geom
