// Laps of a controller cut as curve.laps cut in steps (CurveSampling::
// Steps): the lowering plans each piece's (each knot span's) steps in
// controller_cuts.cpp, and the legalisation expand-controller-loops writes
// the loops (ir/src/curve_lap_loops.cpp).
#include "controller_segment.h"

namespace cncc::ir::lowering {

using namespace frontend;

// A curve table entry cutting each piece in the steps planned for it, when
// every piece (or knot span) is one the controller evaluates from the
// curve's own arithmetic at uniform steps (no arc, or span moved or split by
// parameters): a count chosen here, or the range and count the program
// computes of a piece that depends on parameters (its symbolic form);
// `budget` is the chord tolerance the counts keep (0: samples= gave them).
std::optional<PartLowering::SteppedLap>
PartLowering::steppedLap(const CutStmt& cut, const CutCurve& curve,
                         const std::vector<ControllerSegment>& segments, double budget) {
  for (const ControllerSegment& segment : segments) {
    bool uniform = !segment.isArc && !segment.split && !segment.stepPerPoint &&
                   segment.moved == nullptr && !(segment.isNurbs && segment.symbolic != nullptr);
    // A symbolic piece of one step (a line) folds its end point as the
    // region, at an opaque parameter, would not: it keeps its own form.
    bool counted =
        segment.symbolic != nullptr ? segment.steps != 1 : !segment.stepCount && segment.steps >= 1;
    if (!uniform || !counted) {
      return std::nullopt;
    }
  }
  CurveTableEntry entry = wholeCurveTableEntry(cut, curve);
  if (segments.size() != entry.regionCount()) {
    return std::nullopt;
  }
  entry.sampling = CurveSampling::Steps;
  entry.amount = budget;
  SteppedLap lap;
  for (const ControllerSegment& segment : segments) {
    entry.regionSteps.push_back(segment.symbolic != nullptr ? 0 : segment.steps);
    if (segment.symbolic != nullptr) {
      lap.computedSteps.push_back(arithmetic_.value(segment.start));
      lap.computedSteps.push_back(arithmetic_.value(segment.end));
      lap.computedSteps.push_back(arithmetic_.value(stepsOf(segment)));
    }
  }
  lap.table = builder_.addCurve(std::move(entry));
  return lap;
}

// The lap as a curve.lap: a symbolic piece's region computes its symbolic
// form, a knot span of more than one step its span cleaned of a constant
// weight (as the loop over it did), another its point as the host knows it.
void PartLowering::emitSteppedLap(const CutCurve& curve, const SteppedLap& lap,
                                  const std::vector<ControllerSegment>& segments, ValueId zFrom,
                                  ValueId zTo, ValueId feed, const CutStmt& cut) {
  std::vector<ValueId> operands = {zFrom, zTo, feed};
  operands.insert(operands.end(), lap.computedSteps.begin(), lap.computedSteps.end());
  std::size_t region = 0; // the regions are made in order, one per segment
  emitCurveLapAt(curve, lap.table, std::move(operands),
                 [&](std::size_t piece, std::size_t span, Scalar local) {
                   const ControllerSegment& segment = segments[region++];
                   const CurvePiece& own = curve.pieces[piece];
                   if (segment.symbolic != nullptr) {
                     return symbolicPointAt(*segment.symbolic, *own.value, local);
                   }
                   if (segment.isNurbs && segment.steps > 1) {
                     return transformed(own.transform,
                                        spanPointAt(cleanedSpan(own.spans[span]), local));
                   }
                   return pointAt(curve, piece, span, local, cut);
                 });
}

} // namespace cncc::ir::lowering
