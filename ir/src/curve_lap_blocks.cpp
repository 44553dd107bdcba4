// `write-curve-blocks`: each curve.lap cut as the target's own curve blocks
// (CurveSampling::NurbsBlocks, SplineBlocks or PolynomialBlocks) written
// out as the moves that print them: move.nurbs or move.spline on the
// entry's table of block data, or a move.polynomial per cubic span of it,
// at the lap's height and feed (a NURBS block's weights, the lap's
// operands after its three, carried over, so a weight that is a part
// parameter stays one). The lap's regions, the curve the blocks were fitted
// to, go: the blocks are what the controller cuts.
#include "curve_lap_rewriter.h"

#include <span>

namespace cncc::ir {

namespace {

class CurveBlockWriter : public LapRewriter {
public:
  using LapRewriter::LapRewriter;

private:
  bool writes(const CurveTableEntry& entry) const override { return entry.isBlocks(); }
  // The lap's regions are not rewritten: its move is the blocks'.
  void writePoint(const Instruction&, const Instruction& point) override { copy(point); }

  void writeLap(const Instruction& lap) override {
    const CurveTableEntry& entry = source_.curves[lap.index];
    if (isRamp(lap)) {
      throw CurveLapError(CurveLapError::Kind::DegenerateCurve, lap.span,
                          "a lap cut as curve blocks is level: its two heights must be one value");
    }
    if (entry.sampling == CurveSampling::PolynomialBlocks) {
      writeSpans(lap, *entry.blockTable);
      return;
    }
    Instruction move;
    move.opcode = entry.sampling == CurveSampling::NurbsBlocks ? Opcode::Nurbs : Opcode::Spline;
    move.index = entry.blockTable.value_or(0); // verified to be there
    move.span = lap.span;
    move.pass = lap.pass;
    std::vector<ValueId> operands;
    for (std::size_t k = 1; k < lap.operands.size(); ++k) {
      operands.push_back(mapped(lap.operands[k])); // height, feed, weights
    }
    emit(move, std::move(operands));
  }

  // A move.polynomial per cubic span of the table, its end raised by the
  // lap's height, its coefficients numbers.
  void writeSpans(const Instruction& lap, std::uint32_t table) {
    std::span<const double> spans = source_.tables[table];
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
};

} // namespace

// One rewrite writes out the laps of every kind of blocks.
bool writeCurveBlocks(Function& function) {
  return rewriteLaps<CurveBlockWriter>(function, CurveSampling::NurbsBlocks) ||
         rewriteLaps<CurveBlockWriter>(function, CurveSampling::SplineBlocks) ||
         rewriteLaps<CurveBlockWriter>(function, CurveSampling::PolynomialBlocks);
}

} // namespace cncc::ir
