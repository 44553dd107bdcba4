#pragma once

#include "cncc/geom/curve.h"
#include "cncc/geom/geometry_error.h"

#include <Eigen/Core>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace cncc::geom {

/// Vertices on a curve: parameters[i] is where points[i] = C(parameters[i]) lies.
/// The first vertex is at t0 and the last at t1.
struct CurveSamples {
  std::vector<double> parameters;
  std::vector<Eigen::Vector3d> points;

  std::size_t chordCount() const { return points.empty() ? 0 : points.size() - 1; }
};

/// Largest distance from the curve arc C([ta, tb]) to the chord segment C(ta)C(tb).
/// Sampled at 16 equal parameter steps (four times as many, repeatedly, while
/// neighbouring sample chords turn by more than 0.2 rad), and every sampled local
/// maximum refined by Brent's method, and at each of the curve's breakpoints inside
/// (a corner's peak can lie between two samples), so the value is the arc's true
/// largest distance up to the rounding of the point evaluation (a few ulp of the
/// coordinates).
double chordDeviation(const Curve& curve, double ta, double tb);
/// The same with the curve's breakpoints (curve.breakpoints(), sorted) given, for a
/// caller that measures many chords of one curve.
double chordDeviation(const Curve& curve, double ta, double tb, std::span<const double> breaks);

/// The fewest chords with vertices on the curve such that every chord deviates at
/// most `tolerance` from the arc it replaces (chordDeviation <= tolerance, with a
/// margin of 64 ulp of the coordinates so that rounding in an independent measurement
/// cannot push a chord over).
///
/// A farthest-reach greedy walk: from the current vertex it finds the farthest
/// parameter whose chord still meets the tolerance (bracketing by doubling, then
/// bisection to about 1e-13 of the domain), and moves there. When feasibility is
/// monotone (if a chord meets the tolerance so does every chord over a sub-arc of
/// it) the greedy vertex is at every step at least as far along as the vertex of any
/// other valid chain, so no chain has fewer chords. The walk starts at t0; for a
/// closed curve the count is the fewest for a chain with a vertex at t0. Throws
/// GeometryError for a tolerance <= 0.
/// With `maximumChords`, throws ChordLimitExceeded as soon as the walk passes that
/// many chords (the work of a walk grows with its chords).
CurveSamples discretiseByChordTolerance(const Curve& curve, double tolerance,
                                        std::size_t maximumChords = SIZE_MAX);

/// Thrown by discretiseByChordTolerance past its chord limit.
class ChordLimitExceeded : public GeometryError {
public:
  explicit ChordLimitExceeded(std::size_t limit);
  std::size_t limit;
};

/// What discretising a curve would take, from about a thousand samples of it (cheap
/// next to the walk itself).
struct DiscretisationEstimate {
  /// The chords a curve of the sampled curvature k needs, the integral of
  /// sqrt(k / (8 tolerance)) over the arc length (a chord of length c on a circle
  /// of curvature k deviates c^2 k / 8), plus one per smooth piece; 0 when the
  /// tolerance is not a positive number.
  double chords = 0.0;
  /// The largest |x|, |y| or |z| of the samples.
  double largestCoordinate = 0.0;
};
/// With `offset`, the chords of the curve's offset by that distance in XY (> 0
/// to the left, as OffsetCurve), from the curve's own derivatives (the
/// coordinates are still the curve's, the arcs around corners not counted).
DiscretisationEstimate estimateDiscretisation(const Curve& curve, double tolerance,
                                              double offset = 0.0);

/// `count` >= 2 samples at equal parameter steps from t0 to t1 inclusive.
CurveSamples sampleUniformParameter(const Curve& curve, std::size_t count);

/// Samples every `spacing` mm of arc length from t0, and the last exactly at t1 (so
/// the last step is in (0, spacing]; a remainder below 1e-9 of the spacing is
/// absorbed into the previous step). Throws GeometryError for spacing <= 0.
CurveSamples sampleEqualArcLength(const Curve& curve, double spacing);

} // namespace cncc::geom
