// The Sinumerik spline blocks of one cut, fitted once (lapSplineBlocks,
// curve_blocks.h, for write-curve-blocks and the interpreter): the
// control points, weights PW and knot intervals PL of a BSPLINE, or the
// knots of a CSPLINE / ASPLINE, every number on the printed grid, such that
// the spline the controller builds from them (geom's models, as move.spline
// runs them) stays within the cut's ToleranceBudget.
#pragma once

#include "cncc/ir/tolerance_budget.h"

#include "cncc/geom/curve.h"
#include "cncc/geom/interpolating_splines.h"
#include "cncc/ir/spline_move.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace cncc::ir {

struct SplineFitRequest {
  const geom::Curve* curve = nullptr;
  SplineKind kind = SplineKind::BSpline;
  // Its tolerance NaN when samples= or spacing= chose `samples`.
  ToleranceBudget budget;
  // The cut's chosen points (the first is the start).
  std::vector<Eigen::Vector3d> samples;
  // A and C splines: how they start and end (a tangent start's direction
  // is the block's before it, as printed).
  geom::SplineTransitions transitions;
};

// How the fit went, for the program's comment and the cut's summary.
enum class SplineFitWay {
  Fitted,         // a spline fitted to the curve
  Samples,        // the cut's own points (samples= or spacing=)
  Exact,          // a NURBS as it is, its weights scaled
  Reparametrised, // a NURBS as it is, reparametrised for PW's range
  Refitted,       // a NURBS that could not be written as it is
};

struct FittedSplineBlocks {
  SplineBlockData data;
  Eigen::Vector3d start = Eigen::Vector3d::Zero(); // on the printed grid
  double deviation = 0;                            // of the modelled spline from the curve
  SplineFitWay way = SplineFitWay::Fitted;
  std::string note; // why a NURBS was re-fitted, or its reparametrisation
};

// The points (and derivatives) one cut's spline fit may ask of its curve.
inline constexpr std::size_t maximumSplineFitEvaluations = 5'000'000;

// Throws geom::GeometryError when no spline keeps the tolerance, and
// geom::EvaluationBudgetExceeded past maximumSplineFitEvaluations.
FittedSplineBlocks fitSplineBlocks(const SplineFitRequest& request);

// "; 6 BSPLINE control points, deviation 1.2e-07 mm, ..." without the ";".
std::string splineBlocksComment(const FittedSplineBlocks& blocks);

} // namespace cncc::ir
