// `fit-arcs`: each curve.lap whose table entry asks for arcs
// (CurveSampling::Arcs) written out as the fit's move.arc and move.feed
// ops. The curve is fitted once per entry with tangent-continuous arcs and
// lines (geom/arc_fitting.h) within the entry's tolerance, which already
// leaves room for the rounding of every end and centre to the printed grid;
// the interpreter runs an arcs lap with the same moves (lapArcs).
#include "cncc/ir/curve_lap.h"
#include "cncc/ir/printed_grid.h"

#include "cncc/geom/arc_fitting.h"
#include "cncc/geom/discretisation.h"
#include "cncc/geom/evaluation_budget.h"
#include "cncc/geom/geometry_error.h"

#include "curve_lap_rewriter.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <variant>

namespace cncc::ir {

namespace {

Eigen::Vector2d onGrid(const Eigen::Vector3d& point, double grid) {
  return {onPrintedGrid(point.x(), grid), onPrintedGrid(point.y(), grid)};
}

// An arc too flat or too short to print as one: its sagitta is below half
// a grid step, or its chord is under two (I J would be mostly rounding).
bool printsAsLine(const geom::ArcSegment& segment, double grid) {
  if (segment.kind == geom::ArcSegmentKind::Line) {
    return true;
  }
  double sagitta = segment.radius * (1.0 - std::cos(0.5 * std::fabs(segment.sweep)));
  double chord = (segment.end - segment.start).head<2>().norm();
  return sagitta < 0.5 * grid || chord < 2.0 * grid;
}

class ArcLapFitter : public LapRewriter {
public:
  explicit ArcLapFitter(const Function& source) : LapRewriter(source) { decideAskedArcs(); }

private:
  bool writes(std::uint32_t curve) const override {
    return source_.curves[curve].sampling == CurveSampling::Arcs || arcs_.contains(curve);
  }
  void writeLap(const Instruction& lap) override { writeArcs(lap); }
  // The lap's regions are not rewritten: its moves are the fit's.
  void writePoint(const Instruction&, const Instruction& point) override { copy(point); }

  // Each entry that asks for arcs fitted once, at the first of its laps:
  // the fit's moves, or the arcs-as-chords warning and the entry left to
  // its own expansion, asking no more (so a later lap skips it either way).
  void decideAskedArcs() {
    for (const Instruction& lap : source_.instructions) {
      if (lap.opcode != Opcode::CurveLap || !output_.curves[lap.index].arcsAsked ||
          arcs_.contains(lap.index)) {
        continue;
      }
      const CurveTableEntry& entry = source_.curves[lap.index];
      std::variant<LapArcs, std::string> fitted = askedLapArcs(entry, *curveOf(lap));
      if (LapArcs* arcs = std::get_if<LapArcs>(&fitted)) {
        arcs_.emplace(lap.index, std::move(*arcs));
        continue;
      }
      output_.curves[lap.index].arcsAsked.reset();
      output_.warnings.push_back({LegalisationWarning::Kind::ArcsAsChords, entry.cutSpan,
                                  arcsAsChordsMessage(std::get<std::string>(fitted))});
    }
  }

  // The lap's height plus the plane's: a number where the height is one.
  ValueId heightOf(const Instruction& lap, double planeZ) {
    if (isRamp(lap)) {
      throw CurveLapError(CurveLapError::Kind::DegenerateCurve, lap.span,
                          "a lap cut as arcs is level: its two heights must be one value");
    }
    ValueId to = lap.operands[1];
    std::optional<double> height = passes::constantValue(source_, to);
    if (height) {
      return constant(*height + planeZ);
    }
    if (planeZ == 0) {
      return mapped(to);
    }
    Instruction add;
    add.opcode = Opcode::Add;
    return emit(add, {mapped(to), constant(planeZ)});
  }

  void writeArcs(const Instruction& lap) {
    auto known = arcs_.find(lap.index);
    if (known == arcs_.end()) {
      known = arcs_.emplace(lap.index, lapArcs(source_.curves[lap.index], *curveOf(lap))).first;
    }
    if (std::optional<std::uint32_t> cut = currentCut(); cut && *cut < output_.cuts.size()) {
      output_.cuts[*cut].arcMoves = CutArcs::Fitted;
    }
    const LapArcs& arcs = known->second;
    ValueId z = heightOf(lap, arcs.planeZ);
    ValueId feed = mapped(lap.operands[2]);
    for (const LapArcMove& move : arcs.moves) {
      Instruction instruction;
      instruction.opcode = move.turn ? Opcode::Arc : Opcode::Feed;
      std::vector<ValueId> operands = {constant(move.end.x()), constant(move.end.y()), z};
      if (move.turn) {
        instruction.index = static_cast<std::uint32_t>(*move.turn);
        operands.push_back(constant(move.centreOffset.x()));
        operands.push_back(constant(move.centreOffset.y()));
      }
      operands.push_back(feed);
      emit(instruction, std::move(operands));
    }
  }

