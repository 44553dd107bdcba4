// Arithmetic on the lowering's scalars (lowering_values.h) through the IR
// builder, implemented in arithmetic.cpp.
#pragma once

#include "lowering_values.h"

#include "cncc/ir/builder.h"

namespace cncc::ir::lowering {

// Arithmetic on scalars through the builder: folds constant operands and
// the identities x + 0, x - 0, x * 1, x / 1.
class Arithmetic {
public:
  // `reduceAngles`: the constants the controller reads are rounded, so the
  // constant terms of sin, cos and tan's angles are taken modulo a turn.
  Arithmetic(FunctionBuilder& builder, bool reduceAngles)
      : builder_(builder), reduceAngles_(reduceAngles) {}

  // The scalar as an IR value (a constant is written here).
  ValueId value(Scalar scalar);
  Scalar unary(Opcode opcode, Scalar operand);
  Scalar binary(Opcode opcode, Scalar left, Scalar right);
  Scalar add(Scalar left, Scalar right) { return binary(Opcode::Add, left, right); }
  Scalar multiply(Scalar left, Scalar right) { return binary(Opcode::Mul, left, right); }
  Scalar select(Scalar condition, Scalar yes, Scalar no);
  // max(a, b) = (a + b + |a - b|) / 2, min likewise: one inline expression
  // (the exact Min and Max are blocks of their own on the macro
  // controllers); two constants give the exact result.
  Scalar larger(Scalar a, Scalar b) { return extreme(a, b, Opcode::Add); }
  Scalar smaller(Scalar a, Scalar b) { return extreme(a, b, Opcode::Sub); }

private:
  Scalar extreme(Scalar a, Scalar b, Opcode gap);
  ValueId angleModuloTurns(ValueId angle, int depth);

  FunctionBuilder& builder_;
  bool reduceAngles_ = false;
};

} // namespace cncc::ir::lowering
