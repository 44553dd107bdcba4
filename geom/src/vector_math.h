#pragma once

// Small vector helpers shared by the kernel's sources (not part of the public API).

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace cncc::geom::detail {

/// Angle in [0, pi] between two vectors; 0 if either is zero.
inline double angleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  double cross = a.cross(b).norm();
  double dot = a.dot(b);
  if (cross == 0.0 && dot == 0.0)
    return 0.0;
  return std::atan2(cross, dot);
}

/// Fraction f in [0, 1] of the point on segment [a, b] closest to p.
inline double closestFractionOnSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                       const Eigen::Vector3d& b) {
  Eigen::Vector3d ab = b - a;
  double lengthSquared = ab.squaredNorm();
  if (lengthSquared == 0.0)
    return 0.0;
  return std::clamp((p - a).dot(ab) / lengthSquared, 0.0, 1.0);
}

inline double distanceToSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                const Eigen::Vector3d& b) {
  double f = closestFractionOnSegment(p, a, b);
  return (p - (a + f * (b - a))).norm();
}

} // namespace cncc::geom::detail
