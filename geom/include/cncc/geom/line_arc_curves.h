#pragma once

#include "cncc/geom/curve.h"

#include <Eigen/Core>

namespace cncc::geom {

/// The segment from `start` to `end`, parametrised by arc length: t in [0, |end - start|].
/// Throws GeometryError for a zero-length segment.
class LineCurve : public Curve {
public:
  LineCurve(const Eigen::Vector3d& start, const Eigen::Vector3d& end);

  ParameterRange domain() const override { return {0.0, length_}; }
  Eigen::Vector3d point(double t) const override;
  Eigen::Vector3d derivative(double) const override { return direction_; }
  Eigen::Vector3d secondDerivative(double) const override { return Eigen::Vector3d::Zero(); }

private:
  Eigen::Vector3d start_;
  Eigen::Vector3d direction_;
  double length_;
};

enum class ArcDirection { Clockwise, CounterClockwise };

/// A circular arc in a plane z = const as seen from +z (G17), optionally helical: z
/// changes linearly with the angle, as in G2/G3 with a Z word. Parametrised by arc
/// length of the (helical) path: t in [0, length()].
class ArcCurve : public Curve {
public:
  /// centre (z ignored), radius > 0, start angle (rad, from +x), signed sweep (rad,
  /// positive counter-clockwise, any size incl. several turns), start height and
  /// height change over the sweep. Throws GeometryError for radius <= 0 or sweep = 0.
  ArcCurve(const Eigen::Vector2d& centre, double radius, double startAngle, double sweep,
           double startZ = 0.0, double zChange = 0.0);

  /// The arc G2 (Clockwise) / G3 (CounterClockwise) would cut from start to end
  /// about centre: the radius is |start - centre| (end is projected onto the circle in
  /// angle only), and a full turn is taken when end coincides with start in xy.
  static ArcCurve fromCentre(const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                             const Eigen::Vector2d& centre, ArcDirection direction);

  const Eigen::Vector2d& centre() const { return centre_; }
  double radius() const { return radius_; }
  double startAngle() const { return startAngle_; }
  double sweep() const { return sweep_; }
  double startZ() const { return startZ_; }
  double zChange() const { return zChange_; }
  double length() const { return length_; }

  ParameterRange domain() const override { return {0.0, length_}; }
  Eigen::Vector3d point(double t) const override;
  Eigen::Vector3d derivative(double t) const override;
  Eigen::Vector3d secondDerivative(double t) const override;

private:
  double angleAt(double t) const;

  Eigen::Vector2d centre_;
  double radius_;
  double startAngle_;
  double sweep_;
  double startZ_;
  double zChange_;
  double length_;
};

} // namespace cncc::geom
