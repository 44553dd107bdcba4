// The target's own curve blocks for a lap's curve, fitted where the
// legalisation write-curve-blocks writes a lap that names no table of them
// (and where the interpreter runs such a lap): the cubic spans of Heidenhain
// SPL blocks, the G06.2 block, and Sinumerik spline blocks. The lowering or
// choose-curve-blocks only says how (CurveSampling, the tolerance the blocks
// keep in `amount`, the printed grid in `grid`, a spline's kind and ends in
// `splineFit`).
#pragma once

#include "cncc/geom/nurbs_curve.h"
#include "cncc/ir/curve_table.h"
#include "cncc/ir/polynomial_move.h"
#include "cncc/ir/spline_fitting.h"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::ir {

// The cubic spans of a lap cut as PolynomialBlocks: exactly, a span per knot
// span, for a non-rational NURBS of degree 3 or less; else from a cubic
// B-spline fitted within the entry's amount. Every end on the entry's grid,
// each span starting where the one before ends. Throws CurveLapError at the
// cut when no spans follow the curve within the amount.
std::vector<PolynomialMove> lapPolynomialSpans(const CurveTableEntry& entry,
                                               const geom::Curve& curve);

// The Sinumerik spline a method= word asks for (bspline and nurbs a B
// spline); nullopt for a word that is not a spline's (linear).
std::optional<SplineKind> splineKindOfMethod(std::string_view method);

// Whether the curve lies in a plane z = constant (spline blocks' X and Y).
bool liesInPlane(const geom::Curve& curve);

// The NURBS block of a lap cut as NurbsBlocks that names no table: the
// curve itself where it is a NURBS of its own, else a cubic B-spline fitted
// within the entry's amount; its control points on the entry's grid, as move.nurbs's table and
// weight operands. Throws CurveLapError at the cut when none fits.
struct FittedNurbsBlock {
  std::vector<double> table;   // nurbsMoveTable's
  std::vector<double> weights; // one per control point
  bool own = false;            // the curve's own NURBS (its weights its own)
};
FittedNurbsBlock lapFittedNurbs(const CurveTableEntry& entry, const geom::Curve& curve);

// The Sinumerik spline blocks of a lap cut as SplineBlocks that names no
// table, fitted as the entry's splineFit says (spline_fitting.h) within its
// amount (0: through the chosen points samples= or spacing= chose), every
// number on its grid; an automatic start tangent to the last chord through
// the chosen points when a ramp leads in. Throws CurveLapError at the cut
// when no blocks keep the tolerance, or the fit asks more of the curve than
// maximumSplineFitEvaluations.
FittedSplineBlocks lapSplineBlocks(const CurveTableEntry& entry, const geom::Curve& curve);

// The warning for the transitions between consecutive spans that turn by
// more than the TNC's 0.1 degree, where the control stops exactly; nullopt
// when there are none.
std::optional<std::string> splineExactStops(const std::vector<PolynomialMove>& spans);

} // namespace cncc::ir
