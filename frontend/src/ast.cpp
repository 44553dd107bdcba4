#include "cncc/frontend/ast.h"

namespace cncc::frontend {

std::string_view operatorSpelling(BinaryOperator op) {
  switch (op) {
  case BinaryOperator::Add:
    return "+";
  case BinaryOperator::Subtract:
    return "-";
  case BinaryOperator::Multiply:
    return "*";
  case BinaryOperator::Divide:
    return "/";
  case BinaryOperator::Remainder:
    return "%";
  case BinaryOperator::Power:
    return "^";
  case BinaryOperator::Equal:
    return "==";
  case BinaryOperator::NotEqual:
    return "!=";
  case BinaryOperator::Less:
    return "<";
  case BinaryOperator::LessEqual:
    return "<=";
  case BinaryOperator::Greater:
    return ">";
  case BinaryOperator::GreaterEqual:
    return ">=";
  case BinaryOperator::And:
    return "&&";
  case BinaryOperator::Or:
    return "||";
  }
  return "?";
}

std::string_view coolantModeSpelling(CoolantMode mode) {
  switch (mode) {
  case CoolantMode::Off:
    return "off";
  case CoolantMode::Flood:
    return "flood";
  case CoolantMode::Mist:
    return "mist";
  case CoolantMode::Through:
    return "through";
  }
  return "?";
}

std::string originOffsetSpelling(const OriginStmt& origin) {
  return "G" + std::to_string(origin.group) + (origin.extended != 0 ? ".1" : "");
}

} // namespace cncc::frontend
