#include "macro_expressions.h"

#include "controller_words.h"

#include "cncc/backends/gcode_writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace cncc::backends {

namespace {

using ir::Opcode;
using enum MacroPosition;

// `0.5` -> `.5`, `-0.5` -> `-.5`: the leading zero is no digit of precision.
void dropLeadingZero(std::string& text) {
  if (text.starts_with("0.") && text.size() > 2) {
    text.erase(0, 1);
  } else if (text.starts_with("-0.")) {
    text.erase(1, 1);
  }
}

} // namespace

std::string MacroExpressionWriter::at(const MacroText& text, MacroPosition position) const {
  return dialect_.bare(text.form, position) ? text.text : "[" + text.text + "]";
}

std::string MacroExpressionWriter::rightOperand(const MacroText& text,
                                                MacroPosition position) const {
  std::string written = at(text, position);
  return written.starts_with('-') ? "[" + written + "]" : written;
}

std::string MacroExpressionWriter::constant(double value) const {
  const MacroNumberFormat& format = dialect_.numbers;
  double magnitude = std::abs(value);
  int digits = format.significantDigits;
  if (!std::isfinite(value)) {
    errors_.push_back(fmt::format("the program needs the number {}, which {} cannot read", value,
                                  dialect_.controllerName));
    return "0.";
  }
  if (format.limitWholeDigits && magnitude >= std::pow(10.0, digits)) {
    errors_.push_back(
        fmt::format("the number {} needs more than the controller's {} digits", value, digits));
    return "0.";
  }
  int wholeDigits = magnitude < 1 ? 0 : static_cast<int>(std::floor(std::log10(magnitude))) + 1;
  std::string text = formatGcodeNumber(value, std::max(0, digits - wholeDigits));
  if (format.dropLeadingZero) {
    dropLeadingZero(text);
  }
  return text;
}

std::string MacroExpressionWriter::coordinateLiteral(double value) const {
  const MacroNumberFormat& format = dialect_.numbers;
  if (std::isfinite(format.maximumCoordinate) && !(std::abs(value) <= format.maximumCoordinate)) {
    errors_.push_back(fmt::format("the coordinate {} is beyond the controller's range +-{}", value,
                                  format.maximumCoordinate));
    return "0.";
  }
  if (!std::isfinite(value)) {
    return constant(value);
  }
  std::string text = formatGcodeNumber(value, format.coordinateDecimals);
  if (format.dropLeadingZero) {
    dropLeadingZero(text);
  }
  return text;
}

std::optional<double> MacroExpressionWriter::constantOf(ir::ValueId value) const {
  const ir::Instruction& instruction = function_.definition(value);
  if (instruction.opcode == Opcode::Const) {
    return instruction.number;
  }
  return std::nullopt;
}

bool MacroExpressionWriter::isNamedParameter(ir::ValueId value) const {
  const ir::Instruction& instruction = function_.definition(value);
  return instruction.opcode == Opcode::Param && instruction.index < parameterNames_.size();
}

std::string MacroExpressionWriter::variable(ir::ValueId value) const {
  if (isNamedParameter(value)) {
    return fmt::format("#<{}>", parameterNames_[function_.definition(value).index]);
  }
  return fmt::format("#{}", allocation_.variableOfValue[value.index]);
}

std::string MacroExpressionWriter::parameterVariable(std::size_t index) const {
  if (index < parameterNames_.size()) {
    return fmt::format("#<{}>", parameterNames_[index]);
  }
  return fmt::format("#{}", allocation_.parameterVariables[index]);
}

MacroText MacroExpressionWriter::value(ir::ValueId value) const {
  if (std::optional<double> number = constantOf(value)) {
    std::string text = constant(*number);
    MacroForm form = text.starts_with('-') ? MacroForm::NegativeNumber : MacroForm::Atom;
    return {std::move(text), form};
  }
  if (function_.definition(value).opcode == Opcode::Param || allocation_.inVariable(value)) {
    return {variable(value), MacroForm::Atom};
  }
  return definition(value);
}

std::string MacroExpressionWriter::operand(ir::ValueId value) const {
  return at(this->value(value), Operand);
}

