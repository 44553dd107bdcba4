// Mirrors unaryResult, binaryResult, select and table.load in
// ../interpreter.cpp; a test runs both on the same inputs.
#include "evaluate.h"

#include <algorithm>
#include <cmath>

namespace cncc::ir::passes {

namespace {

std::optional<double> unary(Opcode opcode, double a) {
  switch (opcode) {
  case Opcode::Neg:
    return -a;
  case Opcode::Abs:
    return std::abs(a);
  case Opcode::Sqrt:
    return std::sqrt(a);
  case Opcode::Sin:
    return std::sin(a);
  case Opcode::Cos:
    return std::cos(a);
  case Opcode::Tan:
    return std::tan(a);
  case Opcode::Asin:
    return std::asin(a);
  case Opcode::Acos:
    return std::acos(a);
  case Opcode::Atan:
    return std::atan(a);
  case Opcode::Exp:
    return std::exp(a);
  case Opcode::Ln:
    return std::log(a);
  case Opcode::Floor:
    return std::floor(a);
  case Opcode::Ceil:
    return std::ceil(a);
  case Opcode::Round:
    return std::round(a);
  case Opcode::Not:
    return a != 0 ? 0 : 1;
  default:
    return std::nullopt;
  }
}

std::optional<double> binary(Opcode opcode, double a, double b) {
  switch (opcode) {
  case Opcode::Add:
    return a + b;
  case Opcode::Sub:
    return a - b;
  case Opcode::Mul:
    return a * b;
  case Opcode::Div:
    return a / b;
  case Opcode::Rem:
    return std::fmod(a, b);
  case Opcode::Pow:
    return std::pow(a, b);
  case Opcode::Min:
    return std::min(a, b);
  case Opcode::Max:
    return std::max(a, b);
  case Opcode::Atan2:
    return std::atan2(a, b);
  case Opcode::Lt:
    return a < b;
  case Opcode::Le:
    return a <= b;
  case Opcode::Gt:
    return a > b;
  case Opcode::Ge:
    return a >= b;
  case Opcode::Eq:
    return a == b;
  case Opcode::Ne:
    return a != b;
  case Opcode::And:
    return (a != 0) && (b != 0);
  case Opcode::Or:
    return (a != 0) || (b != 0);
  default:
    return std::nullopt;
  }
}

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
    return unary(instruction.opcode, operands[0]);
  }
  if (operands.size() == 2) {
    return binary(instruction.opcode, operands[0], operands[1]);
  }
  return std::nullopt;
}

} // namespace cncc::ir::passes
