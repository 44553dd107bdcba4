// What the legalisations of curve.lap share: a Rewriter that visits the laps
// a legalisation writes out, writes their moves with the lowering's folding
// of numbers (x + 0, x - 0, x * 1 and x / 1 are x, x / x is 1, two numbers
// their result), and reads the values a lap's curve takes from outside it at the
// values compiled with.
#pragma once

#include "cncc/ir/curve_lap.h"

#include "compiled_values.h"
#include "lap_cuts.h"
#include "passes/evaluate.h"
#include "passes/rewriter.h"

#include <cstdint>
#include <initializer_list>
#include <unordered_set>
#include <vector>

namespace cncc::ir {

// Whether a curve.lap of the function is cut as `sampling` says (any lap:
// nullopt).
inline bool hasCurveLap(const Function& function,
                        std::optional<CurveSampling> sampling = std::nullopt) {
  for (const Instruction& instruction : function.instructions) {
    if (instruction.opcode == Opcode::CurveLap &&
        (!sampling || function.curves[instruction.index].sampling == *sampling)) {
      return true;
    }
  }
  return false;
}

// Runs the legalisation `Rewrite` (a LapRewriter) over the function when it
// has a lap cut as `sampling` says; whether it did.
template <class Rewrite> bool rewriteLaps(Function& function, CurveSampling sampling) {
  if (!hasCurveLap(function, sampling)) {
    return false;
  }
  Rewrite rewrite(function);
  function = rewrite.run();
  return true;
}

class LapRewriter : public passes::Rewriter {
public:
  using Rewriter::Rewriter;

protected:
  // Whether this legalisation writes out the laps of the curve table's
  // entry `curve` (writeLap); the others are copied as they are.
  virtual bool writes(std::uint32_t curve) const = 0;
  virtual void writeLap(const Instruction& lap) = 0;
  // A curve.point of the lap being written, met where writeLap rewrites
  // one of its regions.
  virtual void writePoint(const Instruction& lap, const Instruction& point) = 0;

  void visit(const Instruction& instruction) final {
    bool ends = endsLapRegion(instruction.opcode);
    if (slicing_ && !ends && !kept_.contains(instructionIdOf(instruction))) {
      return; // not needed by the operands of the region's end being written
    }
    if (instruction.opcode == Opcode::CutBegin) {
      cut_ = instruction.index;
    }
    if (instruction.opcode == Opcode::CurveLap && writes(instruction.index)) {
      const Instruction* outer = lap_;
      lap_ = &instruction;
      writeLap(instruction);
      lap_ = outer;
      markChanged();
    } else if (ends && lap_ != nullptr) {
      writePoint(*lap_, instruction);
    } else {
      copy(instruction);
    }
  }

  // Writes the lap's region at the parameter t, only what the operands
  // `wanted` of its end (curve.point, curve.arc or curve.walk) need; the end
  // is written by writePoint, which must not read the other operands.
  void rewriteRegionFor(const Instruction& lap, std::size_t region, ValueId t,
                        std::initializer_list<std::size_t> wanted) {
    const Region& body = lap.regions[region];
    // Sets of the region's own ids and values: the work is the region's size.
    kept_.clear();
    std::unordered_set<std::uint32_t> needed;
    const Instruction& end = source_.instructions[body.instructions.back()];
    for (std::size_t k : wanted) {
      needed.insert(end.operands[k].index);
    }
    for (auto id = body.instructions.rbegin(); id != body.instructions.rend(); ++id) {
      const Instruction& instruction = source_.instructions[*id];
      if (instruction.result.valid() && needed.contains(instruction.result.index)) {
        kept_.insert(*id);
        for (ValueId operand : instruction.operands) {
          needed.insert(operand.index);
        }
      }
    }
    replace(lap.result, t);
    slicing_ = true;
    rewriteRegion(body);
    slicing_ = false;
  }

  // A loop over a lap's points, from `low` to `high`, its body the output
  // region from now on (until endRegions()); returns its variable.
  ValueId beginLapLoop(const Instruction& lap, ValueId low, ValueId high) {
    Instruction loop;
    loop.opcode = Opcode::Loop;
    loop.index = static_cast<std::uint32_t>(LoopRole::Curve);
    loop.span = lap.span;
    loop.pass = lap.pass;
    loop.regions.resize(1);
    ValueId variable = beginRegions(loop, {low, high});
    enterOutputRegion(0);
    return variable;
  }

