// The IR's arithmetic on doubles, shared by the interpreter, constant
// folding and the macro printers' simplifier, so that a folded constant is
// the value the interpreter would have computed at run time, bit for bit
// (the JIT calls the same C library functions). Bools are 0 and 1.
#pragma once

#include "cncc/ir/ir.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace cncc::ir {

// The result of a one-operand operation (neg, abs, sqrt, sin, ..., not) and
// of a two-operand one (add, ..., atan2, the comparisons, and, or); nullopt
// for an opcode that is neither. Inline: the interpreter's inner loop.
inline std::optional<double> unaryResult(Opcode opcode, double a) {
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

} // namespace cncc::ir
