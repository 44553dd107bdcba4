// method=bspline, nurbs, cspline or aspline on a target that prints
// Sinumerik spline blocks (LoweringOptions::splineBlocks), of a curve that
// reads parameters or an offset the host computes (a curve of constants:
// choose-curve-blocks). Each pass is a
// rapid over the curve's start, a plunge (and the ramp lap's chords with
// entry=ramp) and a curve.lap at the pass height whose entry asks for the
// blocks (CurveSampling::SplineBlocks: their kind and ends, the cut's
// tolerance, the printed grid, the points chosen for the cut), which the
// legalisation write-curve-blocks fits once and writes out as the blocks'
// comment and one move.spline; then a retract. A curve that does not lie
// in one plane z = constant (the spline axes are X and Y) is cut as chords.
#include "part_lowering.h"

#include "cncc/ir/curve_blocks.h"
#include "cncc/ir/printed_grid.h"
#include "cncc/ir/spline_move.h"

#include <cmath>
#include <limits>

namespace cncc::ir::lowering {

using namespace frontend;

bool PartLowering::lowerSplineCut(const CutStmt& cut, const CutCurve& curve) {
  std::optional<SplineKind> kind = splineKindOfMethod(methodOf(cut));
  if (!options_.splineBlocks || !kind || !liesInPlane(*curve.geometry)) {
    return false;
  }
  auto [feed, ramp] = beginHostCut(cut);
  geom::CurveSamples samples = checkedSamplesFor(cut, *curve.geometry);
  if (ramp) {
    checkRampCloses(curve, cut);
  }
  auto chosen = std::make_shared<const std::vector<double>>(samples.parameters);
  CurveTableEntry blocks = blocksTableEntry(cut, curve, CurveSampling::SplineBlocks, std::nullopt,
                                            toleranceBudget(cut).tolerance);
  blocks.grid = options_.coordinateIncrement;
  blocks.splineFit = SplineBlocksFit{*kind, options_.splineEnds, ramp};
  if (blocks.amount == 0 || ramp) {
    blocks.chosenParameters = chosen; // the points the blocks go through, or the ramp's
  }
  std::uint32_t blocksEntry = builder_.addCurve(std::move(blocks));

  ValueId feedValue = arithmetic_.value(feed);
  ValueId safeValue = arithmetic_.value(*safe_);
  CutGeometry geometry{curve.geometry,
                       chordTolerance(cut).value_or(std::numeric_limits<double>::quiet_NaN()),
                       cut.span, methodOf(cut)};
  bool activatesLengthOffset = beginCutMoves(std::move(geometry));
  // The ramp's lap as chords through the points the blocks are fitted to.
  std::optional<std::uint32_t> rampTable;
  if (ramp) {
    CurveTableEntry entry = curveTableEntry(cut, curve);
    entry.chosenParameters = chosen;
    rampTable = builder_.addCurve(std::move(entry));
  }
  auto lap = [&](ValueId zFrom, ValueId zTo) {
    if (zFrom != zTo) {
      emitCurveLap(curve, *rampTable, zFrom, zTo, feedValue, cut);
    } else {
      emitCurveLap(curve, blocksEntry, zTo, zTo, feedValue, cut);
    }
  };
  // The blocks start and end where the curve does, on the printed grid.
  auto [first, last] = curveEndsOnGrid(*curve.geometry, options_.coordinateIncrement);
  SweepStart from{builder_.constant(first.x()), builder_.constant(first.y()), safeValue,
                  activatesLengthOffset, Scalar::of(first.z())};
  emitSweep(cut, ramp, from, {builder_.constant(last.x()), builder_.constant(last.y())}, feedValue,
            lap);
  return true;
}

} // namespace cncc::ir::lowering
