// The words the macro dialects share (Fanuc Custom Macro B, Mitsubishi,
// LinuxCNC): function names, comparison operators, and which functions
// take degrees. Each dialect's expression writer adds its own.
#pragma once

#include "cncc/ir/ir.h"

#include <string_view>

namespace cncc::backends {

// SIN, COS and TAN take degrees on the controllers.
inline bool isTrigonometric(ir::Opcode opcode) {
  return opcode == ir::Opcode::Sin || opcode == ir::Opcode::Cos || opcode == ir::Opcode::Tan;
}

// ASIN and ACOS give degrees.
inline bool isInverseTrigonometric(ir::Opcode opcode) {
  return opcode == ir::Opcode::Asin || opcode == ir::Opcode::Acos;
}

// The name of a one-operand function the dialects share (SIN, SQRT, LN,
// ...); empty for any other operation.
std::string_view sharedFunctionName(ir::Opcode opcode);

// LT, LE, ... (the opposite one when `negated`); empty for an operation
// that is no comparison.
std::string_view comparisonName(ir::Opcode opcode, bool negated);

} // namespace cncc::backends
