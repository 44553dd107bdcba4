#pragma once

#include "cncc/geom/curve.h"

#include <Eigen/Core>

#include <functional>

namespace cncc::geom {

using ScalarFunction = std::function<double(double)>;
using PointFunction = std::function<Eigen::Vector3d(double)>;

/// A curve given by callbacks: how the language's analytic curves (parametric
/// x(t), y(t), z(t)) reach the kernel.
///
/// Derivative callbacks are optional. Without them derivatives come from fourth-order
/// finite differences of the position callback: central 5-point stencils inside the
/// domain, one-sided 5-point stencils within two steps of an end (so the callback is
/// never called outside the domain). Steps are eps^(1/5) = 7.4e-4 (first) and
/// eps^(1/6) = 2.5e-3 (second derivative) in t, which balances truncation against
/// rounding for curves that vary on a parameter scale of about 1 (angles, normalised
/// parameters): relative accuracy is then about 1e-9 (first) and 1e-6 (second) for
/// slowly varying curves and (h w)^4 for a curve oscillating at w rad per unit of t.
class FunctionCurve : public Curve {
public:
  FunctionCurve(ParameterRange range, PointFunction position, PointFunction first = {},
                PointFunction second = {});

  /// x(t), y(t) and optionally z(t) (z = 0 when absent).
  static FunctionCurve fromCoordinates(ParameterRange range, ScalarFunction x, ScalarFunction y,
                                       ScalarFunction z = {});

  ParameterRange domain() const override { return range_; }
  Eigen::Vector3d point(double t) const override;
  Eigen::Vector3d derivative(double t) const override;
  Eigen::Vector3d secondDerivative(double t) const override;

  bool hasExactDerivative() const { return static_cast<bool>(first_); }
  bool hasExactSecondDerivative() const { return static_cast<bool>(second_); }

private:
  ParameterRange range_;
  PointFunction position_;
  PointFunction first_;
  PointFunction second_;
};

/// A planar curve in polar form: x = r(t) cos t, y = r(t) sin t, z = 0.
/// With r'(t) and r''(t) given, derivatives are exact; otherwise r's derivatives come
/// from the finite differences described at FunctionCurve.
class PolarCurve : public Curve {
public:
  PolarCurve(ParameterRange range, ScalarFunction radius, ScalarFunction radiusDerivative = {},
             ScalarFunction radiusSecondDerivative = {});

  ParameterRange domain() const override { return range_; }
  Eigen::Vector3d point(double t) const override;
  Eigen::Vector3d derivative(double t) const override;
  Eigen::Vector3d secondDerivative(double t) const override;
  CurveDerivatives derivatives(double t) const override;
  PointWithDerivative pointWithDerivative(double t) const override;

  double radius(double t) const { return radius_(range_.clamp(t)); }

private:
  double radiusDerivative(double t) const;
  double radiusSecondDerivative(double t) const;

  ParameterRange range_;
  ScalarFunction radius_;
  ScalarFunction radiusDerivative_;
  ScalarFunction radiusSecondDerivative_;
};

} // namespace cncc::geom
