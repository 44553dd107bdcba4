#include "cncc/geom/interpolating_splines.h"

#include "cncc/geom/geometry_error.h"
#include "interpolating_splines_detail.h"

#include <algorithm>
#include <cmath>

namespace cncc::geom {

namespace {

using Vector = Eigen::Vector3d;

constexpr double kShortestChord = 1e-9;

void requireValidPoints(const std::vector<Vector>& points) {
  if (std::optional<std::string> problem = findSplinePointsProblem(points))
    throw GeometryError(*problem);
}

// Chord slope d_k = (P_{k+1} - P_k) / h_k.
std::vector<Vector> chordSlopes(const std::vector<Vector>& points,
                                const std::vector<double>& parameters) {
  std::vector<Vector> slopes;
  for (std::size_t k = 0; k + 1 < points.size(); ++k)
    slopes.push_back((points[k + 1] - points[k]) / (parameters[k + 1] - parameters[k]));
  return slopes;
}

Vector unitOr(const std::optional<Vector>& direction, const Vector& fallback) {
  if (direction && direction->norm() > 0.0 && direction->allFinite())
    return direction->normalized();
  return fallback.normalized();
}

// Derivative at t_0 of the parabola through the first three points (h: first two
// chord lengths, d: first two chord slopes).
Vector parabolaEndTangent(const Vector& d0, const Vector& d1, double h0, double h1) {
  return d0 - (d1 - d0) * h0 / (h0 + h1);
}

// One row a m_{i-1} + b m_i + c m_{i+1} = r of a tridiagonal system.
struct TridiagonalRow {
  double below = 0.0;
  double diagonal = 1.0;
  double above = 0.0;
  Vector right = Vector::Zero();
};

// Thomas algorithm; the systems here are diagonally dominant.
std::vector<Vector> solveTridiagonal(std::vector<TridiagonalRow> rows) {
  std::size_t n = rows.size();
  for (std::size_t i = 1; i < n; ++i) {
    double factor = rows[i].below / rows[i - 1].diagonal;
    rows[i].diagonal -= factor * rows[i - 1].above;
    rows[i].right -= factor * rows[i - 1].right;
  }
  std::vector<Vector> x(n);
  x[n - 1] = rows[n - 1].right / rows[n - 1].diagonal;
  for (std::size_t i = n - 1; i-- > 0;)
    x[i] = (rows[i].right - rows[i].above * x[i + 1]) / rows[i].diagonal;
  return x;
}

// The curvature-continuous spline's tangents at points[first..last] (chord parameters
// t), with the tangent at `first` fixed when `fixedStart` is given, otherwise from the
// start transition; at `last` the end transition if `last` is the final point, else
// a natural end.
std::vector<Vector> solveCubicSplineWindow(const std::vector<Vector>& points,
                                           const std::vector<double>& t,
                                           const std::vector<Vector>& slopes, std::size_t first,
                                           std::size_t last,
                                           const std::optional<Vector>& fixedStart,
                                           const SplineTransitions& transitions) {
  std::size_t n = last - first + 1;
  auto h = [&](std::size_t k) { return t[k + 1] - t[k]; };
  std::vector<TridiagonalRow> rows(n);
  if (fixedStart) {
    rows[0].right = *fixedStart;
  } else if (transitions.start == SplineEndCondition::Natural) {
    rows[0] = {0.0, 2.0, 1.0, 3.0 * slopes[first]};
  } else if (transitions.start == SplineEndCondition::Tangent) {
    rows[0].right = unitOr(transitions.startDirection, slopes[first]);
  } else {
    rows[0].right =
        n >= 3 ? parabolaEndTangent(slopes[first], slopes[first + 1], h(first), h(first + 1))
               : slopes[first];
  }
  for (std::size_t j = 1; j + 1 < n; ++j) {
    std::size_t i = first + j;
    rows[j] = {h(i), 2.0 * (h(i - 1) + h(i)), h(i - 1),
               3.0 * (h(i) * slopes[i - 1] + h(i - 1) * slopes[i])};
  }
  bool finalPoint = last + 1 == points.size();
  SplineEndCondition end = finalPoint ? transitions.end : SplineEndCondition::Natural;
  TridiagonalRow& row = rows[n - 1];
  const Vector& lastSlope = slopes[last - 1];
  if (end == SplineEndCondition::Natural) {
    row = {1.0, 2.0, 0.0, 3.0 * lastSlope};
  } else if (end == SplineEndCondition::Tangent) {
    row = {0.0, 1.0, 0.0, unitOr(transitions.endDirection, lastSlope)};
  } else {
    Vector tangent =
        n >= 3 ? parabolaEndTangent(lastSlope, slopes[last - 2], -h(last - 1), -h(last - 2))
               : lastSlope;
    row = {0.0, 1.0, 0.0, tangent};
  }
  return solveTridiagonal(std::move(rows));
}

PolynomialSpan hermiteSpan(const Vector& p0, const Vector& p1, const Vector& m0, const Vector& m1,
                           double t0, double t1) {
  // In the normalised u = (t - t0) / h the end derivatives are h m.
  double h = t1 - t0;
  Vector d0 = h * m0, d1 = h * m1;
  Vector a2 = 3.0 * (p1 - p0) - 2.0 * d0 - d1;
  Vector a3 = 2.0 * (p0 - p1) + d0 + d1;
  PolynomialSpan span;
  span.t0 = t0;
  span.t1 = t1;
  span.coefficients = {
      HomogeneousPoint(p0.x(), p0.y(), p0.z(), 1.0), HomogeneousPoint(d0.x(), d0.y(), d0.z(), 0.0),
      HomogeneousPoint(a2.x(), a2.y(), a2.z(), 0.0), HomogeneousPoint(a3.x(), a3.y(), a3.z(), 0.0)};
  return span;
}

} // namespace

std::optional<std::string> findSplinePointsProblem(const std::vector<Vector>& points) {
  if (points.size() < 2)
    return "a spline needs at least two points";
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite())
      return "spline point " + std::to_string(i + 1) + " is not finite";
    if (i > 0 && (points[i] - points[i - 1]).norm() < kShortestChord)
      return "spline points " + std::to_string(i) + " and " + std::to_string(i + 1) + " coincide";
  }
  return std::nullopt;
}

