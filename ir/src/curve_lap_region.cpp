// A curve.lap region evaluated at one parameter: its pure instructions in
// order with the interpreter's arithmetic (the folding's evaluate), what it
// reads from outside the lap given by the caller.
#include "cncc/ir/curve_lap.h"

#include "passes/evaluate.h"

namespace cncc::ir {

std::optional<Eigen::Vector3d> lapRegionPoint(const Function& function, const Instruction& lap,
                                              std::size_t region, double t,
                                              const OutsideValue& outside) {
  std::vector<std::optional<double>> values(function.valueTypes.size());
  values[lap.result.index] = t;
  auto valueOf = [&](ValueId value) -> std::optional<double> {
    if (values[value.index]) {
      return values[value.index];
    }
    return outside(value);
  };
  std::vector<double> operands;
  for (InstructionId id : lap.regions[region].instructions) {
    const Instruction& instruction = function.instructions[id];
    operands.clear();
    for (ValueId operand : instruction.operands) {
      std::optional<double> value = valueOf(operand);
      if (!value) {
        return std::nullopt;
      }
      operands.push_back(*value);
    }
    if (instruction.opcode == Opcode::CurvePoint) {
      return Eigen::Vector3d(operands[0], operands[1], operands[2]);
    }
    if (instruction.opcode == Opcode::Param) {
      std::optional<double> value = outside(instruction.result);
      if (!value) {
        return std::nullopt;
      }
      values[instruction.result.index] = *value;
      continue;
    }
    if (!isPure(instruction.opcode) || !instruction.regions.empty()) {
      return std::nullopt;
    }
    std::optional<double> result = passes::evaluate(function, instruction, operands);
    if (!result) {
      return std::nullopt;
    }
    values[instruction.result.index] = *result;
  }
  return std::nullopt; // a region without its curve.point (the verifier refuses it)
}

} // namespace cncc::ir