std::string MacroExpressionWriter::coordinate(ir::ValueId value) const {
  if (std::optional<double> number = constantOf(value)) {
    return coordinateLiteral(*number);
  }
  return operand(value);
}

MacroText MacroExpressionWriter::definition(ir::ValueId value) const {
  return instructionText(function_.definition(value));
}

MacroText MacroExpressionWriter::instructionText(const ir::Instruction& instruction) const {
  switch (instruction.opcode) {
  case Opcode::Const:
  case Opcode::Param:
    return value(instruction.result);
  case Opcode::TableLoad:
    return {tableRead(instruction), MacroForm::Atom};
  case Opcode::Add:
  case Opcode::Sub:
  case Opcode::Mul:
  case Opcode::Div:
  case Opcode::Neg:
    return arithmetic(instruction);
  case Opcode::Pow:
    return power(instruction);
  case Opcode::Lt:
  case Opcode::Le:
  case Opcode::Gt:
  case Opcode::Ge:
  case Opcode::Eq:
  case Opcode::Ne:
  case Opcode::And:
  case Opcode::Or:
  case Opcode::Not:
  case Opcode::ConstBool:
    return conditionText(instruction.result, false);
  default:
    return function(instruction);
  }
}

std::string MacroExpressionWriter::tableRead(const ir::Instruction& instruction) const {
  int base = allocation_.tableBase.at(instruction.index);
  ir::ValueId index = instruction.operands[0];
  if (std::optional<double> number = constantOf(index)) {
    return fmt::format("#{}", base + static_cast<int>(std::llround(*number)));
  }
  return fmt::format("#[{}+{}]", base, at(value(index), RightOfAdditive));
}

MacroText MacroExpressionWriter::arithmetic(const ir::Instruction& instruction) const {
  const std::vector<ir::ValueId>& operands = instruction.operands;
  MacroText left = value(operands[0]);
  if (instruction.opcode == Opcode::Neg) {
    return {"-" + at(left, UnderNegation), MacroForm::Negation};
  }
  MacroText right = value(operands[1]);
  if (instruction.opcode == Opcode::Mul || instruction.opcode == Opcode::Div) {
    char sign = instruction.opcode == Opcode::Mul ? '*' : '/';
    return {at(left, LeftOfMultiplicative) + sign + rightOperand(right, RightOfMultiplicative),
            MacroForm::Multiplicative};
  }
  char sign = instruction.opcode == Opcode::Add ? '+' : '-';
  std::optional<double> number = constantOf(operands[1]);
  if (number && *number < 0) { // a+-3. is written a-3.
    sign = sign == '+' ? '-' : '+';
    right = {constant(-*number), MacroForm::Atom};
  }
  return {at(left, LeftOfAdditive) + sign + rightOperand(right, RightOfAdditive),
          MacroForm::Additive};
}

MacroText MacroExpressionWriter::power(const ir::Instruction& instruction) const {
  MacroText base = value(instruction.operands[0]);
  MacroText exponent = value(instruction.operands[1]);
  switch (dialect_.power) {
  case PowerStyle::PowFunction:
    return {fmt::format("POW[{},{}]", base.text, exponent.text), MacroForm::Function};
  case PowerStyle::ExpOfLn:
    return {fmt::format("EXP[LN[{}]*{}]", base.text, at(exponent, RightOfMultiplicative)),
            MacroForm::Function};
  case PowerStyle::Operator: // `-2**2` is 4 in LinuxCNC: a unary minus binds first
    return {at(base, PowerOperand) + "**" + rightOperand(exponent, PowerOperand), MacroForm::Power};
  }
  return {};
}

