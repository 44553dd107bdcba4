// `write-curve-blocks`: each curve.lap cut as the target's own curve blocks
// (CurveSampling::NurbsBlocks, SplineBlocks or PolynomialBlocks) written
// out as the moves that print them: move.nurbs or move.spline on the
// entry's table of block data, or a move.polynomial per cubic span of it,
// at the lap's height and feed (a NURBS block's weights, the lap's
// operands after its three, carried over). The lap's regions, the curve
// the blocks were fitted to, go: the blocks are what the controller cuts.
// An entry that names no table has its blocks fitted here, once
// (curve_blocks.h): the spans of SPL blocks (a spline whose transitions
// make the TNC stop exactly a warning of the function), the G06.2 block (a
// NURBS of its own itself, a weight that is a part parameter read as that
// parameter, CurveTableEntry::parameterWeights, so the operator's edit
// reaches it; any other curve a fitted B-spline), a table of the function
// with its weights, or Sinumerik spline blocks (a table, and how they were
// found a comment before each move.spline and the cut's splineBlocks).
#include "cncc/ir/curve_blocks.h"

#include "curve_lap_rewriter.h"

#include <map>
#include <span>

namespace cncc::ir {

namespace {

class CurveBlockWriter : public LapRewriter {
public:
  using LapRewriter::LapRewriter;

private:
  bool writes(std::uint32_t curve) const override { return source_.curves[curve].isBlocks(); }
  // The lap's regions are not rewritten: its move is the blocks'.
  void writePoint(const Instruction&, const Instruction& point) override { copy(point); }

  void writeLap(const Instruction& lap) override {
    const CurveTableEntry& entry = source_.curves[lap.index];
    if (isRamp(lap)) {
      throw CurveLapError(CurveLapError::Kind::DegenerateCurve, lap.span,
                          "a lap cut as curve blocks is level: its two heights must be one value");
    }
    if (entry.sampling == CurveSampling::PolynomialBlocks) {
      writeSpans(lap, entry.blockTable ? std::span<const double>(source_.tables[*entry.blockTable])
                                       : std::span<const double>(fittedSpans(lap)));
      return;
    }
    if (entry.sampling == CurveSampling::SplineBlocks && !entry.blockTable) {
      writeFittedSpline(lap);
      return;
    }
    Instruction move;
    move.opcode = entry.sampling == CurveSampling::NurbsBlocks ? Opcode::Nurbs : Opcode::Spline;
    const FittedNurbs* fitted = entry.blockTable ? nullptr : &fittedNurbs(lap);
    move.index = fitted != nullptr ? fitted->table : *entry.blockTable;
    move.span = lap.span;
    move.pass = lap.pass;
    std::vector<ValueId> operands;
    for (std::size_t k = 1; k < lap.operands.size(); ++k) {
      operands.push_back(mapped(lap.operands[k])); // height, feed, weights
    }
    for (std::size_t k = 0; fitted != nullptr && k < fitted->weights.size(); ++k) {
      operands.push_back(fitted->own ? weight(entry, k, fitted->weights[k])
                                     : constant(fitted->weights[k])); // the fitted B-spline's
    }
    emit(move, std::move(operands));
  }

  // A NURBS block's weight k: the part parameter it is, or its number.
  ValueId weight(const CurveTableEntry& entry, std::size_t k, double number) {
    for (const CurveTableEntry::ParameterWeight& weight : entry.parameterWeights) {
      if (weight.point == k) {
        Instruction parameter;
        parameter.opcode = Opcode::Param;
        parameter.index = weight.parameter;
        return emit(parameter, {});
      }
    }
    return constant(number);
  }

  // The table of cubic spans fitted to the lap's curve (once per entry),
  // and its warning once.
  const std::vector<double>& fittedSpans(const Instruction& lap) {
    auto known = fitted_.find(lap.index);
    if (known == fitted_.end()) {
      const CurveTableEntry& entry = source_.curves[lap.index];
      std::vector<PolynomialMove> spans = lapPolynomialSpans(entry, *curveOf(lap));
      if (std::optional<std::string> stops = splineExactStops(spans)) {
        output_.warnings.push_back(
            {LegalisationWarning::Kind::SplineExactStop, entry.cutSpan, *stops});
      }
      known = fitted_.emplace(lap.index, polynomialMoveTable(spans)).first;
    }
    return known->second;
  }

