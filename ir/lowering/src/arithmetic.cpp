#include "arithmetic.h"

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

namespace {

// A turn, in long double: taking whole turns off an angle then adds no
// rounding beyond the angle's own where long double is wider than double.
constexpr long double turn = 6.283185307179586476925286766559L;
// How deep the sums and multiples of an angle are followed to its constants.
constexpr int deepestAngleTerm = 8;

bool isPeriodic(Opcode opcode) {
  return opcode == Opcode::Sin || opcode == Opcode::Cos || opcode == Opcode::Tan;
}

// A whole number n that an angle's terms may be multiplied through: n (x + c)
// and n (x + c - k turns) differ by whole turns.
bool isWholeMultiple(const Function& function, ValueId value) {
  const Instruction& definition = function.definition(value);
  return definition.opcode == Opcode::Const && std::abs(definition.number) <= 1e6 &&
         definition.number == std::nearbyint(definition.number);
}

} // namespace

Scalar Arithmetic::unary(Opcode opcode, Scalar operand) {
  if (operand.isConstant() && opcode == Opcode::Neg) {
    return Scalar::of(-operand.constant);
  }
  if (operand.isConstant() && opcode == Opcode::Not) {
    return Scalar::ofBool(operand.constant == 0);
  }
  ValueId argument = value(operand);
  // A constant angle is left to the optimiser, which folds the function of
  // it on the host.
  bool constantAngle = builder_.function().definition(argument).opcode == Opcode::Const;
  if (reduceAngles_ && isPeriodic(opcode) && !constantAngle) {
    argument = angleModuloTurns(argument, 0);
  }
  ValueId result = builder_.unary(opcode, argument);
  return Scalar::of(result, opcodeInfo(opcode).result);
}

// The angle written again with each constant term of more than a turn taken
// modulo a turn, through sums, differences, negation and whole multiples;
// the angle itself where none is. The controller reads 1e9 deg as
// 17453293. (its 8 digits), 0.48 rad off, and -80 deg with all its digits:
// sin, cos and tan are periodic, so both mean the same point. The angle's
// own instructions stay as they are for their other uses (dead code goes).
ValueId Arithmetic::angleModuloTurns(ValueId angle, int depth) {
  // A copy (the builder's instructions move as it appends), not of the
  // regions: the angle may be a curve.lap's parameter, whose instruction
  // holds every region of the lap.
  const Instruction definition = withoutRegions(builder_.function().definition(angle));
  const Opcode opcode = definition.opcode;
  const std::vector<ValueId>& operands = definition.operands;
  if (opcode == Opcode::Const) {
    double number = definition.number;
    if (!std::isfinite(number) || std::abs(number) <= turn) {
      return angle;
    }
    return builder_.constant(
        static_cast<double>(std::remainder(static_cast<long double>(number), turn)));
  }
  if (depth >= deepestAngleTerm) {
    return angle;
  }
  switch (opcode) {
  case Opcode::Neg: {
    ValueId term = angleModuloTurns(operands[0], depth + 1);
    return term == operands[0] ? angle : builder_.unary(Opcode::Neg, term);
  }
  case Opcode::Add:
  case Opcode::Sub:
  case Opcode::Mul: {
    bool multiple = opcode == Opcode::Mul;
    const Function& function = builder_.function();
    bool leftWhole = multiple && isWholeMultiple(function, operands[0]);
    bool rightWhole = multiple && isWholeMultiple(function, operands[1]);
    if (multiple && !leftWhole && !rightWhole) {
      return angle;
    }
    ValueId left = leftWhole ? operands[0] : angleModuloTurns(operands[0], depth + 1);
    ValueId right =
        rightWhole && !leftWhole ? operands[1] : angleModuloTurns(operands[1], depth + 1);
    if (left == operands[0] && right == operands[1]) {
      return angle;
    }
    return builder_.binary(opcode, left, right);
  }
  default:
    return angle;
  }
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