// The argument of SIN/COS/TAN in degrees, a constant factor folded into the
// conversion: `#3*114.59156` rather than `[#3*2.]*57.29578`.
std::string MacroExpressionWriter::degrees(ir::ValueId radians) const {
  const ir::Instruction& instruction = function_.definition(radians);
  bool inlined = !allocation_.inVariable(radians) && instruction.opcode != Opcode::Param;
  if (inlined && (instruction.opcode == Opcode::Mul || instruction.opcode == Opcode::Div)) {
    std::optional<double> left = constantOf(instruction.operands[0]);
    std::optional<double> right = constantOf(instruction.operands[1]);
    if (instruction.opcode == Opcode::Mul && (left || right)) {
      ir::ValueId other = left ? instruction.operands[1] : instruction.operands[0];
      double factor = (left ? *left : *right) * degreesPerRadian;
      return at(value(other), LeftOfMultiplicative) + "*" + constant(factor);
    }
    if (instruction.opcode == Opcode::Div && right && *right != 0) {
      return at(value(instruction.operands[0]), LeftOfMultiplicative) + "*" +
             constant(degreesPerRadian / *right);
    }
  }
  return at(value(radians), LeftOfMultiplicative) + "*" + constant(degreesPerRadian);
}

MacroText MacroExpressionWriter::function(const ir::Instruction& instruction) const {
  Opcode opcode = instruction.opcode;
  const std::vector<ir::ValueId>& operands = instruction.operands;
  std::string_view word = dialect_.functionWord(opcode);
  if (isTrigonometric(opcode)) {
    return {fmt::format("{}[{}]", word, degrees(operands[0])), MacroForm::Function};
  }
  if (isInverseTrigonometric(opcode)) {
    return {fmt::format("{}[{}]*{}", word, value(operands[0]).text, constant(1 / degreesPerRadian)),
            MacroForm::Multiplicative};
  }
  if ((opcode == Opcode::Atan || opcode == Opcode::Atan2) && !dialect_.isStatement(opcode)) {
    // ATAN[y]/[x] as atan2, in -180..180 degrees where it is the only form.
    std::string x = opcode == Opcode::Atan ? dialect_.one : value(operands[1]).text;
    return {
        fmt::format("ATAN[{}]/[{}]*{}", value(operands[0]).text, x, constant(1 / degreesPerRadian)),
        MacroForm::Multiplicative};
  }
  if (word.empty() || operands.size() != 1) {
    errors_.push_back(
        fmt::format("internal: '{}' cannot be written inline", ir::opcodeInfo(opcode).spelling));
    return {"0.", MacroForm::Atom};
  }
  return {fmt::format("{}[{}]", word, value(operands[0]).text), MacroForm::Function};
}

MacroText MacroExpressionWriter::conditionText(ir::ValueId value, bool negated) const {
  const ir::Instruction& instruction = function_.definition(value);
  if (dialect_.comparesBoolVariables && allocation_.inVariable(value)) {
    return {fmt::format("{} {} 0", variable(value), negated ? "EQ" : "NE"), MacroForm::Comparison};
  }
  switch (instruction.opcode) {
  case Opcode::ConstBool:
    return {(instruction.number != 0) != negated ? dialect_.trueComparison
                                                 : dialect_.falseComparison,
            MacroForm::Comparison};
  case Opcode::Not:
    return conditionText(instruction.operands[0], !negated);
  case Opcode::And:
  case Opcode::Or: {
    // De Morgan: not (a and b) = (not a) or (not b).
    bool isAnd = (instruction.opcode == Opcode::And) != negated;
    MacroText left = conditionText(instruction.operands[0], negated);
    MacroText right = conditionText(instruction.operands[1], negated);
    return {fmt::format("{} {} {}", at(left, LeftOfLogical), isAnd ? "AND" : "OR",
                        at(right, RightOfLogical)),
            MacroForm::Logical};
  }
  default:
    break;
  }
  std::string_view name = comparisonName(instruction.opcode, negated);
  if (!name.empty()) {
    return {fmt::format("{} {} {}", at(this->value(instruction.operands[0]), Compared), name,
                        at(this->value(instruction.operands[1]), Compared)),
            MacroForm::Comparison};
  }
  // A bool that is no comparison (a parameter cannot be one): compare.
  return {fmt::format("{} {} 0", operand(value), negated ? "EQ" : "NE"), MacroForm::Comparison};
}

std::string MacroExpressionWriter::condition(ir::ValueId value, bool negated) const {
  return "[" + conditionText(value, negated).text + "]";
}

} // namespace cncc::backends
