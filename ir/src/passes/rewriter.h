// What the passes share: a Rewriter walks a function's regions in order and
// writes a fresh function, instruction by instruction, so a pass only says
// what to do with each instruction (copy it, drop it, replace its result by
// another value, or write something else) and the output keeps the IR's
// rules: values numbered in order, every instruction in one region.
#pragma once

#include "cncc/ir/ir.h"

#include <optional>
#include <utility>
#include <vector>

namespace cncc::ir::passes {

// Which operations are pure, effects or may fail: ir.h, from the traits of ir_ops.def.

// Instructions in the region, nested regions included.
std::size_t regionSize(const Function& function, const Region& region);
// Whether the region (nested regions included) holds an effect.
bool regionHasEffect(const Function& function, const Region& region);

// The value of a constant (const or const.bool), if `value` is one.
std::optional<double> constantValue(const Function& function, ValueId value);

// The times the interpreter runs a loop with these bounds, counting as it
// does (i = low, low + 1, .. while i <= high); nullopt when a bound is not
// finite or the count exceeds `limit`.
std::optional<std::size_t> tripCount(double low, double high, std::size_t limit);

class Rewriter {
public:
  explicit Rewriter(const Function& source);
  Rewriter(const Rewriter&) = delete;
  Rewriter& operator=(const Rewriter&) = delete;
  virtual ~Rewriter() = default;

  // Rewrites the body; call once.
  Function run();
  bool changed() const { return changed_; }

protected:
  // Called for each instruction of the source in order; copies by default.
  virtual void visit(const Instruction& instruction) { copy(instruction); }
  // Called around each region the output enters: the body, a loop's body,
  // an if's then and else.
  virtual void enterRegion() {}
  virtual void leaveRegion() {}

  // Visits each instruction of a source region, in the current output region.
  void rewriteRegion(const Region& region);
  // Copies the instruction, operands mapped; a loop or if gets its regions
  // rewritten through visit().
  void copy(const Instruction& instruction);
  // Appends a copy of a region-less instruction with these operands and
  // returns its result (invalid when it has none).
  ValueId emit(const Instruction& instruction, std::vector<ValueId> operands);
  // The same with another opcode (an operation rewritten as another: its
  // span and pass kept).
  ValueId emitAs(const Instruction& instruction, Opcode opcode, std::vector<ValueId> operands);
  ValueId constant(double value);
  ValueId constantBool(bool value);

  // The output value standing for a source value.
  ValueId mapped(ValueId source) const { return map_[source.index]; }
  std::vector<ValueId> mappedOperands(const Instruction& instruction) const;
  // From now on `source` stands for `replacement`, an output value.
  void replace(ValueId source, ValueId replacement) { map_[source.index] = replacement; }
  void markChanged() { changed_ = true; }

  // Starts a loop or if like `instruction` in the output (regions empty);
  // enterOutputRegion(n) makes its region n the place where instructions
  // go, until endRegions().
  ValueId beginRegions(const Instruction& instruction, std::vector<ValueId> operands);
  void enterOutputRegion(std::size_t region);
  void endRegions();

  const Function& source_;
  Function output_;
  // The trip of a pass loop being written out (an unrolled LoopRole::Passes
  // loop): what is written is that pass's (passInLoop).
  SweepPass writingTrip_;

private:
  Region& currentRegion();
  ValueId append(Instruction instruction);

  std::vector<ValueId> map_;
  // The output regions being filled: (instruction, region); empty = body.
  std::vector<std::pair<InstructionId, std::size_t>> insertion_;
  bool changed_ = false;
  frontend::SourceSpan visiting_; // of the source instruction being visited
  SweepPass visitingPass_;        // and its pass
};

} // namespace cncc::ir::passes
