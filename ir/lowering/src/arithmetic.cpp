#include "part_lowering.h"

#include <algorithm>
#include <cmath>

namespace cncc::ir::lowering {

ValueId Arithmetic::value(Scalar scalar) {
  if (!scalar.isConstant()) {
    return scalar.value;
  }
  return scalar.type == ValueType::Bool ? builder_.constantBool(scalar.constant != 0)
                                        : builder_.constant(scalar.constant);
}

Scalar Arithmetic::unary(Opcode opcode, Scalar operand) {
  if (operand.isConstant() && opcode == Opcode::Neg) {
    return Scalar::of(-operand.constant);
  }
  if (operand.isConstant() && opcode == Opcode::Not) {
    return Scalar::ofBool(operand.constant == 0);
  }
  ValueId result = builder_.unary(opcode, value(operand));
  return Scalar::of(result, opcodeInfo(opcode).result);
}

namespace {

// The folded result of a basic operation, or nullopt to write it out.
std::optional<Scalar> folded(Opcode opcode, Scalar left, Scalar right) {
  bool a = left.isConstant();
  bool b = right.isConstant();
  double x = left.constant;
  double y = right.constant;
  switch (opcode) {
  case Opcode::Add:
    if (a && b) {
      return Scalar::of(x + y);
    }
    if ((a && x == 0) || (b && y == 0)) {
      return a ? right : left;
    }
    break;
  case Opcode::Sub:
    if (a && b) {
      return Scalar::of(x - y);
    }
    if (b && y == 0) {
      return left;
    }
    break;
  case Opcode::Mul:
    if (a && b) {
      return Scalar::of(x * y);
    }
    if ((a && x == 1) || (b && y == 1)) {
      return a ? right : left;
    }
    break;
  case Opcode::Div:
    if (a && b && y != 0) {
      return Scalar::of(x / y);
    }
    if (b && y == 1) {
      return left;
    }
    break;
  default:
    break;
  }
  return std::nullopt;
}

} // namespace

Scalar Arithmetic::binary(Opcode opcode, Scalar left, Scalar right) {
  if (std::optional<Scalar> result = folded(opcode, left, right)) {
    return *result;
  }
  ValueId result = builder_.binary(opcode, value(left), value(right));
  return Scalar::of(result, opcodeInfo(opcode).result);
}

Scalar Arithmetic::extreme(Scalar a, Scalar b, Opcode gap) {
  if (a.isConstant() && b.isConstant()) {
    return Scalar::of(gap == Opcode::Add ? std::max(a.constant, b.constant)
                                         : std::min(a.constant, b.constant));
  }
  Scalar difference = binary(Opcode::Sub, a, b);
  difference = difference.isConstant() ? Scalar::of(std::abs(difference.constant))
                                       : unary(Opcode::Abs, difference);
  return multiply(Scalar::of(0.5), binary(gap, add(a, b), difference));
}

Scalar Arithmetic::select(Scalar condition, Scalar yes, Scalar no) {
  if (condition.isConstant()) {
    return condition.constant != 0 ? yes : no;
  }
  ValueId result = builder_.operation(Opcode::Select, {value(condition), value(yes), value(no)});
  return Scalar::of(result, ValueType::F64);
}

} // namespace cncc::ir::lowering
