// A cut's tolerance, split once between the approximation (chords, arcs,
// fitted splines), the controller's rounding of the printed numbers and the
// spline model's error, and read by every way of lowering the cut: nothing
// else computes the rounding.
#pragma once

#include <cmath>
#include <limits>

namespace cncc::ir {

// The share of the increment kept for the rounding of a controller's printed
// literals: 8 significant digits move a step's points a few micrometres at
// most.
inline constexpr double literalShare = 0.02;

// `points` (what a tolerance leaves for points on a grid of `increment`)
// less that share; 0 when nothing is left.
inline double lessLiteralShare(double points, double increment) {
  return points > 0 ? points - increment * literalShare : 0.0;
}

// The tolerance of a cut without tolerance=: the chords' where no samples=
// or spacing= chose its points, and where they did, the one its numbers are
// read within.
inline constexpr double defaultTolerance = 0.01;

struct ToleranceBudget {
  // The cut's promise; NaN when samples= or spacing= chose its points.
  double tolerance = std::numeric_limits<double>::quiet_NaN();
  // The printed grid (LoweringOptions::coordinateIncrement; 0: none).
  double increment = 0;

  // How far rounding moves a point: half an increment on each of `axes`.
  double pointRounding(int axes = 3) const { return increment / 2 * std::sqrt(double(axes)); }
  // How far rounding moves an arc: its start, end and centre each by half an
  // increment in X and Y.
  double arcRounding() const { return 3.0 * std::sqrt(2.0) * increment / 2; }

  // The tolerance the cut's numbers are read within: its own, or the default.
  double toleranceOrDefault() const { return std::isnan(tolerance) ? defaultTolerance : tolerance; }
  // What is left for the chords between rounded points, and for arcs.
  double forPoints(int axes = 3) const { return tolerance - pointRounding(axes); }
  // What is left for the chords of uniform steps the controller counts: for
  // points, less a share of the increment for the rounding of the printed
  // literals (coefficients, the step); 0 when nothing is left.
  double forControllerSteps(int axes) const { return lessLiteralShare(forPoints(axes), increment); }
  double forArcs() const { return tolerance - arcRounding(); }

  // The spline model's error (spline_fitting.cpp): how accurately the
  // deviation of a modelled spline from the curve is measured, and how far
  // an analytic curve's stand-in, on which the fits search, may be off.
  double measurementAccuracy() const { return tolerance * 1e-3; }
  double standInError() const { return tolerance * 1e-4; }
  // What is left for a B spline's control points, which rounding moves the
  // spline by at most as much; and for the knots of a C or A spline, where
  // rounding a knot also turns its neighbours' tangents.
  double forSplineControlPoints() const {
    return tolerance - measurementAccuracy() - pointRounding();
  }
  double forSplineKnots() const { return tolerance - measurementAccuracy() - 3 * pointRounding(); }
};

} // namespace cncc::ir
