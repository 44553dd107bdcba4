#pragma once

// Models of Sinumerik's interpolating splines (CSPLINE, ASPLINE): given the points a
// program lists and the transitions at its ends, the curve the controller is taken to
// cut. Both are cubic Hermite splines through the points, parametrised by chord length
// (t_0 = 0, t_i = t_{i-1} + |P_i - P_{i-1}|; the controller's parametrisation is not
// published, chord length is the usual choice and makes |C'| close to 1), output as one
// PolynomialSpan per pair of neighbouring points.
//
// Transitions (Sinumerik BAUTO/BNAT/BTAN at the start, EAUTO/ENAT/ETAN at the end):
// - Natural (BNAT/ENAT): zero second derivative at the end point.
// - Tangent (BTAN/ETAN, the controller's default): "tangential transition to the
//   previous / next block". The model takes the direction of that block from the
//   caller (startDirection / endDirection, e.g. the G1 move into the spline or the
//   exact tangent of the curve being approximated); without one it falls back to the
//   adjacent chord of the spline itself (P_0 P_1 at the start, P_{n-1} P_n at the end),
//   which is what the controller does when the neighbouring block is a line along that
//   chord. The end derivative is that unit direction (unit speed, as chord length
//   parametrisation gives).
// - Auto (BAUTO/EAUTO, "determined by the first/last points"; the rule is not
//   published): C spline: the tangent of the parabola through the first (last) three
//   points; A spline: Akima's own end rule (the chord slopes are extended linearly by
//   two virtual chords).

#include "cncc/geom/polynomial_span.h"

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace cncc::geom {

enum class SplineEndCondition { Auto, Natural, Tangent };

struct SplineTransitions {
  SplineEndCondition start = SplineEndCondition::Tangent;
  SplineEndCondition end = SplineEndCondition::Tangent;
  /// Direction of the block before the spline (Tangent start); need not be unit length.
  std::optional<Eigen::Vector3d> startDirection;
  /// Direction of the block after the spline (Tangent end).
  std::optional<Eigen::Vector3d> endDirection;
};

/// $MC_CUBIC_SPLINE_BLOCKS default: how many blocks ahead the C spline looks.
inline constexpr int kDefaultCubicSplineWindow = 8;

struct CSplineOptions {
  /// The controller computes the C spline over a window of blocks rather than
  /// globally. Model (an assumption, the algorithm is not published): on reaching the
  /// segment P_i P_{i+1} it knows the tangent m_i it arrived with and the points
  /// P_i .. P_{i+w}, w = windowBlocks; it solves the curvature-continuous cubic spline
  /// through them with the tangent m_i at P_i and, at P_{i+w}, the end transition if
  /// that is the last point, a natural end otherwise; it cuts only the first segment
  /// and moves on. The path is tangent-continuous, and curvature-continuous except for
  /// the truncation of the window: the influence of a point on a cubic spline decays
  /// by a factor 2 - sqrt(3) = 0.27 per point, so with w = 8 the curvature steps are
  /// about 3e-5 of the curvature and the path differs from the global spline by a
  /// similar fraction of the point spacing. windowBlocks <= 0 computes the whole
  /// spline at once (the global spline), as a window covering every point does.
  int windowBlocks = kDefaultCubicSplineWindow;
};

/// The first problem with a spline's points (fewer than two, a non-finite coordinate,
/// two neighbouring points closer than 1e-9 mm), or nothing.
std::optional<std::string> findSplinePointsProblem(const std::vector<Eigen::Vector3d>& points);

/// Cumulative chord lengths, t_0 = 0.
std::vector<double> chordLengthParameters(const std::vector<Eigen::Vector3d>& points);

/// Derivatives with respect to the chord length parameter at every point.
std::vector<Eigen::Vector3d> cSplineTangents(const std::vector<Eigen::Vector3d>& points,
                                             const SplineTransitions& transitions,
                                             const CSplineOptions& options = {});
/// Akima's tangents: at P_i the weighted mean (w_a d_{i-1} + w_b d_i) / (w_a + w_b) of
/// the neighbouring chord slopes d = (P_{k+1} - P_k) / h_k with w_a = |d_{i+1} - d_i|,
/// w_b = |d_{i-1} - d_{i-2}| (the plain mean where both are zero). A point moves the
/// tangents of at most its two neighbours on each side, so at most six segments.
std::vector<Eigen::Vector3d> akimaTangents(const std::vector<Eigen::Vector3d>& points,
                                           const SplineTransitions& transitions);

/// The cubic Hermite spline through `points` at `parameters` with the given derivatives.
std::vector<PolynomialSpan> hermiteSpans(const std::vector<Eigen::Vector3d>& points,
                                         const std::vector<double>& parameters,
                                         const std::vector<Eigen::Vector3d>& tangents);

/// The C spline (CSPLINE) through the points. Throws GeometryError with
/// findSplinePointsProblem's message.
PiecewisePolynomialCurve cSpline(const std::vector<Eigen::Vector3d>& points,
                                 const SplineTransitions& transitions = {},
                                 const CSplineOptions& options = {});

/// The A spline (ASPLINE, Akima) through the points. Throws as cSpline.
PiecewisePolynomialCurve aSpline(const std::vector<Eigen::Vector3d>& points,
                                 const SplineTransitions& transitions = {});

} // namespace cncc::geom
