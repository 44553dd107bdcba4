// The IR's arithmetic on doubles, shared by the interpreter and constant
// folding (fold, and fold-finite for the macro targets), so that a folded
// constant is the value the interpreter would have computed at run time,
// bit for bit.
// The math functions are the one table's (cncc/geom/math_functions.h) that
// the front end evaluates CDL by and the JIT calls the C library functions
// of. Bools are 0 and 1.
#pragma once

#include "cncc/geom/math_functions.h"
#include "cncc/ir/ir.h"

#include <array>
#include <cmath>
#include <optional>
#include <string_view>
#include <utility>

namespace cncc::ir {

// The opcode of each math function of the table.
inline constexpr std::array<std::pair<Opcode, geom::MathFunction>, geom::mathFunctions.size()>
    mathOpcodes = {{
        {Opcode::Sin, geom::MathFunction::Sin},
        {Opcode::Cos, geom::MathFunction::Cos},
        {Opcode::Tan, geom::MathFunction::Tan},
        {Opcode::Asin, geom::MathFunction::Asin},
        {Opcode::Acos, geom::MathFunction::Acos},
        {Opcode::Atan, geom::MathFunction::Atan},
        {Opcode::Atan2, geom::MathFunction::Atan2},
        {Opcode::Sqrt, geom::MathFunction::Sqrt},
        {Opcode::Abs, geom::MathFunction::Abs},
        {Opcode::Min, geom::MathFunction::Min},
        {Opcode::Max, geom::MathFunction::Max},
        {Opcode::Pow, geom::MathFunction::Pow},
        {Opcode::Exp, geom::MathFunction::Exp},
        {Opcode::Ln, geom::MathFunction::Ln},
        {Opcode::Floor, geom::MathFunction::Floor},
        {Opcode::Ceil, geom::MathFunction::Ceil},
        {Opcode::Round, geom::MathFunction::Round},
        {Opcode::Rem, geom::MathFunction::Rem},
    }};

// The math function an opcode computes; nullopt for any other opcode.
constexpr std::optional<geom::MathFunction> mathFunctionOf(Opcode opcode) {
  for (const auto& [known, function] : mathOpcodes) {
    if (known == opcode) {
      return function;
    }
  }
  return std::nullopt;
}

// The opcode of the math function CDL calls `name` with `arity` operands;
// nullopt for any other name.
constexpr std::optional<Opcode> mathOpcode(std::string_view name, int arity) {
  const geom::MathFunctionInfo* info = geom::findMathFunction(name);
  if (info == nullptr || info->arity != arity) {
    return std::nullopt;
  }
  for (const auto& [opcode, function] : mathOpcodes) {
    if (function == info->function) {
      return opcode;
    }
  }
  return std::nullopt;
}

// The result of a one-operand operation (neg, abs, sqrt, sin, ..., not) and
// of a two-operand one (add, ..., atan2, the comparisons, and, or); nullopt
// for an opcode that is neither. Inline: the interpreter's inner loop.
inline std::optional<double> unaryResult(Opcode opcode, double a) {
  switch (opcode) {
  case Opcode::Neg:
    return -a;
  case Opcode::Not:
    return a != 0 ? 0 : 1;
  default:
    break;
  }
  std::optional<geom::MathFunction> function = mathFunctionOf(opcode);
  if (!function || geom::mathFunctionInfo(*function).arity != 1) {
    return std::nullopt;
  }
  return geom::computeMath(*function, a);
}

inline std::optional<double> binaryResult(Opcode opcode, double a, double b) {
  switch (opcode) {
  case Opcode::Add:
    return a + b;
  case Opcode::Sub:
    return a - b;
  case Opcode::Mul:
    return a * b;
  case Opcode::Div:
    return a / b;
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
    break;
  }
  std::optional<geom::MathFunction> function = mathFunctionOf(opcode);
  if (!function || geom::mathFunctionInfo(*function).arity != 2) {
    return std::nullopt;
  }
  return geom::computeMath(*function, a, b);
}

} // namespace cncc::ir
