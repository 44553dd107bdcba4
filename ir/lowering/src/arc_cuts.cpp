// Fitted arcs (LoweringOptions::fittedArcs: every target prints G02/G03
// or its dialect's circles). A cut that wants arcs (arcs=true,
// or --arcs without arcs=false) is lowered as any other (host chords, or
// controller loops), its level laps' entry asking for arcs within its
// tolerance less the rounding of the printed ends and centres, on the
// printed grid (ArcsAsked); the legalisation fit-arcs fits the curve and
// writes the arcs, or warns and leaves the laps to their expansion. What
// the cut itself stands in the way of is reported here: samples= or
// spacing=, and on a controller-side target a ramp or a curve that depends
// on a part parameter (the arcs are the host's numbers), or a tolerance
// that leaves no room for the grid.
#include "part_lowering.h"

#include "cncc/geom/arc_fitting.h"
#include "cncc/ir/curve_lap.h"
#include "cncc/ir/printed_grid.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <variant>

namespace cncc::ir::lowering {

using namespace frontend;

bool PartLowering::asksFittedArcs(const CutStmt& cut) {
  std::optional<bool> wanted;
  if (const Expr* arcs = modifierValue(cut, "arcs");
      arcs != nullptr && arcs->kind == ExprKind::Bool) {
    wanted = as<BoolExpr>(*arcs).value;
  }
  return options_.fittedArcs && wanted.value_or(options_.arcsOnEveryCut);
}

// Why the cut cannot be printed as host-fitted arcs, before its curve is
// built; nullopt when nothing stands in the way.
std::optional<std::string> PartLowering::arcCutProblem(const CutStmt& cut) {
  if (modifierValue(cut, "samples") != nullptr || modifierValue(cut, "spacing") != nullptr) {
    return "samples= or spacing= chose its points; arcs are fitted within a tolerance=";
  }
  if (options_.controllerLoops) {
    if (rampEntry(cut)) {
      return "its entry=ramp laps are computed on the controller";
    }
    // A loop variable unrolls the loop: each copy's arcs are fitted. The
    // arcs' height is the sweep's pass loop's: depth= and step= may read
    // parameters, the curve not.
    if (std::optional<ParameterUse> use = parameterUse(cut)) {
      return fmt::format("its {} depends on parameter '{}'", use->what, use->parameter);
    }
  } // the host evaluates everything at the values compiled with
  ToleranceBudget budget = toleranceBudget(cut);
  if (!(budget.tolerance > 2.0 * budget.arcRounding())) {
    return fmt::format("its tolerance {:g} leaves no room for rounding the arcs' centres to the "
                       "increment {:g}",
                       budget.tolerance, budget.increment);
  }
  return std::nullopt;
}

void PartLowering::reportArcsAsChords(const CutStmt& cut, std::string_view problem) {
  diagnostics_->report(DiagnosticKind::ArcsAsChords, cut.span, arcsAsChordsMessage(problem));
}

std::optional<ArcsAsked> PartLowering::arcsAskedBy(const CutStmt& cut) {
  if (!asksFittedArcs(cut)) {
    return std::nullopt;
  }
  if (std::optional<std::string> problem = arcCutProblem(cut)) {
    reportArcsAsChords(cut, *problem);
    return std::nullopt;
  }
  return ArcsAsked{toleranceBudget(cut).forArcs(), options_.coordinateIncrement,
                   largestCoordinateInUnits()};
}

// One lap of arcs at height z from their start on the grid; returns where
// it ends.
Eigen::Vector2d PartLowering::emitArcLap(const std::vector<geom::ArcSegment>& segments, ValueId z,
                                         ValueId feed) {
  LapArcs arcs = arcMovesOnGrid(segments, options_.coordinateIncrement);
  for (const LapArcMove& move : arcs.moves) {
    ValueId endX = builder_.constant(move.end.x());
    ValueId endY = builder_.constant(move.end.y());
    if (move.turn) {
      builder_.arc(*move.turn, endX, endY, z, builder_.constant(move.centreOffset.x()),
                   builder_.constant(move.centreOffset.y()), feed);
    } else {
      builder_.feed(endX, endY, z, feed);
    }
  }
  return arcs.moves.empty() ? arcs.start : arcs.moves.back().end;
}

} // namespace cncc::ir::lowering
