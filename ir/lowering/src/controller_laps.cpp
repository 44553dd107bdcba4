// Laps of a controller cut as curve.laps cut in steps (CurveSampling::
// Steps): the lowering plans each piece's (each knot span's) steps in
// controller_cuts.cpp, and the legalisation expand-controller-loops writes
// the loops (ir/src/curve_lap_loops.cpp).
#include "controller_segment.h"

#include "cncc/geom/curve.h"
#include "cncc/geom/line_arc_curves.h"
#include "cncc/lowering/literal_rounding.h"

#include <fmt/format.h>

#include <cmath>

namespace cncc::ir::lowering {

using namespace frontend;

double PartLowering::measuredBudget(double budget) const {
  return lessLiteralShare(budget, options_.coordinateIncrement);
}

// The curve table entry cutting each piece (or knot span) as planned for
// it: uniform steps, a count chosen here or the range and count the
// program computes of a piece that depends on parameters (its symbolic
// form, a span counting its steps), or a count of a piece of its own
// the legalisation measures (stepsChosenByLegalisation); an arc's move.arc
// blocks; a walk. `budget` is the chord tolerance the counts keep less the
// printed rounding (0: samples= gave them).
PartLowering::SteppedLap PartLowering::steppedLap(const CutStmt& cut, const CutCurve& curve,
                                                  const std::vector<ControllerSegment>& segments,
                                                  double budget) {
  CurveTableEntry entry = wholeCurveTableEntry(cut, curve); // a region per segment
  entry.sampling = CurveSampling::Steps;
  entry.amount = measuredBudget(budget);
  SteppedLap lap;
  for (const ControllerSegment& segment : segments) {
    if (segment.isArc) {
      addArcRegion(entry, lap, segment, curve, cut);
      continue;
    }
    if (segment.stepPerPoint) {
      addWalkRegion(entry, lap, segment);
      continue;
    }
    bool computed = segment.symbolic != nullptr || countsItsSteps(segment);
    entry.regionSteps.push_back(computed ? 0 : segment.steps);
    if (segment.symbolic != nullptr) {
      lap.computedSteps.push_back(arithmetic_.value(segment.start));
      lap.computedSteps.push_back(arithmetic_.value(segment.end));
      lap.computedSteps.push_back(arithmetic_.value(stepsOf(segment)));
    } else if (computed) {
      Scalar count = stepsOf(segment);
      for (Scalar operand : {Scalar::of(0), count, count}) {
        lap.computedSteps.push_back(arithmetic_.value(operand));
      }
    }
  }
  entry.arcsAsked = arcsAsked_; // never with a ramp (arcCutProblem)
  if (blocksAskedBy(cut)) {
    entry.blocksAsked = true;
    entry.parameterWeights = ownWeightParameters(cut, curve);
  }
  lap.table = builder_.addCurve(std::move(entry));
  return lap;
}

// An arc's region is cut in its move.arc blocks: a constant arc's count in
// the entry (its parameter, the arc's length, runs over the piece's range),
// a symbolic arc's as an operand with its range 0 .. 1 (the fraction its
// symbolic form takes).
void PartLowering::addArcRegion(CurveTableEntry& entry, SteppedLap& lap,
                                const ControllerSegment& segment, const CutCurve& curve,
                                const CutStmt& cut) {
  const CurvePiece& piece = curve.pieces[segment.piece];
  ArcPath path = segment.symbolic != nullptr ? symbolicArcPath(*segment.symbolic, *piece.value)
                                             : constantArcPath(curve, segment.piece, cut);
  ArcBlocks blocks = arcBlocks(path, cut);
  entry.arcRegions.push_back(
      {entry.regionSteps.size(), blocks.counterClockwise, blocks.wholeTurns});
  if (segment.symbolic == nullptr) {
    entry.regionSteps.push_back(static_cast<int>(blocks.count.constant));
    return;
  }
  entry.regionSteps.push_back(0);
  for (Scalar operand : {Scalar::of(0), Scalar::of(1), blocks.count}) {
    lap.computedSteps.push_back(arithmetic_.value(operand));
  }
}

// The point of an arc's region and the offset from it to the centre.
LapRegionPoint PartLowering::arcRegionPoint(const CutCurve& curve, const ControllerSegment& segment,
                                            Scalar local, const CutStmt& cut) {
  const CurvePiece& own = curve.pieces[segment.piece];
  if (segment.symbolic != nullptr) {
    ArcPath path = symbolicArcPath(*segment.symbolic, *own.value);
    return {symbolicPointAt(*segment.symbolic, *own.value, local), path.toCentre(local)};
  }
  // At the angle the point is at (curves.cpp), so that the two share it.
  const auto& arc = static_cast<const geom::ArcCurve&>(*own.geometry);
  Affine direction = own.transform;
  direction.offset = Eigen::Vector2d::Zero();
  CurvePoint toCentre =
      radiusTowardsCentre(Scalar::of(own.value->arcRadius), Scalar::of(own.value->startAngle),
                          Scalar::of(arc.sweep() / arc.length()), local);
  return {pointAt(curve, segment.piece, 0, local, cut), transformed(direction, toCentre)};
}

// A rational span walked by a step computed at each point
// (rational_span_walk.cpp) over its u, 0 .. 1; its count, the most steps
// the walk takes, in the entry or an operand.
void PartLowering::addWalkRegion(CurveTableEntry& entry, SteppedLap& lap,
                                 const ControllerSegment& segment) {
  entry.walkRegions.push_back(entry.regionSteps.size());
  entry.regionSteps.push_back(segment.stepCount ? 0 : segment.steps);
  if (segment.stepCount) {
    for (Scalar operand : {Scalar::of(0), Scalar::of(1), *segment.stepCount}) {
      lap.computedSteps.push_back(arithmetic_.value(operand));
    }
  }
}

// A knot span split by parameters (its control points computed by the
// program), or moved by a scale the program computes, is cut at u = i / N
// (a quotient: no step rounded to the controller's digits adds up over the
// span): its region's parameter runs over 0 .. N (the range and count the
// lap's operands) and the region divides it by N.
bool PartLowering::countsItsSteps(const ControllerSegment& segment) {
  return segment.isNurbs && !segment.stepPerPoint &&
         (segment.split || (segment.moved != nullptr && segment.stepCount));
}

// A region's point at its parameter: an arc's with the offset to its centre,
// a symbolic piece's its symbolic form, a knot span of more than one step
// its span cleaned of a constant weight (as the loop over it did), moved as
// the program computes or at u = t / N (countsItsSteps), another its point
// as the host knows it.
LapRegionPoint PartLowering::steppedRegionPoint(const CutCurve& curve,
                                                const ControllerSegment& segment, Scalar local,
                                                const CutStmt& cut) {
  const CurvePiece& own = curve.pieces[segment.piece];
  if (segment.isArc) {
    return arcRegionPoint(curve, segment, local, cut);
  }
  if (segment.symbolic != nullptr && own.value->kind == CurveKind::Line) {
    return symbolicLineRegionPoint(*segment.symbolic, local);
  }
  if (segment.symbolic != nullptr) {
    return symbolicPointAt(*segment.symbolic, *own.value, local);
  }
  if (segment.stepPerPoint) {
    LapRegionPoint walked = movedSplitSpanPoint(segment, local);
    walked.walkStep = rationalSpanStep(segment, local, splitSpanDerivative(segment, local, 0));
    return walked;
  }
  if (countsItsSteps(segment)) {
    Scalar count = Scalar::of(arithmetic_.value(stepsOf(segment)), ValueType::F64);
    Scalar u = arithmetic_.binary(Opcode::Div, local, count);
    if (segment.split) {
      return movedSplitSpanPoint(segment, u);
    }
    return applied(*segment.moved, spanPointAt(cleanedSpan(own.spans[segment.span]), u));
  }
  // A constant span of more than one step: its polynomial in u, moved as
  // the program computes it, or as pointAt gives it (the cleaned span's).
  bool manySteps = segment.steps > 1 || segment.steps == stepsChosenByLegalisation;
  if (segment.isNurbs && manySteps && segment.moved != nullptr) {
    return applied(*segment.moved, spanPointAt(cleanedSpan(own.spans[segment.span]), local));
  }
  if (segment.isNurbs && !manySteps) {
    return nurbsSegmentPoint(curve, segment, local, cut);
  }
  return pointAt(curve, segment.piece, segment.span, local, cut);
}

// The lap as a curve.lap, its regions steppedRegionPoint's.
void PartLowering::emitSteppedLap(const CutCurve& curve, const SteppedLap& lap,
                                  const std::vector<ControllerSegment>& segments, ValueId zFrom,
                                  ValueId zTo, ValueId feed, const CutStmt& cut) {
  std::vector<ValueId> operands = {zFrom, zTo, feed};
  operands.insert(operands.end(), lap.computedSteps.begin(), lap.computedSteps.end());
  // The regions are made in order: one per segment, or beside the curve
  // one per segment and corner arc (controller_offset_laps.cpp).
  bool beside = !lap.besideRegions.empty();
  emitLapRegions(
      lap.table, std::move(operands), beside ? lap.besideRegions.size() : segments.size(),
      [&](std::size_t region, Scalar local) {
        return beside ? besideRegionPoint(curve, segments, lap.besideRegions[region], local, cut)
                      : steppedRegionPoint(curve, segments[region], local, cut);
      });
}

} // namespace cncc::ir::lowering