  struct FittedNurbs {
    std::uint32_t table = 0;
    std::vector<double> weights; // one per control point
    bool own = false;            // the curve's own: its parameter weights too
  };

  // The NURBS block fitted to the lap's curve (once per entry), its data a
  // table of the function.
  const FittedNurbs& fittedNurbs(const Instruction& lap) {
    auto known = nurbs_.find(lap.index);
    if (known == nurbs_.end()) {
      FittedNurbsBlock block = lapFittedNurbs(source_.curves[lap.index], *curveOf(lap));
      output_.tables.push_back(std::move(block.table));
      FittedNurbs fitted{static_cast<std::uint32_t>(output_.tables.size() - 1),
                         std::move(block.weights), block.own};
      known = nurbs_.emplace(lap.index, std::move(fitted)).first;
    }
    return known->second;
  }

  struct FittedSpline {
    std::uint32_t table = 0;
    std::string comment; // how they were found
  };

  // The spline blocks fitted to the lap's curve (once per entry), their
  // comment before the move.spline and in the cut's summary (CutGeometry).
  void writeFittedSpline(const Instruction& lap) {
    auto known = splines_.find(lap.index);
    if (known == splines_.end()) {
      FittedSplineBlocks blocks = lapSplineBlocks(source_.curves[lap.index], *curveOf(lap));
      output_.tables.push_back(splineMoveTable(blocks.data));
      FittedSpline fitted{static_cast<std::uint32_t>(output_.tables.size() - 1),
                          splineBlocksComment(blocks)};
      known = splines_.emplace(lap.index, std::move(fitted)).first;
    }
    const FittedSpline& fitted = known->second;
    if (std::optional<std::uint32_t> cut = currentCut(); cut && *cut < output_.cuts.size()) {
      output_.cuts[*cut].splineBlocks = fitted.comment;
    }
    Instruction comment;
    comment.opcode = Opcode::Comment;
    comment.text = fitted.comment;
    comment.span = lap.span;
    comment.pass = lap.pass;
    emit(comment, {});
    Instruction move;
    move.opcode = Opcode::Spline;
    move.index = fitted.table;
    move.span = lap.span;
    move.pass = lap.pass;
    emit(move, {mapped(lap.operands[1]), mapped(lap.operands[2])});
  }

  // A move.polynomial per cubic span of the table, its end raised by the
  // lap's height, its coefficients numbers.
  void writeSpans(const Instruction& lap, std::span<const double> spans) {
    Operand height = operandOf(mapped(lap.operands[1]));
    for (std::size_t at = 0; at + 12 <= spans.size(); at += 12) {
      Instruction move;
      move.opcode = Opcode::Polynomial;
      move.span = lap.span;
      move.pass = lap.pass;
      std::vector<ValueId> operands = {constant(spans[at]), constant(spans[at + 1]),
                                       valueOf(add(height, Operand{ValueId{}, spans[at + 2]}))};
      for (std::size_t k = 3; k < 12; ++k) {
        operands.push_back(constant(spans[at + k]));
      }
      operands.push_back(mapped(lap.operands[2]));
      emit(move, std::move(operands));
    }
  }

  std::map<std::uint32_t, std::vector<double>> fitted_; // spans by curve
  std::map<std::uint32_t, FittedNurbs> nurbs_;          // by curve
  std::map<std::uint32_t, FittedSpline> splines_;       // by curve
};

} // namespace

// One rewrite writes out the laps of every kind of blocks.
bool writeCurveBlocks(Function& function) {
  return rewriteLaps<CurveBlockWriter>(function, CurveSampling::NurbsBlocks) ||
         rewriteLaps<CurveBlockWriter>(function, CurveSampling::SplineBlocks) ||
         rewriteLaps<CurveBlockWriter>(function, CurveSampling::PolynomialBlocks);
}

} // namespace cncc::ir
