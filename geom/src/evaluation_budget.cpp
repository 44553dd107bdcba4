#include "cncc/geom/evaluation_budget.h"

#include <string>

namespace cncc::geom {

EvaluationBudgetExceeded::EvaluationBudgetExceeded(std::size_t limit)
    : GeometryError("the search asked more than " + std::to_string(limit) + " points of the curve"),
      limit(limit) {}

void BudgetedCurve::count() const {
  if (++used_ > limit_) {
    throw EvaluationBudgetExceeded(limit_);
  }
}

Eigen::Vector3d BudgetedCurve::point(double t) const {
  count();
  return curve_.point(t);
}

Eigen::Vector3d BudgetedCurve::derivative(double t) const {
  count();
  return curve_.derivative(t);
}

Eigen::Vector3d BudgetedCurve::secondDerivative(double t) const {
  count();
  return curve_.secondDerivative(t);
}

CurveDerivatives BudgetedCurve::derivatives(double t) const {
  count();
  return curve_.derivatives(t);
}

PointWithDerivative BudgetedCurve::pointWithDerivative(double t) const {
  count();
  count();
  return curve_.pointWithDerivative(t);
}

} // namespace cncc::geom