std::vector<double> chordLengthParameters(const std::vector<Vector>& points) {
  std::vector<double> t{0.0};
  for (std::size_t i = 1; i < points.size(); ++i)
    t.push_back(t.back() + (points[i] - points[i - 1]).norm());
  return t;
}

std::vector<Vector> detail::cSplineTangentsFrom(const std::vector<Vector>& points,
                                                const SplineTransitions& transitions,
                                                const CSplineOptions& options,
                                                const std::optional<Vector>& startDerivative) {
  requireValidPoints(points);
  std::vector<double> t = chordLengthParameters(points);
  std::vector<Vector> slopes = chordSlopes(points, t);
  std::size_t last = points.size() - 1;
  if (options.windowBlocks <= 0 || std::size_t(options.windowBlocks) >= last)
    return solveCubicSplineWindow(points, t, slopes, 0, last, startDerivative, transitions);
  // Window by window: each fixes the tangent at the far end of its first segment.
  std::vector<Vector> tangents;
  std::size_t window = std::size_t(options.windowBlocks);
  for (std::size_t i = 0; i < last; ++i) {
    std::optional<Vector> arrival = startDerivative;
    if (i > 0)
      arrival = tangents[i];
    std::vector<Vector> solved = solveCubicSplineWindow(
        points, t, slopes, i, std::min(last, i + window), arrival, transitions);
    if (i == 0)
      tangents.push_back(solved[0]);
    tangents.push_back(solved[1]);
  }
  return tangents;
}

