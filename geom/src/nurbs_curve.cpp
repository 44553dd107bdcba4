#include "cncc/geom/nurbs_curve.h"

#include "cncc/geom/bspline_basis.h"
#include "cncc/geom/geometry_error.h"
#include "rational.h"

#include <array>
#include <cmath>

namespace cncc::geom {

namespace {

std::vector<double> unitWeights(std::size_t count) {
  return std::vector<double>(count, 1.0);
}

std::vector<double> bezierKnots(std::size_t pointCount) {
  std::vector<double> knots(pointCount, 0.0);
  knots.insert(knots.end(), pointCount, 1.0);
  return knots;
}

} // namespace

NurbsCurve::NurbsCurve(KnotVector knots, std::vector<Eigen::Vector3d> controlPoints,
                       std::vector<double> weights)
    : knots_(std::move(knots)), controlPoints_(std::move(controlPoints)),
      weights_(std::move(weights)) {
  if (auto problem = findProblem(knots_.values(), knots_.degree(), controlPoints_, weights_))
    throw GeometryError(*problem);
  rational_ = false;
  for (double w : weights_)
    rational_ = rational_ || w != weights_.front();
  // Equal weights cancel: store them as 1 so polynomial curves stay polynomial (W = 1)
  // in every derived form.
  double scale = rational_ ? 1.0 : 1.0 / weights_.front();
  homogeneous_.reserve(controlPoints_.size());
  for (std::size_t i = 0; i < controlPoints_.size(); ++i) {
    double w = weights_[i] * scale;
    homogeneous_.emplace_back(w * controlPoints_[i].x(), w * controlPoints_[i].y(),
                              w * controlPoints_[i].z(), w);
  }
}

NurbsCurve NurbsCurve::bspline(KnotVector knots, std::vector<Eigen::Vector3d> controlPoints) {
  std::vector<double> weights = unitWeights(controlPoints.size());
  return NurbsCurve(std::move(knots), std::move(controlPoints), std::move(weights));
}

NurbsCurve NurbsCurve::bspline(int degree, std::vector<Eigen::Vector3d> controlPoints) {
  KnotVector knots = KnotVector::clampedUniform(degree, static_cast<int>(controlPoints.size()));
  return bspline(std::move(knots), std::move(controlPoints));
}

NurbsCurve NurbsCurve::bezier(std::vector<Eigen::Vector3d> controlPoints,
                              std::vector<double> weights) {
  if (controlPoints.size() < 2)
    throw GeometryError("a Bezier curve needs at least 2 control points");
  if (weights.empty())
    weights = unitWeights(controlPoints.size());
  int degree = static_cast<int>(controlPoints.size()) - 1;
  KnotVector knots(bezierKnots(controlPoints.size()), degree);
  return NurbsCurve(std::move(knots), std::move(controlPoints), std::move(weights));
}

std::optional<std::string> NurbsCurve::findProblem(const std::vector<double>& knots, int degree,
                                                   const std::vector<Eigen::Vector3d>& points,
                                                   const std::vector<double>& weights) {
  if (auto problem = KnotVector::findProblem(knots, degree))
    return problem;
  std::size_t needed = knots.size() - static_cast<std::size_t>(degree) - 1;
  if (points.size() != needed)
    return std::to_string(knots.size()) + " knots of degree " + std::to_string(degree) + " need " +
           std::to_string(needed) + " control points, got " + std::to_string(points.size());
  if (weights.size() != points.size())
    return std::to_string(points.size()) + " control points need as many weights, got " +
           std::to_string(weights.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite())
      return "control point " + std::to_string(i) + " has a coordinate that is not finite";
    if (!std::isfinite(weights[i]) || !(weights[i] > 0.0))
      return "weight " + std::to_string(i) + " must be positive and finite";
  }
  return std::nullopt;
}

Eigen::Vector3d NurbsCurve::point(double t) const {
  // de Boor's algorithm on the p + 1 homogeneous points that act on the span.
  t = domain().clamp(t);
  int p = degree();
  int span = knots_.findSpan(t);
  std::array<HomogeneousPoint, kMaxDegree + 1> d;
  for (int j = 0; j <= p; ++j)
    d[j] = homogeneous_[static_cast<std::size_t>(j + span - p)];
  for (int r = 1; r <= p; ++r) {
    for (int j = p; j >= r; --j) {
      double lower = knots_[j + span - p];
      double alpha = (t - lower) / (knots_[j + 1 + span - r] - lower);
      d[j] = (1.0 - alpha) * d[j - 1] + alpha * d[j];
    }
  }
  return d[p].head<3>() / d[p].w();
}

Eigen::Vector3d NurbsCurve::derivative(double t) const {
  return derivatives(t).first;
}

Eigen::Vector3d NurbsCurve::secondDerivative(double t) const {
  return derivatives(t).second;
}

CurveDerivatives NurbsCurve::derivatives(double t) const {
  t = domain().clamp(t);
  int p = degree();
  int span = knots_.findSpan(t);
  BasisDerivatives basis = basisFunctionDerivatives(knots_, span, t, 2);
  std::array<HomogeneousPoint, 3> h;
  h.fill(HomogeneousPoint::Zero());
  for (int k = 0; k <= 2; ++k)
    for (int j = 0; j <= p; ++j)
      h[k] += basis(k, j) * homogeneous_[static_cast<std::size_t>(span - p + j)];
  return detail::rationalDerivatives(h[0], h[1], h[2]);
}

std::vector<HomogeneousPoint> NurbsCurve::homogeneousDerivatives(int span, double t,
                                                                 int order) const {
  int p = degree();
  BasisDerivatives basis = basisFunctionDerivatives(knots_, span, t, order);
  std::vector<HomogeneousPoint> result(static_cast<std::size_t>(order + 1),
                                       HomogeneousPoint::Zero());
  for (int k = 0; k <= order; ++k)
    for (int j = 0; j <= p; ++j)
      result[static_cast<std::size_t>(k)] +=
          basis(k, j) * homogeneous_[static_cast<std::size_t>(span - p + j)];
  return result;
}

} // namespace cncc::geom
