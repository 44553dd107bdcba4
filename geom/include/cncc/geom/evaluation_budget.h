// A bound on the work of a search over a curve: the points, derivatives
// asked of it. A curve that changes faster than any sampling resolves (a
// cosine of 1e6 t) makes every chord of a walk cost thousands of points,
// and a walk of the chord limit hours.
#pragma once

#include "cncc/geom/curve.h"
#include "cncc/geom/geometry_error.h"

#include <cstddef>

namespace cncc::geom {

// Thrown by BudgetedCurve past its limit.
class EvaluationBudgetExceeded : public GeometryError {
public:
  explicit EvaluationBudgetExceeded(std::size_t limit);
  std::size_t limit;
};

// `curve`, counting what is asked of it (points and derivatives) and
// throwing EvaluationBudgetExceeded past `limit`. It refers to `curve`,
// which must outlive it.
class BudgetedCurve : public Curve {
public:
  BudgetedCurve(const Curve& curve, std::size_t limit) : curve_(curve), limit_(limit) {}

  ParameterRange domain() const override { return curve_.domain(); }
  Eigen::Vector3d point(double t) const override;
  Eigen::Vector3d derivative(double t) const override;
  Eigen::Vector3d secondDerivative(double t) const override;
  CurveDerivatives derivatives(double t) const override;
  // Counted as the point and the derivative it is.
  PointWithDerivative pointWithDerivative(double t) const override;
  std::vector<double> breakpoints() const override { return curve_.breakpoints(); }

  std::size_t used() const { return used_; }

private:
  void count() const;

  const Curve& curve_;
  std::size_t limit_;
  mutable std::size_t used_ = 0;
};

// Adds the points `curve` was asked for to `total` when it goes out of
// scope, also when its budget ran out (the budget of a search is shared by
// the curves it makes).
struct EvaluationsCharged {
  std::size_t& total;
  const BudgetedCurve& curve;
  ~EvaluationsCharged() { total += curve.used(); }
};

} // namespace cncc::geom
