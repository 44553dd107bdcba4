#include "cncc/geom/knot_vector.h"

#include "cncc/geom/geometry_error.h"

#include <algorithm>
#include <cmath>

namespace cncc::geom {

KnotVector::KnotVector(std::vector<double> knots, int degree)
    : knots_(std::move(knots)), degree_(degree) {
  if (auto problem = findProblem(knots_, degree_))
    throw GeometryError(*problem);
}

KnotVector KnotVector::clampedUniform(int degree, int controlPointCount, double t0, double t1) {
  if (degree < 1 || degree > kMaxDegree)
    throw GeometryError("degree " + std::to_string(degree) + " is outside 1.." +
                        std::to_string(kMaxDegree));
  if (controlPointCount < degree + 1)
    throw GeometryError("a degree " + std::to_string(degree) + " curve needs at least " +
                        std::to_string(degree + 1) + " control points, got " +
                        std::to_string(controlPointCount));
  if (!(t0 < t1))
    throw GeometryError("the parameter range must increase");
  std::vector<double> knots(static_cast<std::size_t>(degree + 1), t0);
  int interior = controlPointCount - degree - 1;
  for (int i = 1; i <= interior; ++i)
    knots.push_back(t0 + (t1 - t0) * i / (interior + 1));
  knots.insert(knots.end(), static_cast<std::size_t>(degree + 1), t1);
  return KnotVector(std::move(knots), degree);
}

std::optional<std::string> KnotVector::findProblem(const std::vector<double>& knots, int degree) {
  if (degree < 1 || degree > kMaxDegree)
    return "degree " + std::to_string(degree) + " is outside 1.." + std::to_string(kMaxDegree);
  std::size_t needed = 2 * static_cast<std::size_t>(degree + 1);
  if (knots.size() < needed)
    return "a degree " + std::to_string(degree) + " knot vector needs at least " +
           std::to_string(needed) + " knots, got " + std::to_string(knots.size());
  for (std::size_t i = 0; i < knots.size(); ++i) {
    if (!std::isfinite(knots[i]))
      return "knot " + std::to_string(i) + " is not a finite number";
    if (i > 0 && knots[i] < knots[i - 1])
      return "knots must not decrease (knot " + std::to_string(i) + " is smaller than knot " +
             std::to_string(i - 1) + ")";
  }
  std::size_t p = static_cast<std::size_t>(degree);
  double t0 = knots[p];
  double t1 = knots[knots.size() - 1 - p];
  if (!(t0 < t1))
    return "the knot vector's domain [knot p, knot m-p] is empty";
  for (std::size_t i = 0; i < knots.size();) {
    std::size_t j = i;
    while (j < knots.size() && knots[j] == knots[i])
      ++j;
    int multiplicity = static_cast<int>(j - i);
    bool interior = knots[i] > t0 && knots[i] < t1;
    int allowed = interior ? degree : degree + 1;
    if (multiplicity > allowed)
      return "knot " + std::to_string(knots[i]) + " repeats " + std::to_string(multiplicity) +
             " times, at most " + std::to_string(allowed) + " allowed there";
    i = j;
  }
  return std::nullopt;
}

ParameterRange KnotVector::domain() const {
  return {knots_[static_cast<std::size_t>(degree_)],
          knots_[knots_.size() - 1 - static_cast<std::size_t>(degree_)]};
}

int KnotVector::findSpan(double t) const {
  ParameterRange range = domain();
  int lastControlPoint = controlPointCount() - 1;
  if (t >= range.t1) {
    // t1 belongs to the last non-empty span.
    int span = lastControlPoint;
    while ((*this)[span] >= range.t1)
      --span;
    return span;
  }
  t = std::max(t, range.t0);
  // Binary search (The NURBS Book A2.1): the last knot <= t among u_0..u_n.
  auto end = knots_.begin() + lastControlPoint + 1;
  int span = static_cast<int>(std::upper_bound(knots_.begin(), end, t) - knots_.begin()) - 1;
  return std::clamp(span, degree_, lastControlPoint);
}

int KnotVector::multiplicity(double t) const {
  return static_cast<int>(std::count(knots_.begin(), knots_.end(), t));
}

std::vector<double> KnotVector::breakpoints() const {
  ParameterRange range = domain();
  std::vector<double> result{range.t0};
  for (double knot : knots_)
    if (knot > result.back() && knot < range.t1)
      result.push_back(knot);
  result.push_back(range.t1);
  return result;
}

bool KnotVector::isClamped() const {
  ParameterRange range = domain();
  return multiplicity(range.t0) == degree_ + 1 && multiplicity(range.t1) == degree_ + 1 &&
         knots_.front() == range.t0 && knots_.back() == range.t1;
}

} // namespace cncc::geom
