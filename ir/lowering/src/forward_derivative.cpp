#include "forward_derivative.h"

namespace cncc::ir::lowering {

namespace {

bool isZero(const Scalar& scalar) {
  return scalar.isConstant() && scalar.constant == 0;
}

} // namespace

bool ValueDependence::operator()(ValueId value) {
  if (value == variable_) {
    return true;
  }
  if (auto found = varying_.find(value.index); found != varying_.end()) {
    return found->second;
  }
  bool result = false;
  for (ValueId operand : function_.definition(value).operands) {
    result = result || (*this)(operand);
  }
  return varying_[value.index] = result;
}

std::optional<Scalar> ForwardDerivative::of(Scalar value) {
  if (value.isConstant() || !varies_(value.value)) {
    return Scalar::of(0);
  }
  if (value.value == variable_) {
    return Scalar::of(1);
  }
  if (auto found = derivatives_.find(value.value.index); found != derivatives_.end()) {
    return found->second;
  }
  // A copy, without regions: the arithmetic below appends instructions.
  Instruction instruction = withoutRegions(builder_.function().definition(value.value));
  std::vector<Scalar> operands;
  for (ValueId operand : instruction.operands) {
    // A condition (a select's) has no derivative; its value picks one.
    if (opcodeInfo(builder_.function().definition(operand).opcode).result == ValueType::Bool) {
      operands.push_back(Scalar::of(0));
      continue;
    }
    std::optional<Scalar> own = of(Scalar::of(operand, ValueType::F64));
    if (!own) {
      return derivatives_[value.value.index] = std::nullopt;
    }
    operands.push_back(*own);
  }
  return derivatives_[value.value.index] = rule(instruction, operands);
}

// The derivative of one instruction's result from its operands' values
// (a, b) and derivatives (da, db).
std::optional<Scalar> ForwardDerivative::rule(const Instruction& instruction,
                                              const std::vector<Scalar>& operandDerivatives) {
  Arithmetic& math = math_;
  auto operand = [&](std::size_t i) { return Scalar::of(instruction.operands[i], ValueType::F64); };
  auto d = [&](std::size_t i) { return operandDerivatives[i]; };
  Scalar result = Scalar::of(instruction.result, ValueType::F64);
  auto sub = [&](Scalar a, Scalar b) { return math.binary(Opcode::Sub, a, b); };
  auto div = [&](Scalar a, Scalar b) { return isZero(a) ? a : math.binary(Opcode::Div, a, b); };
  auto mul = [&](Scalar a, Scalar b) {
    return isZero(a) || isZero(b) ? Scalar::of(0) : math.multiply(a, b);
  };
  switch (instruction.opcode) {
  case Opcode::Add:
    return math.add(d(0), d(1));
  case Opcode::Sub:
    return sub(d(0), d(1));
  case Opcode::Neg:
    return math.unary(Opcode::Neg, d(0));
  case Opcode::Mul:
    return math.add(mul(d(0), operand(1)), mul(operand(0), d(1)));
  case Opcode::Div: // (a / b)' = (a' - (a / b) b') / b
    return div(sub(d(0), mul(result, d(1))), operand(1));
  case Opcode::Sqrt: // a' / (2 sqrt a)
    return div(d(0), mul(Scalar::of(2), result));
  case Opcode::Sin:
    return mul(math.unary(Opcode::Cos, operand(0)), d(0));
  case Opcode::Cos:
    return mul(math.unary(Opcode::Neg, math.unary(Opcode::Sin, operand(0))), d(0));
  case Opcode::Tan: // a' (1 + tan^2 a)
    return mul(math.add(Scalar::of(1), mul(result, result)), d(0));
  case Opcode::Exp:
    return mul(result, d(0));
  case Opcode::Ln:
    return div(d(0), operand(0));
  case Opcode::Atan: // a' / (1 + a^2)
    return div(d(0), math.add(Scalar::of(1), mul(operand(0), operand(0))));
  case Opcode::Asin:
  case Opcode::Acos: { // +- a' / sqrt(1 - a^2)
    Scalar slope =
        div(d(0), math.unary(Opcode::Sqrt, sub(Scalar::of(1), mul(operand(0), operand(0)))));
    return instruction.opcode == Opcode::Asin ? slope : math.unary(Opcode::Neg, slope);
  }
  case Opcode::Atan2: { // atan2(y, x)' = (x y' - y x') / (x^2 + y^2)
    Scalar y = operand(0);
    Scalar x = operand(1);
    return div(sub(mul(x, d(0)), mul(y, d(1))), math.add(mul(x, x), mul(y, y)));
  }
  case Opcode::Pow: // with a constant exponent n: n a^(n - 1) a'
    if (!isZero(d(1))) {
      return std::nullopt;
    }
    return mul(
        mul(operand(1), math.binary(Opcode::Pow, operand(0), sub(operand(1), Scalar::of(1)))),
        d(0));
  case Opcode::Abs:
    return math.select(math.binary(Opcode::Lt, operand(0), Scalar::of(0)),
                       math.unary(Opcode::Neg, d(0)), d(0));
  case Opcode::Min:
  case Opcode::Max:
    return math.select(math.binary(instruction.opcode == Opcode::Min ? Opcode::Le : Opcode::Ge,
                                   operand(0), operand(1)),
                       d(0), d(1));
  case Opcode::Select:
    return math.select(Scalar::of(instruction.operands[0], ValueType::Bool), d(1), d(2));
  case Opcode::Floor:
  case Opcode::Ceil:
  case Opcode::Round: // steps: flat between them
    return Scalar::of(0);
  default:
    return std::nullopt;
  }
}

} // namespace cncc::ir::lowering
