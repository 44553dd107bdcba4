// Fitted arcs on a target that prints G02/G03 (LoweringOptions::arcBlocks:
// gcode, the macro targets and LinuxCNC). A cut that wants arcs (arcs=true, or
// --arcs without arcs=false) has its curve fitted once with tangent-
// continuous arcs (geom/arc_fitting.h) within its tolerance less the
// rounding of the printed numbers; each pass is a rapid over the start, a
// plunge (on the host, a ramp lap of chords) and the fit as move.arc and
// move.feed ops. Every coordinate and centre offset is on the printed grid
// already (coordinateIncrement), so the IR is the path the printed program
// makes. The arcs are the host's, so on a controller-side target a cut
// whose geometry depends on a part parameter keeps its controller loops,
// with an arcs-as-chords warning saying why.
#include "part_lowering.h"
#include "printed_grid.h"

#include "cncc/geom/arc_fitting.h"
#include "cncc/geom/evaluation_budget.h"
#include "cncc/geom/geometry_error.h"

#include <fmt/format.h>

#include <cmath>
#include <variant>

namespace cncc::ir::lowering {

using namespace frontend;

namespace {

std::optional<bool> arcsModifier(const CutStmt& cut) {
  const Expr* arcs = modifierValue(cut, "arcs");
  if (arcs != nullptr && arcs->kind == ExprKind::Bool) {
    return as<BoolExpr>(*arcs).value;
  }
  return std::nullopt;
}

Eigen::Vector2d onGrid(const Eigen::Vector3d& point, double increment) {
  return {onPrintedGrid(point.x(), increment), onPrintedGrid(point.y(), increment)};
}

// An arc too flat or too short to print as one: its sagitta is below half
// an increment, or its chord is under two increments (I J would be mostly
// rounding).
bool printsAsLine(const geom::ArcSegment& segment, double increment) {
  if (segment.kind == geom::ArcSegmentKind::Line) {
    return true;
  }
  double sagitta = segment.radius * (1.0 - std::cos(0.5 * std::fabs(segment.sweep)));
  double chord = (segment.end - segment.start).head<2>().norm();
  return sagitta < 0.5 * increment || chord < 2.0 * increment;
}

} // namespace

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
  if (std::optional<std::string> problem = geom::findArcFittingProblem(*curve.geometry)) {
    return *problem;
  }
  ToleranceBudget budget = toleranceBudget(cut);
  if (!(budget.tolerance > 2.0 * budget.arcRounding())) {
    return fmt::format("its tolerance {:g} leaves no room for rounding the arcs' centres to the "
                       "increment {:g}",
                       budget.tolerance, budget.increment);
  }
  try {
    // The biarc search asks a bounded number of points of the curve.
    geom::BudgetedCurve budgeted(*curve.geometry, maximumArcFitEvaluations);
    return geom::fitArcs(budgeted, {budget.forArcs()});
  } catch (const geom::EvaluationBudgetExceeded& error) {
    return fmt::format("fitting arcs within its tolerance asks more than {} points of the curve; "
                       "that is the limit of one cut's arc fit",
                       error.limit);
  } catch (const geom::GeometryError& error) {
    return std::string(error.what());
  }
}

bool PartLowering::lowerArcCut(const CutStmt& cut, const CutCurve& curve) {
  if (!options_.arcBlocks || !arcsModifier(cut).value_or(options_.arcsOnEveryCut)) {
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

  const std::vector<geom::ArcSegment>& segments = std::get<geom::ArcFit>(fitted).segments;
  double increment = options_.coordinateIncrement;
  Eigen::Vector2d start = onGrid(segments.front().start, increment);
  double planeZ = segments.front().start.z();
  std::vector<double> depths = passDepths(cut);
  double previous = 0;
  for (std::size_t k = 0; k < depths.size(); ++k) {
    PassScope pass(builder_, sweepPass(k, depths.size()));
    double passZ = beginPass(depths[k], depths.size());
    double entryZ = begun.ramp ? previous : passZ;
    builder_.rapid(builder_.constant(start.x()), builder_.constant(start.y()), safeValue);
    builder_.feed(builder_.constant(start.x()), builder_.constant(start.y()),
                  builder_.constant(onPrintedGrid(planeZ + entryZ, increment)), feedValue);
    if (begun.ramp) {
      PassScope rampLap(builder_, sweepPass(k, depths.size(), true));
      builder_.comment("ramp");
      for (std::size_t p = 0; p < rampTables.size(); ++p) {
        emitCurveLap(curve, *rampTables[p], entryZ, passZ, feedValue, cut, p, p + 1);
      }
    }
    Eigen::Vector2d end = emitArcLap(
        segments, builder_.constant(onPrintedGrid(planeZ + passZ, increment)), feedValue);
    builder_.rapid(builder_.constant(end.x()), builder_.constant(end.y()), safeValue);
    previous = passZ;
  }
  return true;
}

// One lap of the fitted arcs at height z from the fit's start on the grid;
// returns where it ends.
Eigen::Vector2d PartLowering::emitArcLap(const std::vector<geom::ArcSegment>& segments, ValueId z,
                                         ValueId feed) {
  double increment = options_.coordinateIncrement;
  Eigen::Vector2d at = onGrid(segments.front().start, increment);
  for (const geom::ArcSegment& segment : segments) {
    Eigen::Vector2d end = onGrid(segment.end, increment);
    if (end == at) {
      continue; // rounds to no movement
    }
    ValueId endX = builder_.constant(end.x());
    ValueId endY = builder_.constant(end.y());
    if (printsAsLine(segment, increment)) {
      builder_.feed(endX, endY, z, feed);
    } else {
      bool clockwise = segment.direction == geom::ArcDirection::Clockwise;
      builder_.arc(clockwise ? ArcTurn::Clockwise : ArcTurn::CounterClockwise, endX, endY, z,
                   builder_.constant(onPrintedGrid(segment.centre.x() - at.x(), increment)),
                   builder_.constant(onPrintedGrid(segment.centre.y() - at.y(), increment)), feed);
    }
    at = end;
  }
  return at;
}

} // namespace cncc::ir::lowering
