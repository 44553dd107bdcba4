#include "cncc/geom/geometry_error.h"
#include "cncc/geom/nurbs_curve.h"

#include <array>

namespace cncc::geom {

NurbsCurve insertKnot(const NurbsCurve& curve, double t, int times) {
  const KnotVector& knots = curve.knots();
  ParameterRange range = curve.domain();
  int p = curve.degree();
  if (!(t > range.t0 && t < range.t1))
    throw GeometryError("a knot can only be inserted inside the domain");
  if (times < 1)
    throw GeometryError("a knot must be inserted at least once");
  int existing = knots.multiplicity(t);
  if (existing + times > p)
    throw GeometryError("inserting the knot would repeat it " + std::to_string(existing + times) +
                        " times, more than the degree " + std::to_string(p));

  // Boehm's algorithm (The NURBS Book A5.1): points outside the span's reach are kept,
  // the p - s points acting on it are replaced by `times` rounds of affine blends.
  int span = knots.findSpan(t);
  int lastPoint = knots.controlPointCount() - 1;
  const std::vector<HomogeneousPoint>& old = curve.homogeneousControlPoints();

  std::vector<double> newKnots(knots.values().begin(), knots.values().begin() + span + 1);
  newKnots.insert(newKnots.end(), static_cast<std::size_t>(times), t);
  newKnots.insert(newKnots.end(), knots.values().begin() + span + 1, knots.values().end());

  std::vector<HomogeneousPoint> updated(old.size() + static_cast<std::size_t>(times));
  auto at = [](auto& v, int i) -> auto& {
    return v[static_cast<std::size_t>(i)];
  };
  for (int i = 0; i <= span - p; ++i)
    at(updated, i) = at(old, i);
  for (int i = span - existing; i <= lastPoint; ++i)
    at(updated, i + times) = at(old, i);
  std::array<HomogeneousPoint, kMaxDegree + 1> blend;
  for (int i = 0; i <= p - existing; ++i)
    blend[static_cast<std::size_t>(i)] = at(old, span - p + i);
  int first = span - p;
  for (int round = 1; round <= times; ++round) {
    first = span - p + round;
    for (int i = 0; i <= p - round - existing; ++i) {
      double alpha = (t - knots[first + i]) / (knots[i + span + 1] - knots[first + i]);
      at(blend, i) = alpha * at(blend, i + 1) + (1.0 - alpha) * at(blend, i);
    }
    at(updated, first) = blend[0];
    at(updated, span + times - round - existing) = at(blend, p - round - existing);
  }
  for (int i = first + 1; i < span - existing; ++i)
    at(updated, i) = at(blend, i - first);

  std::vector<Eigen::Vector3d> points;
  std::vector<double> weights;
  for (const HomogeneousPoint& h : updated) {
    points.push_back(h.head<3>() / h.w());
    weights.push_back(h.w());
  }
  return NurbsCurve(KnotVector(std::move(newKnots), p), std::move(points), std::move(weights));
}

} // namespace cncc::geom
