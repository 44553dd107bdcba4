// `expand-controller-loops`: each curve.lap whose table entry says how many
// uniform steps each region takes (CurveSampling::Steps) written out as the
// loops a controller runs: per region of N steps over its own parameter
// range [from, to], a loop i = 1 .. N whose body is the region's arithmetic
// at from + i (to - from) / N and a feed move there (a region of one step:
// its arithmetic at `to`, no loop). A ramp lap descends through each region
// by its share of the lap's length, in proportion to i / N. Nothing is
// tabled: the program computes every point, so the part's parameters stay
// editable at the machine.
#include "curve_lap_rewriter.h"

#include <map>

namespace cncc::ir {

namespace {

class ControllerLoopExpander : public LapRewriter {
public:
  using LapRewriter::LapRewriter;

private:
  bool writes(const CurveTableEntry& entry) const override {
    return entry.sampling == CurveSampling::Steps;
  }
  void writeLap(const Instruction& lap) override { expandLap(lap); }
  void writePoint(const Instruction& lap, const Instruction& point) override {
    feedToPoint(lap, point);
  }

  void expandLap(const Instruction& lap) {
    const CurveTableEntry& entry = source_.curves[lap.index];
    shares_ = isRamp(lap) ? &sharesOf(lap) : nullptr;
    std::size_t region = 0;
    for (const CurvePieceLayout& piece : entry.pieces) {
      int steps = entry.regionSteps[region];
      share_ = shares_ != nullptr ? (*shares_)[region] : LapRegionShare{};
      steps_ = steps;
      if (steps == 1) {
        replace(lap.result, constant(piece.to));
        rewriteRegion(lap.regions[region]);
      } else {
        emitLoop(lap, region, piece, steps);
      }
      ++region;
    }
  }

  const std::vector<LapRegionShare>& sharesOf(const Instruction& lap) {
    auto known = entryShares_.find(lap.index);
    if (known == entryShares_.end()) {
      known =
          entryShares_.emplace(lap.index, lapRegionShares(source_.curves[lap.index], *curveOf(lap)))
              .first;
    }
    return known->second;
  }

  // i = 1 .. steps, the region at from + i * step.
  void emitLoop(const Instruction& lap, std::size_t region, const CurvePieceLayout& piece,
                int steps) {
    ValueId first = constant(1);
    ValueId last = constant(steps);
    ValueId index = beginLapLoop(lap, first, last);
    double step = (piece.to - piece.from) / steps;
    Operand t = add({ValueId{}, piece.from}, multiply({index, 0}, {ValueId{}, step}));
    index_ = index;
    replace(lap.result, valueOf(t));
    rewriteRegion(lap.regions[region]);
    endRegions();
  }

  // The region's curve.point: a feed move there, raised by the lap's height
  // (on a ramp, from + (to - from) (before + share fraction)).
  void feedToPoint(const Instruction& lap, const Instruction& point) {
    std::vector<ValueId> operands = mappedOperands(point);
    Operand height = operandOf(mapped(lap.operands[1]));
    if (shares_ != nullptr) {
      Operand fraction =
          steps_ == 1
              ? Operand{ValueId{}, 1}
              : Operand{binary(Opcode::Div, {index_, 0}, {ValueId{}, static_cast<double>(steps_)}),
                        0};
      Operand done = add({ValueId{}, share_.before}, multiply({ValueId{}, share_.share}, fraction));
      Operand from = operandOf(mapped(lap.operands[0]));
      Operand rise = from.isNumber() && height.isNumber()
                         ? Operand{ValueId{}, height.number - from.number}
                         : Operand{binary(Opcode::Sub, height, from), 0};
      height = add(from, multiply(rise, done));
    }
    ValueId z = valueOf(add(height, operandOf(operands[2])));
    emitFeedMove(lap, operands[0], operands[1], z);
  }

  // A ramp lap's regions' shares (null on a level lap), and the region's;
  // the region's steps and its loop's index (the fraction done: i / steps).
  const std::vector<LapRegionShare>* shares_ = nullptr;
  LapRegionShare share_;
  int steps_ = 1;
  ValueId index_;
  std::map<std::uint32_t, std::vector<LapRegionShare>> entryShares_;
};

} // namespace

std::vector<LapStep> lapSteps(const CurveTableEntry& entry) {
  std::vector<LapStep> steps;
  std::size_t region = 0;
  for (const CurvePieceLayout& piece : entry.pieces) {
    int count = region < entry.regionSteps.size() ? entry.regionSteps[region] : 0;
    if (count == 1) {
      steps.push_back({region, piece.to, 1});
    } else {
      double step = (piece.to - piece.from) / count;
      for (int i = 1; i <= count; ++i) {
        steps.push_back({region, piece.from == 0 ? i * step : piece.from + i * step,
                         static_cast<double>(i) / count});
      }
    }
    ++region;
  }
  return steps;
}

bool expandControllerLoops(Function& function) {
  if (!hasCurveLap(function, CurveSampling::Steps)) {
    return false;
  }
  ControllerLoopExpander expander(function);
  function = expander.run();
  return true;
}

} // namespace cncc::ir
