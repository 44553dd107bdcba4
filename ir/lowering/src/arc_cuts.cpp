// Fitted arcs on a target that prints G02/G03 (LoweringOptions::arcBlocks:
// gcode, the macro targets and LinuxCNC). A cut that wants arcs (arcs=true, or
// --arcs without arcs=false) has its curve fitted once with tangent-
// continuous arcs (geom/arc_fitting.h) within its tolerance less the
// rounding of the printed numbers; each pass is a rapid over the start, a
// plunge (on the host, a ramp lap of chords) and a curve.lap whose entry
// asks for arcs and holds the fit, which the fit-arcs legalisation writes
// out as move.arc and move.feed ops. Every coordinate and centre offset is
// on the printed grid (coordinateIncrement), so the IR is the path the
// printed program makes. The arcs are the host's, so on a controller-side
// target a cut whose geometry depends on a part parameter keeps its
// controller loops, with an arcs-as-chords warning saying why.
#include "part_lowering.h"

#include "cncc/geom/arc_fitting.h"
#include "cncc/ir/curve_lap.h"
#include "cncc/ir/printed_grid.h"

#include <fmt/format.h>

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
  return options_.arcBlocks && wanted.value_or(options_.arcsOnEveryCut);
}

// Why the cut cannot be printed as host-fitted arcs, before its curve is
// built; nullopt when nothing stands in the way.
std::optional<std::string> PartLowering::arcCutProblem(const CutStmt& cut) {
  if (modifierValue(cut, "samples") != nullptr || modifierValue(cut, "spacing") != nullptr) {
    return "samples= or spacing= chose its points; arcs are fitted within a tolerance=";
  }
  if (!options_.controllerLoops) {
    return std::nullopt; // the host evaluates everything at the values compiled with
  }
  if (rampEntry(cut)) {
    return "its entry=ramp laps are computed on the controller";
  }
  // A loop variable unrolls the loop: each copy's arcs are fitted.
  if (std::optional<ParameterUse> use = parameterUse(cut)) {
    return fmt::format("its {} depends on parameter '{}'", use->what, use->parameter);
  }
  return std::nullopt;
}

// The cut's curve as arcs within its tolerance less the printed rounding,
// or why it cannot be.
std::variant<geom::ArcFit, std::string> PartLowering::fitCutArcs(const CutStmt& cut,
                                                                 const CutCurve& curve) {
  if (std::optional<std::string> problem = arcCutProblem(cut)) {
    return *problem;
  }
  ToleranceBudget budget = toleranceBudget(cut);
  if (!(budget.tolerance > 2.0 * budget.arcRounding())) {
    return fmt::format("its tolerance {:g} leaves no room for rounding the arcs' centres to the "
                       "increment {:g}",
                       budget.tolerance, budget.increment);
  }
  try {
    return fitArcsWithinBudget(*curve.geometry, budget.forArcs(), cut.span, cut.curve->span);
  } catch (const CurveLapError& error) {
    return std::string(error.what());
  }
}

bool PartLowering::lowerArcCut(const CutStmt& cut, const CutCurve& curve) {
  if (!asksFittedArcs(cut)) {
    return false;
  }
  std::variant<geom::ArcFit, std::string> fitted = fitCutArcs(cut, curve);
  if (const std::string* problem = std::get_if<std::string>(&fitted)) {
    diagnostics_->report(DiagnosticKind::ArcsAsChords, cut.span,
                         fmt::format("this cut is printed as G01 chords, not arcs: {}", *problem));
    return false;
  }
  HostCut begun = beginHostCut(cut);
  // The ramp lap as chords: each piece a curve.lap of its own.
  std::vector<std::optional<std::uint32_t>> rampTables;
  if (begun.ramp) {
    checkRampCloses(curve, cut);
    rampTables = pieceCurveTables(cut, curve, rampSegments(curve, cut), false);
  }
  ValueId feedValue = arithmetic_.value(begun.feed);
  ValueId safeValue = arithmetic_.value(*safe_);
  beginCutMoves({curve.geometry, *chordTolerance(cut), cut.span, methodOf(cut), CutArcs::Fitted});

  // The level laps: curve.laps the fit-arcs legalisation writes out as the
  // fit made here (which decided the cut is printed as arcs).
  CurveTableEntry entry = wholeCurveTableEntry(cut, curve);
  entry.sampling = CurveSampling::Arcs;
  entry.amount = toleranceBudget(cut).forArcs();
  entry.grid = options_.coordinateIncrement;
  entry.fittedArcs =
      std::make_shared<const geom::ArcFit>(std::get<geom::ArcFit>(std::move(fitted)));
  LapArcs arcs = lapArcs(entry, *curve.geometry);
  std::uint32_t arcsTable = builder_.addCurve(std::move(entry));
  Eigen::Vector2d end = arcs.moves.empty() ? arcs.start : arcs.moves.back().end;

  double increment = options_.coordinateIncrement;
  std::vector<double> depths = passDepths(cut);
  double previous = 0;
  for (std::size_t k = 0; k < depths.size(); ++k) {
    PassScope pass(builder_, sweepPass(k, depths.size()));
    double passZ = beginPass(depths[k], depths.size());
    double entryZ = begun.ramp ? previous : passZ;
    builder_.rapid(builder_.constant(arcs.start.x()), builder_.constant(arcs.start.y()), safeValue);
    builder_.feed(builder_.constant(arcs.start.x()), builder_.constant(arcs.start.y()),
                  builder_.constant(onPrintedGrid(arcs.planeZ + entryZ, increment)), feedValue);
    if (begun.ramp) {
      PassScope rampLap(builder_, sweepPass(k, depths.size(), true));
      builder_.comment("ramp");
      for (std::size_t p = 0; p < rampTables.size(); ++p) {
        emitCurveLap(curve, *rampTables[p], entryZ, passZ, feedValue, cut, p, p + 1);
      }
    }
    emitCurveLap(curve, arcsTable, passZ, passZ, feedValue, cut);
    builder_.rapid(builder_.constant(end.x()), builder_.constant(end.y()), safeValue);
    previous = passZ;
  }
  return true;
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
