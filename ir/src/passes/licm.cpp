// Loop-invariant code motion. A pure operation directly in a loop's body
// whose operands are all defined outside the loop (or by operations that
// move too) goes before the loop, in its original order. Pure f64 math and
// comparisons never stop a run, so computing them when the loop runs zero
// times is harmless; table.load can (an index out of range), so it stays.
// Operations inside an if in the loop stay: they may not run at all. One
// rewrite moves operations out of one loop level; the pass repeats until
// nothing moves, which lifts them out of nested loops level by level.
#include "cncc/ir/passes.h"

#include "rewriter.h"

#include <set>

namespace cncc::ir {

namespace {

constexpr InstructionId noParent = ~InstructionId{0};

class InvariantMotion : public passes::Rewriter {
public:
  explicit InvariantMotion(const Function& source)
      : Rewriter(source), parents_(source.instructions.size(), noParent) {
    recordParents(source.body, noParent);
  }

private:
  void visit(const Instruction& instruction) override {
    if (hoisted_.count(&instruction) != 0) {
      return; // already written before its loop
    }
    if (instruction.opcode == Opcode::Loop) {
      for (InstructionId id : invariants(instruction)) {
        const Instruction& invariant = source_.instructions[id];
        hoisted_.insert(&invariant);
        replace(invariant.result, emit(invariant, mappedOperands(invariant)));
        markChanged();
      }
    }
    copy(instruction);
  }

  void recordParents(const Region& region, InstructionId parent) {
    for (InstructionId id : region.instructions) {
      parents_[id] = parent;
      for (const Region& nested : source_.instructions[id].regions) {
        recordParents(nested, id);
      }
    }
  }

  bool definedInside(ValueId value, InstructionId loop) const {
    for (InstructionId id = source_.definitions[value.index]; id != noParent; id = parents_[id]) {
      if (id == loop) {
        return true;
      }
    }
    return false;
  }

  // The operations of the loop's body that can move before it, in order.
  std::vector<InstructionId> invariants(const Instruction& loop) const {
    InstructionId loopId = source_.definitions[loop.result.index];
    std::vector<InstructionId> result;
    std::set<std::uint32_t> moving; // values of the operations in `result`
    for (InstructionId id : loop.regions[0].instructions) {
      const Instruction& instruction = source_.instructions[id];
      if (!isPure(instruction.opcode) || mayFail(instruction.opcode)) {
        continue;
      }
      bool invariant = true;
      for (ValueId operand : instruction.operands) {
        invariant =
            invariant && (moving.count(operand.index) != 0 || !definedInside(operand, loopId));
      }
      if (invariant) {
        result.push_back(id);
        moving.insert(instruction.result.index);
      }
    }
    return result;
  }

  std::vector<InstructionId> parents_;
  std::set<const Instruction*> hoisted_;
};

} // namespace

bool hoistLoopInvariants(Function& function) {
  bool changed = false;
  // Each round lifts operations one loop level; nesting is shallow.
  for (int round = 0; round < 32; ++round) {
    InvariantMotion pass(function);
    Function result = pass.run();
    function = std::move(result);
    if (!pass.changed()) {
      break;
    }
    changed = true;
  }
  return changed;
}

} // namespace cncc::ir
