// Mirrors select and table.load in ../interpreter.cpp, and shares its
// arithmetic (../arithmetic.h); a test runs both on the same inputs.
#include "evaluate.h"

#include "cncc/ir/arithmetic.h"

namespace cncc::ir::passes {

namespace {

std::optional<double> tableLoad(const Function& function, std::uint32_t table, double index) {
  if (table >= function.tables.size()) {
    return std::nullopt;
  }
  const std::vector<double>& values = function.tables[table];
  if (!(index >= 0 && index < static_cast<double>(values.size()))) {
    return std::nullopt;
  }
  return values[static_cast<std::size_t>(index)];
}

} // namespace

std::optional<double> evaluate(const Function& function, const Instruction& instruction,
                               const std::vector<double>& operands) {
  switch (instruction.opcode) {
  case Opcode::Const:
  case Opcode::ConstBool:
    return instruction.number;
  case Opcode::TableLoad:
    return operands.size() == 1 ? tableLoad(function, instruction.index, operands[0])
                                : std::nullopt;
  case Opcode::Select:
    return operands.size() == 3 ? std::optional(operands[0] != 0 ? operands[1] : operands[2])
                                : std::nullopt;
  default:
    break;
  }
  if (operands.size() == 1) {
    return unaryResult(instruction.opcode, operands[0]);
  }
  if (operands.size() == 2) {
    return binaryResult(instruction.opcode, operands[0], operands[1]);
  }
  return std::nullopt;
}

} // namespace cncc::ir::passes
