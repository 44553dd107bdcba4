#pragma once

#include "cncc/geom/curve.h"
#include "cncc/geom/knot_vector.h"

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace cncc::geom {

/// Homogeneous control point (w x, w y, w z, w).
using HomogeneousPoint = Eigen::Vector4d;

/// A NURBS curve C(t) = sum N_i(t) w_i P_i / sum N_i(t) w_i of degree p.
///
/// Construction validates the inputs and throws GeometryError naming the first
/// problem; findProblem reports the same problem without throwing. Valid means:
/// 1 <= p <= kMaxDegree, a valid KnotVector of degree p, as many control points as
/// the knot vector needs (knots - p - 1), one weight per point, every weight
/// positive and finite, every coordinate finite.
class NurbsCurve : public Curve {
public:
  NurbsCurve(KnotVector knots, std::vector<Eigen::Vector3d> controlPoints,
             std::vector<double> weights);

  /// Non-rational B-spline (all weights 1).
  static NurbsCurve bspline(KnotVector knots, std::vector<Eigen::Vector3d> controlPoints);
  /// Non-rational B-spline on clamped uniform knots over [0, 1].
  static NurbsCurve bspline(int degree, std::vector<Eigen::Vector3d> controlPoints);
  /// One Bezier segment over [0, 1] of degree controlPoints.size() - 1; weights empty
  /// means all 1.
  static NurbsCurve bezier(std::vector<Eigen::Vector3d> controlPoints,
                           std::vector<double> weights = {});

  static std::optional<std::string> findProblem(const std::vector<double>& knots, int degree,
                                                const std::vector<Eigen::Vector3d>& controlPoints,
                                                const std::vector<double>& weights);

  int degree() const { return knots_.degree(); }
  const KnotVector& knots() const { return knots_; }
  const std::vector<Eigen::Vector3d>& controlPoints() const { return controlPoints_; }
  const std::vector<double>& weights() const { return weights_; }
  const std::vector<HomogeneousPoint>& homogeneousControlPoints() const { return homogeneous_; }
  /// False when every weight is equal (the curve is then a polynomial spline).
  bool isRational() const { return rational_; }

  ParameterRange domain() const override { return knots_.domain(); }
  /// Evaluated by de Boor's algorithm on the homogeneous points.
  Eigen::Vector3d point(double t) const override;
  Eigen::Vector3d derivative(double t) const override;
  Eigen::Vector3d secondDerivative(double t) const override;
  /// Basis function derivatives (The NURBS Book A2.3) combined as in A4.2.
  CurveDerivatives derivatives(double t) const override;
  std::vector<double> breakpoints() const override { return knots_.breakpoints(); }

  /// Derivatives 0..order (order <= kMaxDegree) of the homogeneous curve
  /// A(t) = sum N_i(t) w_i P_i, w(t) = sum N_i(t) w_i, taken from the polynomial
  /// piece of `span` (so at a knot either neighbouring piece can be asked for).
  std::vector<HomogeneousPoint> homogeneousDerivatives(int span, double t, int order) const;

private:
  KnotVector knots_;
  std::vector<Eigen::Vector3d> controlPoints_;
  std::vector<double> weights_;
  std::vector<HomogeneousPoint> homogeneous_;
  bool rational_ = false;
};

/// Inserts the knot t `times` times (Boehm's algorithm, The NURBS Book A5.1). The curve
/// is unchanged as a point set and as a parametrisation. Throws GeometryError if t is
/// outside the domain or the resulting multiplicity would exceed the degree.
NurbsCurve insertKnot(const NurbsCurve& curve, double t, int times = 1);

} // namespace cncc::geom