  // A value of the source the lap's curve reads from outside it, at the
  // values the program was compiled with (compiled_values.h).
  std::optional<double> outsideValue(ValueId value) const { return compiled_(value); }

  // The cut (of the function's cut table) the moves being written belong
  // to: the last cut.begin met; nullopt before the first.
  std::optional<std::uint32_t> currentCut() const { return cut_; }

  // Whether the lap climbs or descends: its two heights not one value.
  bool isRamp(const Instruction& lap) const { return lapRamps(source_, lap); }

  std::shared_ptr<const geom::Curve> curveOf(const Instruction& lap) const {
    return lapCurve(source_, lap, [&](ValueId value) { return outsideValue(value); });
  }

  // An operand of the move being written: a value, or a number not yet
  // written (as the lowering's arithmetic folds).
  struct Operand {
    ValueId value;
    double number = 0;
    bool isNumber() const { return !value.valid(); }
  };

  Operand operandOf(ValueId output) const {
    std::optional<double> number = passes::constantValue(output_, output);
    return number ? Operand{ValueId{}, *number} : Operand{output, 0};
  }

  ValueId valueOf(const Operand& operand) {
    return operand.isNumber() ? constant(operand.number) : operand.value;
  }

  // a + b, a - b, a * b and a / b, folding numbers and the identities
  // x + 0, x - 0, x * 1 and x / 1 (as the lowering's arithmetic does).
  Operand arithmetic(Opcode opcode, const Operand& a, const Operand& b) {
    bool numbers = a.isNumber() && b.isNumber();
    switch (opcode) {
    case Opcode::Add:
      if (numbers) {
        return {ValueId{}, a.number + b.number};
      }
      if ((a.isNumber() && a.number == 0) || (b.isNumber() && b.number == 0)) {
        return a.isNumber() ? b : a;
      }
      break;
    case Opcode::Sub:
      if (numbers) {
        return {ValueId{}, a.number - b.number};
      }
      if (b.isNumber() && b.number == 0) {
        return a;
      }
      break;
    case Opcode::Mul:
      if (numbers) {
        return {ValueId{}, a.number * b.number};
      }
      if ((a.isNumber() && a.number == 1) || (b.isNumber() && b.number == 1)) {
        return a.isNumber() ? b : a;
      }
      break;
    case Opcode::Div:
      if (numbers && b.number != 0) {
        return {ValueId{}, a.number / b.number};
      }
      if (!a.isNumber() && a.value == b.value) {
        return {ValueId{}, 1}; // a count over itself (a loop of none never reads it)
      }
      if (b.isNumber() && b.number == 1) {
        return a;
      }
      break;
    default:
      break;
    }
    return {binary(opcode, a, b), 0};
  }
  Operand add(const Operand& a, const Operand& b) { return arithmetic(Opcode::Add, a, b); }
  Operand multiply(const Operand& a, const Operand& b) { return arithmetic(Opcode::Mul, a, b); }

  ValueId binary(Opcode opcode, const Operand& a, const Operand& b) {
    ValueId left = valueOf(a);
    ValueId right = valueOf(b);
    Instruction instruction;
    instruction.opcode = opcode;
    return emit(instruction, {left, right});
  }

  // A feed move to (x, y, z) at the lap's feed, on the lap's line.
  void emitFeedMove(const Instruction& lap, ValueId x, ValueId y, ValueId z) {
    Instruction feed;
    feed.opcode = Opcode::Feed;
    feed.span = lap.span;
    feed.pass = lap.pass;
    emit(feed, {x, y, z, mapped(lap.operands[2])});
  }

private:
  std::size_t instructionIdOf(const Instruction& instruction) const {
    return static_cast<std::size_t>(&instruction - source_.instructions.data());
  }

  mutable CompiledValues compiled_{source_};
  const Instruction* lap_ = nullptr; // being written
  std::optional<std::uint32_t> cut_;
  // While a region is written for some of its end's operands (slicing_):
  // the instructions they need.
  bool slicing_ = false;
  std::unordered_set<std::size_t> kept_;
};

} // namespace cncc::ir
