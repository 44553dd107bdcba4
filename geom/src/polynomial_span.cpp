#include "cncc/geom/polynomial_span.h"

#include "cncc/geom/geometry_error.h"
#include "rational.h"

#include <algorithm>
#include <array>

namespace cncc::geom {

namespace {

double binomial(int n, int k) {
  double result = 1.0;
  for (int i = 1; i <= k; ++i)
    result = result * (n - k + i) / i;
  return result;
}

} // namespace

bool PolynomialSpan::isRational() const {
  for (std::size_t k = 0; k < coefficients.size(); ++k)
    if (coefficients[k].w() != (k == 0 ? 1.0 : 0.0))
      return true;
  return false;
}

HomogeneousPoint PolynomialSpan::homogeneousAt(double u) const {
  HomogeneousPoint value = coefficients.back();
  for (int k = degree() - 1; k >= 0; --k)
    value = value * u + coefficients[static_cast<std::size_t>(k)];
  return value;
}

Eigen::Vector3d PolynomialSpan::pointAt(double u) const {
  HomogeneousPoint h = homogeneousAt(u);
  return h.head<3>() / h.w();
}

CurveDerivatives PolynomialSpan::derivativesAt(double u) const {
  // Horner's rule run three times in step: value, first and half the second derivative.
  HomogeneousPoint value = coefficients.back();
  HomogeneousPoint first = HomogeneousPoint::Zero();
  HomogeneousPoint halfSecond = HomogeneousPoint::Zero();
  for (int k = degree() - 1; k >= 0; --k) {
    halfSecond = halfSecond * u + first;
    first = first * u + value;
    value = value * u + coefficients[static_cast<std::size_t>(k)];
  }
  return detail::rationalDerivatives(value, first, 2.0 * halfSecond);
}

Eigen::Vector3d BezierSpan::pointAt(double u) const {
  std::array<HomogeneousPoint, kMaxDegree + 1> d;
  int p = degree();
  for (int j = 0; j <= p; ++j)
    d[static_cast<std::size_t>(j)] = controlPoints[static_cast<std::size_t>(j)];
  for (int r = 1; r <= p; ++r)
    for (int j = 0; j <= p - r; ++j)
      d[static_cast<std::size_t>(j)] =
          (1.0 - u) * d[static_cast<std::size_t>(j)] + u * d[static_cast<std::size_t>(j + 1)];
  return d[0].head<3>() / d[0].w();
}

std::vector<PolynomialSpan> toPowerBasis(const NurbsCurve& curve) {
  // The span's polynomial piece equals its Taylor expansion at the span start t0; with
  // u = (t - t0) / h the k-th coefficient is A^(k)(t0) h^k / k!. The derivatives come
  // from the basis functions of that span, so a knot's left piece is never mixed in.
  const KnotVector& knots = curve.knots();
  int p = curve.degree();
  std::vector<PolynomialSpan> spans;
  for (int span = p; span < knots.controlPointCount(); ++span) {
    double t0 = knots[span], t1 = knots[span + 1];
    if (!(t0 < t1))
      continue;
    std::vector<HomogeneousPoint> taylor = curve.homogeneousDerivatives(span, t0, p);
    double h = t1 - t0, scale = 1.0;
    for (int k = 0; k <= p; ++k) {
      taylor[static_cast<std::size_t>(k)] *= scale;
      scale *= h / (k + 1);
    }
    if (!curve.isRational()) {
      // The weight is 1 exactly, not a sum of basis functions rounded to about 1.
      for (int k = 0; k <= p; ++k)
        taylor[static_cast<std::size_t>(k)].w() = k == 0 ? 1.0 : 0.0;
    }
    spans.push_back({t0, t1, std::move(taylor)});
  }
  return spans;
}

BezierSpan toBezier(const PolynomialSpan& span) {
  // b_j = sum_{k<=j} C(j,k) / C(p,k) a_k: the power basis written in Bernstein form.
  int p = span.degree();
  BezierSpan bezier{span.t0, span.t1, {}};
  for (int j = 0; j <= p; ++j) {
    HomogeneousPoint b = HomogeneousPoint::Zero();
    for (int k = 0; k <= j; ++k)
      b += binomial(j, k) / binomial(p, k) * span.coefficients[static_cast<std::size_t>(k)];
    bezier.controlPoints.push_back(b);
  }
  return bezier;
}

PolynomialSpan toPowerBasis(const BezierSpan& span) {
  // a_k = C(p,k) sum_{i<=k} (-1)^(k-i) C(k,i) b_i, the k-th forward difference scaled.
  int p = span.degree();
  PolynomialSpan power{span.t0, span.t1, {}};
  for (int k = 0; k <= p; ++k) {
    HomogeneousPoint a = HomogeneousPoint::Zero();
    for (int i = 0; i <= k; ++i) {
      double sign = ((k - i) % 2 == 0) ? 1.0 : -1.0;
      a += sign * binomial(k, i) * span.controlPoints[static_cast<std::size_t>(i)];
    }
    power.coefficients.push_back(binomial(p, k) * a);
  }
  return power;
}

std::vector<BezierSpan> toBezierSpans(const NurbsCurve& curve) {
  std::vector<BezierSpan> result;
  for (const PolynomialSpan& span : toPowerBasis(curve))
    result.push_back(toBezier(span));
  return result;
}

PiecewisePolynomialCurve::PiecewisePolynomialCurve(std::vector<PolynomialSpan> spans)
    : spans_(std::move(spans)) {
  if (spans_.empty())
    throw GeometryError("a piecewise polynomial curve needs at least one span");
  for (std::size_t i = 0; i < spans_.size(); ++i) {
    const PolynomialSpan& span = spans_[i];
    if (!(span.t0 < span.t1))
      throw GeometryError("span " + std::to_string(i) + " has an empty parameter interval");
    if (span.coefficients.empty() || span.degree() > kMaxDegree)
      throw GeometryError("span " + std::to_string(i) + " must have 1.." +
                          std::to_string(kMaxDegree + 1) + " coefficients");
    if (i > 0 && span.t0 != spans_[i - 1].t1)
      throw GeometryError("span " + std::to_string(i) + " does not start where span " +
                          std::to_string(i - 1) + " ends");
  }
}

std::size_t PiecewisePolynomialCurve::spanIndex(double t) const {
  auto after = std::upper_bound(spans_.begin(), spans_.end(), t,
                                [](double value, const PolynomialSpan& s) { return value < s.t0; });
  if (after == spans_.begin())
    return 0;
  return static_cast<std::size_t>(after - spans_.begin()) - 1;
}

ParameterRange PiecewisePolynomialCurve::domain() const {
  return {spans_.front().t0, spans_.back().t1};
}

Eigen::Vector3d PiecewisePolynomialCurve::point(double t) const {
  t = domain().clamp(t);
  const PolynomialSpan& span = spans_[spanIndex(t)];
  return span.pointAt((t - span.t0) / (span.t1 - span.t0));
}

Eigen::Vector3d PiecewisePolynomialCurve::derivative(double t) const {
  return derivatives(t).first;
}

Eigen::Vector3d PiecewisePolynomialCurve::secondDerivative(double t) const {
  return derivatives(t).second;
}

CurveDerivatives PiecewisePolynomialCurve::derivatives(double t) const {
  t = domain().clamp(t);
  const PolynomialSpan& span = spans_[spanIndex(t)];
  double h = span.t1 - span.t0;
  CurveDerivatives d = span.derivativesAt((t - span.t0) / h);
  d.first /= h;
  d.second /= h * h;
  return d;
}

std::vector<double> PiecewisePolynomialCurve::breakpoints() const {
  std::vector<double> result;
  for (const PolynomialSpan& span : spans_)
    result.push_back(span.t0);
  result.push_back(spans_.back().t1);
  return result;
}

} // namespace cncc::geom
