// A spline cut (method=cspline, aspline, bspline or nurbs) on a target
// with polynomial span blocks (LoweringOptions::polynomialBlocks: the
// Heidenhain TNC's SPL), of a curve that reads parameters or an offset the
// host computes (a curve of constants: choose-curve-blocks). Each pass (a
// trip of the controller's pass loop, depth= and step= editable) is a rapid
// over the curve's start on the printed grid, a plunge, and a curve.lap at
// the pass height whose entry asks for the cubic spans
// (CurveSampling::PolynomialBlocks) within the tolerance less the rounding
// of the end points, on the printed grid: the legalisation
// write-curve-blocks fits them (curve_blocks.h: exactly, one per knot span,
// for a non-rational NURBS of degree 3 or less; else from a cubic
// B-spline), writes a move.polynomial per span and warns of transitions
// that turn by more than the TNC's 0.1 degree, where the control stops
// exactly.
#include "part_lowering.h"

#include "cncc/ir/curve_blocks.h"
#include "cncc/ir/polynomial_move.h"
#include "cncc/ir/printed_grid.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

namespace cncc::ir::lowering {

using namespace frontend;

bool PartLowering::lowerPolynomialCut(const CutStmt& cut, const CutCurve* given) {
  const Modifier* method = findModifier(cut, "method");
  std::string word = method != nullptr && method->value ? wordOf(*method->value) : "";
  bool spline = word == "cspline" || word == "aspline" || word == "bspline" || word == "nurbs";
  if (!options_.polynomialBlocks || !spline || rampEntry(cut)) {
    return false;
  }
  if (!safe_) {
    fail(cut.span, "this cut has no safe height; write 'safe z=Z' before it",
         DiagnosticKind::NoSafeHeight);
  }
  Scalar feed = cutFeed(cut);
  CutCurve curve = given != nullptr ? *given : cutCurve(cut);
  fixParameters(*cut.curve, cut.curve->span, "this curve's points");
  ToleranceBudget budget = blocksBudget(cut, "spline end points");
  ValueId feedValue = arithmetic_.value(feed);
  ValueId safeValue = arithmetic_.value(*safe_);
  CutGeometry geometry;
  geometry.curve = curve.geometry;
  geometry.tolerance = chordTolerance(cut).value_or(std::numeric_limits<double>::quiet_NaN());
  geometry.span = cut.span;
  geometry.method = word;
  bool activatesLengthOffset = beginCutMoves(geometry);

  CurveTableEntry entry = blocksTableEntry(cut, curve, CurveSampling::PolynomialBlocks,
                                           std::nullopt, budget.forPoints());
  entry.grid = budget.increment;
  std::uint32_t spansTable = builder_.addCurve(std::move(entry));
  auto [first, last] = curveEndsOnGrid(*curve.geometry, budget.increment);
  // The passes (the controller's loop: depth= and step= stay editable), each
  // a lap at the pass height, which write-curve-blocks writes out as a
  // move.polynomial per span.
  std::array<ValueId, 2> finish{builder_.constant(last.x()), builder_.constant(last.y())};
  SweepStart from{builder_.constant(first.x()), builder_.constant(first.y()), safeValue,
                  activatesLengthOffset, Scalar::of(first.z())};
  emitSweep(cut, false, from, finish, feedValue, [&](ValueId zFrom, ValueId zTo) {
    emitCurveLap(curve, spansTable, zFrom, zTo, feedValue, cut);
  });
  return true;
}

} // namespace cncc::ir::lowering
