// Dead code elimination. What must stay: every effect, every if or loop
// that holds one, every curve.lap (its moves), a loop whose bounds may not
// be finite (the interpreter stops the run there), and, recursively,
// whatever computes their operands.
// Everything else is pure and unused, and goes: a dead table.load with it,
// though it might have stopped the run with an index out of range.
#include "cncc/ir/passes.h"

#include "rewriter.h"

#include <cmath>

namespace cncc::ir {

namespace {

class DeadCode : public passes::Rewriter {
public:
  explicit DeadCode(const Function& source)
      : Rewriter(source), live_(source.instructions.size(), false) {
    markRoots(source.body);
    while (!work_.empty()) {
      InstructionId id = work_.back();
      work_.pop_back();
      for (ValueId operand : source.instructions[id].operands) {
        markLive(source.definitions[operand.index]);
      }
    }
  }

private:
  void visit(const Instruction& instruction) override {
    if (!live_[idOf(instruction)]) {
      markChanged();
      return;
    }
    copy(instruction);
  }

  InstructionId idOf(const Instruction& instruction) const {
    return static_cast<InstructionId>(&instruction - source_.instructions.data());
  }

  void markLive(InstructionId id) {
    if (!live_[id]) {
      live_[id] = true;
      work_.push_back(id);
    }
  }

  void markRoots(const Region& region) {
    for (InstructionId id : region.instructions) {
      const Instruction& instruction = source_.instructions[id];
      bool hasRegions = !instruction.regions.empty();
      if (isEffect(instruction.opcode) || (hasRegions && mustStay(instruction))) {
        markLive(id);
      }
      for (const Region& nested : instruction.regions) {
        markRoots(nested);
      }
    }
  }

  // An if or loop that holds an effect or a loop that must stay, a loop
  // that may stop the run, or a curve.lap (its moves).
  bool mustStay(const Instruction& instruction) const {
    if (instruction.opcode == Opcode::CurveLap) {
      return true;
    }
    for (const Region& region : instruction.regions) {
      for (InstructionId id : region.instructions) {
        const Instruction& nested = source_.instructions[id];
        if (isEffect(nested.opcode) || (!nested.regions.empty() && mustStay(nested))) {
          return true;
        }
      }
    }
    return instruction.opcode == Opcode::Loop &&
           !(knownFinite(instruction.operands[0]) && knownFinite(instruction.operands[1]));
  }

  bool knownFinite(ValueId value) const {
    const Instruction& definition = source_.definition(value);
    if (definition.opcode == Opcode::Loop) {
      return true; // an induction variable, between finite bounds
    }
    return definition.opcode == Opcode::Const && std::isfinite(definition.number);
  }

  std::vector<bool> live_;
  std::vector<InstructionId> work_;
};

} // namespace

bool eliminateDeadCode(Function& function) {
  DeadCode pass(function);
  Function result = pass.run();
  function = std::move(result);
  return pass.changed();
}

} // namespace cncc::ir
