// What a value the controller computes comes to at the values the part is
// compiled with (the parameters' defaults, or -D). The step counts of
// parameter-dependent pieces are checked there against the limit of the
// counts chosen at compile time: past it (a weight of 1e9 typed for 1) the
// cut takes the tables, whose points are bounded, rather than give the
// controller (and verify) a loop of a hundred million steps.
#include "controller_segment.h"
#include "part_lowering.h"

#include "cncc/ir/arithmetic.h"

#include <cmath>
#include <map>

namespace cncc::ir::lowering {

namespace {

// Operand chains of a step count are a few hundred operations; far deeper
// is not a step count.
constexpr int maximumDepth = 10'000;

class CompiledValues {
public:
  explicit CompiledValues(const Function& function) : function_(function) {}

  std::optional<double> of(ValueId value, int depth = 0) {
    if (!value.valid() || value.index >= function_.definitions.size() || depth > maximumDepth) {
      return std::nullopt;
    }
    if (auto known = known_.find(value.index); known != known_.end()) {
      return known->second;
    }
    std::optional<double> result = compute(function_.definition(value), depth);
    if (result) {
      known_[value.index] = *result;
    }
    return result;
  }

private:
  std::optional<double> compute(const Instruction& instruction, int depth) {
    switch (instruction.opcode) {
    case Opcode::Const:
    case Opcode::ConstBool:
      return instruction.number;
    case Opcode::Param:
      return instruction.index < function_.parameters.size()
                 ? std::optional(function_.parameters[instruction.index].defaultValue)
                 : std::nullopt;
    case Opcode::Select: {
      std::optional<double> condition = of(instruction.operands[0], depth + 1);
      if (!condition) {
        return std::nullopt;
      }
      return of(instruction.operands[*condition != 0 ? 1 : 2], depth + 1);
    }
    default:
      break;
    }
    if (!isPure(instruction.opcode) || mayFail(instruction.opcode)) {
      return std::nullopt; // a loop's index, a table entry: not one number
    }
    std::vector<double> operands;
    for (ValueId operand : instruction.operands) {
      std::optional<double> number = of(operand, depth + 1);
      if (!number) {
        return std::nullopt;
      }
      operands.push_back(*number);
    }
    if (operands.size() == 1) {
      return unaryResult(instruction.opcode, operands[0]);
    }
    if (operands.size() == 2) {
      return binaryResult(instruction.opcode, operands[0], operands[1]);
    }
    return std::nullopt;
  }

  const Function& function_;
  std::map<std::uint32_t, double> known_;
};

} // namespace

std::optional<double> PartLowering::atCompiledValues(Scalar value) {
  if (value.isConstant()) {
    return value.constant;
  }
  return CompiledValues(builder_.function()).of(value.value);
}

bool PartLowering::stepsFitAtCompiledValues(const std::vector<ControllerSegment>& segments) {
  for (const ControllerSegment& segment : segments) {
    if (segment.steps > 0 || !segment.stepCount) {
      continue;
    }
    std::optional<double> steps = atCompiledValues(*segment.stepCount);
    if (steps && !(*steps <= maximumStepsPerPiece)) {
      return false;
    }
  }
  return true;
}

} // namespace cncc::ir::lowering
