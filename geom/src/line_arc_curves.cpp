#include "cncc/geom/line_arc_curves.h"

#include "cncc/geom/geometry_error.h"

#include <cmath>
#include <numbers>

namespace cncc::geom {

LineCurve::LineCurve(const Eigen::Vector3d& start, const Eigen::Vector3d& end)
    : start_(start), length_((end - start).norm()) {
  if (!(length_ > 0.0) || !std::isfinite(length_))
    throw GeometryError("a line needs two distinct finite end points");
  direction_ = (end - start) / length_;
}

Eigen::Vector3d LineCurve::point(double t) const {
  return start_ + domain().clamp(t) * direction_;
}

ArcCurve::ArcCurve(const Eigen::Vector2d& centre, double radius, double startAngle, double sweep,
                   double startZ, double zChange)
    : centre_(centre), radius_(radius), startAngle_(startAngle), sweep_(sweep), startZ_(startZ),
      zChange_(zChange), length_(std::hypot(radius * sweep, zChange)) {
  if (!(radius_ > 0.0) || !std::isfinite(radius_))
    throw GeometryError("an arc needs a positive finite radius");
  if (sweep_ == 0.0 || !std::isfinite(sweep_))
    throw GeometryError("an arc needs a non-zero finite sweep angle");
}

ArcCurve ArcCurve::fromCentre(const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                              const Eigen::Vector2d& centre, ArcDirection direction) {
  Eigen::Vector2d fromCentre = start.head<2>() - centre;
  Eigen::Vector2d toEnd = end.head<2>() - centre;
  double startAngle = std::atan2(fromCentre.y(), fromCentre.x());
  double endAngle = std::atan2(toEnd.y(), toEnd.x());
  const double turn = 2.0 * std::numbers::pi;
  // Angle travelled in the cutting direction, in (0, 2 pi]: coincident ends mean a full turn.
  double travel =
      direction == ArcDirection::CounterClockwise ? endAngle - startAngle : startAngle - endAngle;
  travel = std::fmod(travel, turn);
  if (travel < 0.0)
    travel += turn;
  if (travel <= 1e-12)
    travel = turn;
  double sweep = direction == ArcDirection::CounterClockwise ? travel : -travel;
  return ArcCurve(centre, fromCentre.norm(), startAngle, sweep, start.z(), end.z() - start.z());
}

double ArcCurve::angleAt(double t) const {
  return startAngle_ + sweep_ * (t / length_);
}

Eigen::Vector3d ArcCurve::point(double t) const {
  t = domain().clamp(t);
  double angle = angleAt(t);
  return {centre_.x() + radius_ * std::cos(angle), centre_.y() + radius_ * std::sin(angle),
          startZ_ + zChange_ * (t / length_)};
}

Eigen::Vector3d ArcCurve::derivative(double t) const {
  t = domain().clamp(t);
  double angle = angleAt(t);
  double angularSpeed = sweep_ / length_;
  return {-radius_ * angularSpeed * std::sin(angle), radius_ * angularSpeed * std::cos(angle),
          zChange_ / length_};
}

Eigen::Vector3d ArcCurve::secondDerivative(double t) const {
  t = domain().clamp(t);
  double angle = angleAt(t);
  double angularSpeed = sweep_ / length_;
  double scale = radius_ * angularSpeed * angularSpeed;
  return {-scale * std::cos(angle), -scale * std::sin(angle), 0.0};
}

} // namespace cncc::geom
