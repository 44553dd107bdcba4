// The spline blocks of one cut: control points, weights and knot intervals
// of a BSPLINE, or the knots of a CSPLINE / ASPLINE, chosen so that the
// spline the controller builds from the printed numbers stays within the
// cut's tolerance.
#pragma once

#include "cncc/backends/sinumerik_writer.h"
#include "cncc/geom/curve.h"
#include "cncc/geom/interpolating_splines.h"

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace cncc::backends::sinumerik {

enum class SplineKind { BSpline, CSpline, ASpline };

struct SplineBlocks {
  SplineKind kind = SplineKind::BSpline;
  int degree = 3; // BSpline: SD
  // The points after the start (the start is where the tool already is):
  // control points of a BSPLINE, knots of a CSPLINE / ASPLINE.
  std::vector<Eigen::Vector3d> points;
  std::vector<double> weights;   // BSpline: PW per point
  std::vector<double> intervals; // BSpline: PL per point
  geom::SplineEndCondition start = geom::SplineEndCondition::Tangent;
  geom::SplineEndCondition end = geom::SplineEndCondition::Tangent;
  double deviation = 0; // of the spline from the curve, as modelled
  bool exact = false;
  std::string note;
};

struct SplineRequest {
  const geom::Curve* curve = nullptr;
  SplineKind kind = SplineKind::BSpline;
  // The cut's tolerance; NaN when samples= or spacing= chose `samples`.
  double tolerance = 0.01;
  // The cut's points as the lowering chose them (the first is the start).
  std::vector<Eigen::Vector3d> samples;
  // The XY direction of the block before the spline, if it moves in XY.
  std::optional<Eigen::Vector3d> startDirection;
  SinumerikTransitions transitions = SinumerikTransitions::Automatic;
  int decimals = 5;
};

// The largest distance rounding a point to `decimals` decimals moves it.
double roundingBound(int decimals);

// Rounds to `decimals` decimals, as the program prints it.
double roundTo(double value, int decimals);
Eigen::Vector3d roundPoint(const Eigen::Vector3d& point, int decimals);

// Throws geom::GeometryError when no spline can be found.
SplineBlocks chooseSplineBlocks(const SplineRequest& request);

} // namespace cncc::backends::sinumerik