std::vector<Vector> cSplineTangents(const std::vector<Vector>& points,
                                    const SplineTransitions& transitions,
                                    const CSplineOptions& options) {
  return detail::cSplineTangentsFrom(points, transitions, options, std::nullopt);
}

std::vector<Vector> akimaTangents(const std::vector<Vector>& points,
                                  const SplineTransitions& transitions) {
  requireValidPoints(points);
  std::vector<double> t = chordLengthParameters(points);
  std::vector<Vector> slopes = chordSlopes(points, t);
  std::size_t segments = slopes.size();
  // Two virtual slopes before and after (Akima's linear extension), so slope k sits
  // at extended[k + 2].
  std::vector<Vector> extended(segments + 4);
  for (std::size_t k = 0; k < segments; ++k)
    extended[k + 2] = slopes[k];
  const Vector& second = segments > 1 ? slopes[1] : slopes[0];
  const Vector& secondLast = segments > 1 ? slopes[segments - 2] : slopes[0];
  extended[1] = 2.0 * slopes[0] - second;
  extended[0] = 2.0 * extended[1] - slopes[0];
  extended[segments + 2] = 2.0 * slopes[segments - 1] - secondLast;
  extended[segments + 3] = 2.0 * extended[segments + 2] - slopes[segments - 1];

  double scale = 0.0;
  for (const Vector& d : slopes)
    scale = std::max(scale, d.norm());
  std::vector<Vector> tangents;
  for (std::size_t i = 0; i <= segments; ++i) {
    const Vector& before2 = extended[i];
    const Vector& before = extended[i + 1];
    const Vector& after = extended[i + 2];
    const Vector& after2 = extended[i + 3];
    double weightBefore = (after2 - after).norm();
    double weightAfter = (before - before2).norm();
    if (weightBefore + weightAfter <= 1e-12 * scale)
      tangents.push_back(0.5 * (before + after));
    else
      tangents.push_back((weightBefore * before + weightAfter * after) /
                         (weightBefore + weightAfter));
  }
  // Natural: zero second derivative, 2 m_0 + m_1 = 3 d_0 (mirrored at the end).
  if (transitions.start == SplineEndCondition::Tangent)
    tangents.front() = unitOr(transitions.startDirection, slopes.front());
  else if (transitions.start == SplineEndCondition::Natural)
    tangents.front() = 0.5 * (3.0 * slopes.front() - tangents[1]);
  if (transitions.end == SplineEndCondition::Tangent)
    tangents.back() = unitOr(transitions.endDirection, slopes.back());
  else if (transitions.end == SplineEndCondition::Natural)
    tangents.back() = 0.5 * (3.0 * slopes.back() - tangents[segments - 1]);
  return tangents;
}

std::vector<PolynomialSpan> hermiteSpans(const std::vector<Vector>& points,
                                         const std::vector<double>& parameters,
                                         const std::vector<Vector>& tangents) {
  std::vector<PolynomialSpan> spans;
  for (std::size_t i = 0; i + 1 < points.size(); ++i)
    spans.push_back(hermiteSpan(points[i], points[i + 1], tangents[i], tangents[i + 1],
                                parameters[i], parameters[i + 1]));
  return spans;
}

PiecewisePolynomialCurve cSpline(const std::vector<Vector>& points,
                                 const SplineTransitions& transitions,
                                 const CSplineOptions& options) {
  std::vector<Vector> tangents = cSplineTangents(points, transitions, options);
  return PiecewisePolynomialCurve(hermiteSpans(points, chordLengthParameters(points), tangents));
}

PiecewisePolynomialCurve aSpline(const std::vector<Vector>& points,
                                 const SplineTransitions& transitions) {
  std::vector<Vector> tangents = akimaTangents(points, transitions);
  return PiecewisePolynomialCurve(hermiteSpans(points, chordLengthParameters(points), tangents));
}

} // namespace cncc::geom
