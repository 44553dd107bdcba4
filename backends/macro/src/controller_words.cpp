#include "controller_words.h"

namespace cncc::backends {

using ir::Opcode;

std::string_view sharedFunctionName(Opcode opcode) {
  switch (opcode) {
  case Opcode::Sin:
    return "SIN";
  case Opcode::Cos:
    return "COS";
  case Opcode::Tan:
    return "TAN";
  case Opcode::Asin:
    return "ASIN";
  case Opcode::Acos:
    return "ACOS";
  case Opcode::Sqrt:
    return "SQRT";
  case Opcode::Abs:
    return "ABS";
  case Opcode::Exp:
    return "EXP";
  case Opcode::Ln:
    return "LN";
  case Opcode::Round:
    return "ROUND";
  default:
    return "";
  }
}

std::string_view comparisonName(Opcode opcode, bool negated) {
  switch (opcode) {
  case Opcode::Lt:
    return negated ? "GE" : "LT";
  case Opcode::Le:
    return negated ? "GT" : "LE";
  case Opcode::Gt:
    return negated ? "LE" : "GT";
  case Opcode::Ge:
    return negated ? "LT" : "GE";
  case Opcode::Eq:
    return negated ? "NE" : "EQ";
  case Opcode::Ne:
    return negated ? "EQ" : "NE";
  default:
    return "";
  }
}

} // namespace cncc::backends