  std::map<std::uint32_t, LapArcs> arcs_;
};

} // namespace

LapArcs arcMovesOnGrid(const std::vector<geom::ArcSegment>& segments, double grid) {
  LapArcs arcs;
  if (segments.empty()) {
    return arcs;
  }
  arcs.start = onGrid(segments.front().start, grid);
  arcs.planeZ = segments.front().start.z();
  Eigen::Vector2d at = arcs.start;
  for (const geom::ArcSegment& segment : segments) {
    LapArcMove move;
    move.end = onGrid(segment.end, grid);
    if (move.end == at) {
      continue; // rounds to no movement
    }
    if (!printsAsLine(segment, grid)) {
      move.turn = segment.direction == geom::ArcDirection::Clockwise ? ArcTurn::Clockwise
                                                                     : ArcTurn::CounterClockwise;
      move.centreOffset = {onPrintedGrid(segment.centre.x() - at.x(), grid),
                           onPrintedGrid(segment.centre.y() - at.y(), grid)};
    }
    arcs.moves.push_back(move);
    at = move.end;
  }
  return arcs;
}

geom::ArcFit fitArcsWithinBudget(const geom::Curve& curve, const geom::ArcFitOptions& options,
                                 frontend::SourceSpan cutSpan, frontend::SourceSpan curveSpan) {
  if (std::optional<std::string> problem = geom::findArcFittingProblem(curve)) {
    throw CurveLapError(CurveLapError::Kind::DegenerateCurve, curveSpan, *problem);
  }
  try {
    // The fit measures the curve at least as densely as chords within the
    // tolerance: a curve whose chords are well past the budget (a polar
    // range of 1e300) is refused at once, not after the budget's seconds.
    double chords = geom::estimateDiscretisation(curve, options.tolerance).chords;
    if (chords > 2.0 * static_cast<double>(maximumArcFitEvaluations)) {
      throw geom::EvaluationBudgetExceeded(maximumArcFitEvaluations);
    }
    geom::BudgetedCurve budgeted(curve, maximumArcFitEvaluations);
    return geom::fitArcs(budgeted, options);
  } catch (const geom::EvaluationBudgetExceeded& error) {
    throw CurveLapError(CurveLapError::Kind::ProgramTooLarge, cutSpan,
                        fmt::format("fitting arcs within its tolerance asks more than {} points "
                                    "of the curve; that is the limit of one cut's arc fit",
                                    error.limit));
  } catch (const geom::GeometryError& error) {
    throw CurveLapError(CurveLapError::Kind::DegenerateCurve, curveSpan, error.what());
  }
}

namespace {

LapArcs arcsOfFit(const geom::ArcFit& fit, double grid, frontend::SourceSpan curveSpan) {
  if (fit.segments.empty()) {
    throw CurveLapError(CurveLapError::Kind::DegenerateCurve, curveSpan,
                        "the arcs fitted to this curve are none");
  }
  return arcMovesOnGrid(fit.segments, grid);
}

} // namespace

LapArcs lapArcs(const CurveTableEntry& entry, const geom::Curve& curve) {
  return arcsOfFit(fitArcsWithinBudget(curve, {entry.amount}, entry.cutSpan, entry.curveSpan),
                   entry.grid, entry.curveSpan);
}

std::variant<LapArcs, std::string> askedLapArcs(const CurveTableEntry& entry,
                                                const geom::Curve& curve) {
  const ArcsAsked& asked = *entry.arcsAsked;
  try {
    geom::ArcFitOptions options{asked.tolerance, asked.largestRadius};
    return arcsOfFit(fitArcsWithinBudget(curve, options, entry.cutSpan, entry.curveSpan),
                     asked.grid, entry.curveSpan);
  } catch (const CurveLapError& error) {
    return std::string(error.what());
  }
}

std::string arcsAsChordsMessage(std::string_view problem) {
  return fmt::format("this cut is printed as G01 chords, not arcs: {}", problem);
}

bool fitLapArcs(Function& function) {
  bool asked = std::any_of(function.curves.begin(), function.curves.end(),
                           [](const CurveTableEntry& entry) { return entry.arcsAsked; });
  if (!asked && !hasCurveLap(function, CurveSampling::Arcs)) {
    return false;
  }
  ArcLapFitter fitter(function);
  function = fitter.run();
  return true;
}

} // namespace cncc::ir
