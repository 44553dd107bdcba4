#pragma once

#include "cncc/geom/curve.h"

#include <optional>
#include <string>
#include <vector>

namespace cncc::geom {

/// Highest spline degree the kernel evaluates (controllers stop at 5 or 7; the
/// bound lets evaluation work on fixed-size stack buffers).
inline constexpr int kMaxDegree = 9;

/// A non-decreasing knot vector u_0..u_m for a B-spline of degree p with
/// n + 1 = m - p control points. The curve's domain is [u_p, u_{m-p}]; knots
/// outside it (unclamped ends) are allowed. Interior knots may repeat up to p
/// times (a repeat of p + 1 would break the curve in two).
class KnotVector {
public:
  /// Validates and throws GeometryError with findProblem's message.
  KnotVector(std::vector<double> knots, int degree);

  /// Clamped uniform knots: p + 1 copies of t0 and of t1, and `controlPointCount - p - 1`
  /// interior knots spaced evenly, as CAM systems and controllers default to.
  static KnotVector clampedUniform(int degree, int controlPointCount, double t0 = 0.0,
                                   double t1 = 1.0);

  /// The first problem with these inputs, or nothing if they make a valid knot vector.
  static std::optional<std::string> findProblem(const std::vector<double>& knots, int degree);

  int degree() const { return degree_; }
  const std::vector<double>& values() const { return knots_; }
  double operator[](int i) const { return knots_[static_cast<std::size_t>(i)]; }
  int size() const { return static_cast<int>(knots_.size()); }
  int controlPointCount() const { return size() - degree_ - 1; }
  ParameterRange domain() const;

  /// The span index i with u_i <= t < u_{i+1}, p <= i <= n, found by bisection
  /// (The NURBS Book A2.1). At the end of the domain it returns the last non-empty
  /// span, so t1 belongs to the last span. t is clamped into the domain.
  int findSpan(double t) const;

  /// How many knots equal t exactly.
  int multiplicity(double t) const;

  /// The distinct knot values inside the domain, from t0 to t1 inclusive.
  std::vector<double> breakpoints() const;

  /// True if both ends repeat p + 1 times (the curve interpolates its end points).
  bool isClamped() const;

private:
  std::vector<double> knots_;
  int degree_;
};

} // namespace cncc::geom
