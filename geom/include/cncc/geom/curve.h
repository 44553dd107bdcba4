#pragma once

#include <Eigen/Core>

#include <vector>

namespace cncc::geom {

/// A closed parameter interval [t0, t1] with t0 < t1.
struct ParameterRange {
  double t0 = 0.0;
  double t1 = 1.0;

  double length() const { return t1 - t0; }
  double clamp(double t) const { return t < t0 ? t0 : (t > t1 ? t1 : t); }
  bool contains(double t) const { return t >= t0 && t <= t1; }
};

/// Position and first two derivatives with respect to the curve parameter.
struct CurveDerivatives {
  Eigen::Vector3d point;
  Eigen::Vector3d first;
  Eigen::Vector3d second;
};

/// Position and first derivative.
struct PointWithDerivative {
  Eigen::Vector3d point;
  Eigen::Vector3d first;
};

/// A parametric curve C(t), t in domain(), in 3D (planar curves have z = 0).
///
/// Every later stage (discretisation, arc length, the IR's derivative pass, the
/// virtual controller's spline models, verification) works through this interface.
/// Derivatives are with respect to t. Where the curve is only piecewise smooth
/// (knots of a spline, joins of a path) breakpoints() lists the parameters, and the
/// derivatives there are those of the piece that starts at the breakpoint (the last
/// piece at t1). Parameters outside the domain are clamped into it.
class Curve {
public:
  virtual ~Curve() = default;

  virtual ParameterRange domain() const = 0;
  virtual Eigen::Vector3d point(double t) const = 0;
  virtual Eigen::Vector3d derivative(double t) const = 0;
  virtual Eigen::Vector3d secondDerivative(double t) const = 0;

  /// All three at once; implementations override it when that is cheaper.
  virtual CurveDerivatives derivatives(double t) const;
  /// point(t) and derivative(t) at once (the same values); implementations override
  /// it when that is cheaper.
  virtual PointWithDerivative pointWithDerivative(double t) const;

  /// Increasing parameters, first t0 and last t1, between which the curve is smooth
  /// (infinitely differentiable). The default is {t0, t1}.
  virtual std::vector<double> breakpoints() const;

  /// Unsigned curvature |C' x C''| / |C'|^3; zero where the curve is singular (C' = 0).
  double curvature(double t) const;
};

/// Curvature from derivatives, as Curve::curvature.
double curvatureOf(const CurveDerivatives& d);

} // namespace cncc::geom
