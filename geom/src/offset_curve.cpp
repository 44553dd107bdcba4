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

// The arc about a convex corner from where one offset ends to where the next
// starts; throws at a concave corner.
std::shared_ptr<const Curve> cornerArc(const Curve& before, const Curve& after, double distance) {
  double end = before.domain().t1;
  double start = after.domain().t0;
  Eigen::Vector3d corner = before.point(end);
  Eigen::Vector2d incoming = before.derivative(end).head<2>().normalized();
  Eigen::Vector2d outgoing = after.derivative(start).head<2>().normalized();
  double cross = incoming.x() * outgoing.y() - incoming.y() * outgoing.x();
  double turn = std::atan2(cross, incoming.dot(outgoing));
  // The tool is outside a turn away from its side: d > 0 (left) at a right turn.
  if (distance * turn > 0) {
    throw OffsetError("the pieces of this path meet at a corner on the tool's side at " +
                          placeText(corner) +
                          "; trimming the offsets at such a corner is not built yet",
                      corner, 0.0);
  }
  double startAngle = std::atan2(incoming.x(), -incoming.y()); // the left normal's angle
  if (distance < 0) {
    startAngle += std::numbers::pi;
  }
  return std::make_shared<ArcCurve>(corner.head<2>(), std::fabs(distance), startAngle, turn,
                                    corner.z(), 0.0);
}

} // namespace

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
  return base_->point(t) + distance_ * leftNormalOf(base_->derivative(t));
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
  if (pieces.empty()) {
    throw GeometryError("an offset needs a curve");
  }
  if (!(distance != 0) || !std::isfinite(distance)) {
    throw GeometryError("an offset needs a finite non-zero distance");
  }
  std::vector<std::shared_ptr<const Curve>> joined;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    std::shared_ptr<const Curve> offset = offsetOfPiece(pieces[i], distance);
    if (i > 0) {
      const Curve& previous = *joined.back();
      Eigen::Vector3d end = previous.point(previous.domain().t1);
      if ((offset->point(offset->domain().t0) - end).norm() > kTangentJoin) {
        joined.push_back(cornerArc(*pieces[i - 1], *pieces[i], distance));
      }
    }
    joined.push_back(std::move(offset));
  }
  if (joined.size() == 1) {
    return joined.front();
  }
  return std::make_shared<CompositeCurve>(std::move(joined), 10 * kTangentJoin);
}

} // namespace cncc::geom
