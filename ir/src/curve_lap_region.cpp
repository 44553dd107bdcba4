// A curve.lap region evaluated at parameters: its pure instructions in
// order with the interpreter's arithmetic (the folding's evaluate), what it
// reads from outside the lap resolved once.
#include "cncc/ir/curve_lap.h"

#include "passes/evaluate.h"

#include <unordered_map>

namespace cncc::ir {

LapRegionEvaluator::LapRegionEvaluator(const Function& function, const Instruction& lap,
                                       std::size_t region, const OutsideValue& outside)
    : function_(function) {
  std::unordered_map<std::uint32_t, Operand> known;
  known[lap.result.index] = {Operand::Kind::Parameter, 0};
  auto operandOf = [&](ValueId value) -> std::optional<Operand> {
    auto found = known.find(value.index);
    if (found != known.end()) {
      return found->second;
    }
    std::optional<double> number = outside(value);
    if (!number) {
      return std::nullopt;
    }
    return Operand{Operand::Kind::Number, *number};
  };
  for (InstructionId id : lap.regions[region].instructions) {
    const Instruction& instruction = function.instructions[id];
    Step step{&instruction, {}, 0};
    for (ValueId value : instruction.operands) {
      std::optional<Operand> operand = operandOf(value);
      if (!operand) {
        return;
      }
      step.operands.push_back(*operand);
    }
    if (instruction.opcode == Opcode::CurvePoint) {
      point_ = std::move(step.operands);
      valid_ = point_.size() == 3;
      return;
    }
    if (instruction.opcode == Opcode::Param) {
      std::optional<double> number = outside(instruction.result);
      if (!number) {
        return;
      }
      known[instruction.result.index] = {Operand::Kind::Number, *number};
      continue;
    }
    if (!isPure(instruction.opcode) || !instruction.regions.empty() ||
        !instruction.result.valid()) {
      return;
    }
    step.slot = slots_++;
    known[instruction.result.index] = {Operand::Kind::Slot, static_cast<double>(step.slot)};
    steps_.push_back(std::move(step));
  }
}

std::optional<Eigen::Vector3d> LapRegionEvaluator::operator()(double t) const {
  if (!valid_) {
    return std::nullopt;
  }
  std::vector<double> values(slots_);
  std::vector<double> operands;
  auto valueOf = [&](const Operand& operand) {
    switch (operand.kind) {
    case Operand::Kind::Parameter:
      return t;
    case Operand::Kind::Slot:
      return values[static_cast<std::size_t>(operand.number)];
    case Operand::Kind::Number:
      break;
    }
    return operand.number;
  };
  for (const Step& step : steps_) {
    operands.clear();
    for (const Operand& operand : step.operands) {
      operands.push_back(valueOf(operand));
    }
    std::optional<double> result = passes::evaluate(function_, *step.instruction, operands);
    if (!result) {
      return std::nullopt; // a table index out of range
    }
    values[step.slot] = *result;
  }
  return Eigen::Vector3d(valueOf(point_[0]), valueOf(point_[1]), valueOf(point_[2]));
}

} // namespace cncc::ir
