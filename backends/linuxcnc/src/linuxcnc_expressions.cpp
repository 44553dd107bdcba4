#include "linuxcnc_expressions.h"

#include "controller_words.h"

#include "cncc/backends/gcode_writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>

namespace cncc::backends {

namespace {

using ir::Opcode;

constexpr double degreesPerRadian = 57.29577951308232;

// The shared names, and LinuxCNC's FIX (rounds down) and FUP (up).
std::string_view functionName(Opcode opcode) {
  switch (opcode) {
  case Opcode::Floor:
    return "FIX";
  case Opcode::Ceil:
    return "FUP";
  default:
    return sharedFunctionName(opcode);
  }
}

// Strips the zero before the point a number does not need (`0.5` stays: it
// reads better and LinuxCNC accepts both).
std::string significant(double value, int digits) {
  double magnitude = std::abs(value);
  int wholeDigits = magnitude < 1 ? 0 : static_cast<int>(std::floor(std::log10(magnitude))) + 1;
  return formatGcodeNumber(value, std::max(0, digits - wholeDigits));
}

} // namespace

std::string bracketedUnlessTighter(const LinuxcncText& text, LinuxcncForm loosest) {
  return text.form <= loosest ? text.text : "[" + text.text + "]";
}

std::vector<ir::Opcode> linuxcncStatementOpcodes() {
  return {Opcode::Min, Opcode::Max, Opcode::Select, Opcode::Rem};
}

ir::InlineShape linuxcncInlineShape(const ir::Function&, const ir::Instruction& instruction,
                                    std::span<const ir::InlineShape> operands) {
  switch (instruction.opcode) {
  case Opcode::Const:
  case Opcode::Param:
  case Opcode::Loop:
    return {};
  default:
    break;
  }
  int depth = 0;
  int operations = 1;
  for (const ir::InlineShape& operand : operands) {
    depth = std::max(depth, operand.bracketDepth);
    operations += operand.operations;
  }
  // Trigonometry adds its conversion to degrees.
  bool converts = isTrigonometric(instruction.opcode) ||
                  isInverseTrigonometric(instruction.opcode) ||
                  instruction.opcode == Opcode::Atan || instruction.opcode == Opcode::Atan2;
  return {depth + 1, ir::InlineForm::Atom, operations + (converts ? 1 : 0)};
}

std::string LinuxcncExpressionWriter::constant(double value) const {
  if (!std::isfinite(value)) {
    errors_.push_back(
        fmt::format("the program needs the number {}, which LinuxCNC cannot read", value));
    return "0";
  }
  return significant(value, format_.significantDigits);
}

std::string LinuxcncExpressionWriter::coordinateLiteral(double value) const {
  if (!std::isfinite(value)) {
    return constant(value);
  }
  return formatGcodeNumber(value, format_.coordinateDecimals);
}

std::optional<double> LinuxcncExpressionWriter::constantOf(ir::ValueId value) const {
  const ir::Instruction& instruction = function_.definition(value);
  if (instruction.opcode == Opcode::Const) {
    return instruction.number;
  }
  return std::nullopt;
}

std::string LinuxcncExpressionWriter::variable(ir::ValueId value) const {
  const ir::Instruction& instruction = function_.definition(value);
  if (instruction.opcode == Opcode::Param && instruction.index < parameterNames_.size()) {
    return fmt::format("#<{}>", parameterNames_[instruction.index]);
  }
  return fmt::format("#{}", allocation_.variableOfValue[value.index]);
}

LinuxcncText LinuxcncExpressionWriter::value(ir::ValueId value) const {
  if (std::optional<double> number = constantOf(value)) {
    std::string text = constant(*number);
    return {text, text.starts_with('-') ? LinuxcncForm::Negation : LinuxcncForm::Atom};
  }
  if (function_.definition(value).opcode == Opcode::Param || allocation_.inVariable(value)) {
    return {variable(value), LinuxcncForm::Atom};
  }
  return definition(value);
}

std::string LinuxcncExpressionWriter::operand(ir::ValueId value) const {
  LinuxcncText text = this->value(value);
  // A negative number is one token; `-#1` is not.
  bool number = constantOf(value).has_value();
  // `X[SIN[..]]` rather than `XSIN[..]`: both are read, one is read easily.
  bool function = !text.text.empty() && std::isalpha(static_cast<unsigned char>(text.text[0]));
  return number || (text.form == LinuxcncForm::Atom && !function) ? text.text
                                                                  : "[" + text.text + "]";
}

std::string LinuxcncExpressionWriter::coordinate(ir::ValueId value) const {
  if (std::optional<double> number = constantOf(value)) {
    return coordinateLiteral(*number);
  }
  return operand(value);
}

LinuxcncText LinuxcncExpressionWriter::definition(ir::ValueId value) const {
  return instructionText(function_.definition(value));
}

LinuxcncText LinuxcncExpressionWriter::instructionText(const ir::Instruction& instruction) const {
  switch (instruction.opcode) {
  case Opcode::Const:
    return value(instruction.result);
  case Opcode::Param:
    return {variable(instruction.result), LinuxcncForm::Atom};
  case Opcode::TableLoad:
    return {tableRead(instruction), LinuxcncForm::Atom};
  case Opcode::Add:
  case Opcode::Sub:
  case Opcode::Mul:
  case Opcode::Div:
  case Opcode::Neg:
  case Opcode::Pow:
    return arithmetic(instruction);
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

std::string LinuxcncExpressionWriter::tableRead(const ir::Instruction& instruction) const {
  int base = allocation_.tableBase.at(instruction.index);
  ir::ValueId index = instruction.operands[0];
  if (std::optional<double> number = constantOf(index)) {
    return fmt::format("#{}", base + static_cast<int>(std::llround(*number)));
  }
  return fmt::format("#[{}+{}]", base,
                     bracketedUnlessTighter(value(index), LinuxcncForm::Multiplicative));
}

namespace {

// The right operand of a binary operator: a sign right after the operator
// (`#1*-0.5`) is written in brackets, the portable form (TARGETS.md).
std::string rightOperand(const LinuxcncText& text, LinuxcncForm loosest) {
  std::string written = bracketedUnlessTighter(text, loosest);
  return written.starts_with('-') ? "[" + written + "]" : written;
}

} // namespace

LinuxcncText LinuxcncExpressionWriter::arithmetic(const ir::Instruction& instruction) const {
  const std::vector<ir::ValueId>& operands = instruction.operands;
  LinuxcncText left = value(operands[0]);
  if (instruction.opcode == Opcode::Neg) {
    return {"-" + bracketedUnlessTighter(left, LinuxcncForm::Atom), LinuxcncForm::Negation};
  }
  LinuxcncText right = value(operands[1]);
  switch (instruction.opcode) {
  case Opcode::Pow: // `-2**2` is 4 in LinuxCNC: a unary minus binds first
    return {bracketedUnlessTighter(left, LinuxcncForm::Negation) + "**" +
                rightOperand(right, LinuxcncForm::Negation),
            LinuxcncForm::Power};
  case Opcode::Mul:
  case Opcode::Div:
    return {bracketedUnlessTighter(left, LinuxcncForm::Multiplicative) +
                (instruction.opcode == Opcode::Mul ? "*" : "/") +
                rightOperand(right, LinuxcncForm::Power),
            LinuxcncForm::Multiplicative};
  default:
    break;
  }
  char sign = instruction.opcode == Opcode::Add ? '+' : '-';
  std::optional<double> number = constantOf(operands[1]);
  if (number && *number < 0) { // a+-3. is written a-3.
    sign = sign == '+' ? '-' : '+';
    right = {constant(-*number), LinuxcncForm::Atom};
  }
  return {bracketedUnlessTighter(left, LinuxcncForm::Additive) + sign +
              rightOperand(right, LinuxcncForm::Multiplicative),
          LinuxcncForm::Additive};
}

// The argument of SIN/COS/TAN in degrees, a constant factor folded into the
// conversion: `#31*114.591559026` rather than `[#31*2.]*57.2957795131`.
std::string LinuxcncExpressionWriter::degrees(ir::ValueId radians) const {
  const ir::Instruction& instruction = function_.definition(radians);
  bool inline_ = !allocation_.inVariable(radians) && instruction.opcode != Opcode::Param;
  if (inline_ && (instruction.opcode == Opcode::Mul || instruction.opcode == Opcode::Div)) {
    std::optional<double> left = constantOf(instruction.operands[0]);
    std::optional<double> right = constantOf(instruction.operands[1]);
    if (instruction.opcode == Opcode::Mul && (left || right)) {
      ir::ValueId other = left ? instruction.operands[1] : instruction.operands[0];
      double factor = (left ? *left : *right) * degreesPerRadian;
      return bracketedUnlessTighter(value(other), LinuxcncForm::Multiplicative) + "*" +
             constant(factor);
    }
    if (instruction.opcode == Opcode::Div && right && *right != 0) {
      return bracketedUnlessTighter(value(instruction.operands[0]), LinuxcncForm::Multiplicative) +
             "*" + constant(degreesPerRadian / *right);
    }
  }
  return bracketedUnlessTighter(value(radians), LinuxcncForm::Multiplicative) + "*" +
         constant(degreesPerRadian);
}

LinuxcncText LinuxcncExpressionWriter::function(const ir::Instruction& instruction) const {
  Opcode opcode = instruction.opcode;
  const std::vector<ir::ValueId>& operands = instruction.operands;
  std::string toRadians = constant(1 / degreesPerRadian);
  if (isTrigonometric(opcode)) {
    return {fmt::format("{}[{}]", functionName(opcode), degrees(operands[0])), LinuxcncForm::Atom};
  }
  if (isInverseTrigonometric(opcode)) {
    return {fmt::format("{}[{}]*{}", functionName(opcode), value(operands[0]).text, toRadians),
            LinuxcncForm::Multiplicative};
  }
  if (opcode == Opcode::Atan || opcode == Opcode::Atan2) {
    // ATAN[y]/[x] is the only arctangent, -180..180 degrees as atan2.
    std::string x = opcode == Opcode::Atan ? "1" : value(operands[1]).text;
    return {fmt::format("ATAN[{}]/[{}]*{}", value(operands[0]).text, x, toRadians),
            LinuxcncForm::Multiplicative};
  }
  std::string_view name = functionName(opcode);
  if (name.empty() || operands.size() != 1) {
    // The printer writes the other operations as statements.
    return {"0", LinuxcncForm::Atom};
  }
  return {fmt::format("{}[{}]", name, value(operands[0]).text), LinuxcncForm::Atom};
}

LinuxcncText LinuxcncExpressionWriter::conditionText(ir::ValueId value, bool negated) const {
  const ir::Instruction& instruction = function_.definition(value);
  if (allocation_.inVariable(value)) {
    return {fmt::format("{} {} 0", variable(value), negated ? "EQ" : "NE"),
            LinuxcncForm::Comparison};
  }
  switch (instruction.opcode) {
  case Opcode::ConstBool:
    return {(instruction.number != 0) != negated ? "1 EQ 1" : "1 EQ 0", LinuxcncForm::Comparison};
  case Opcode::Not:
    return conditionText(instruction.operands[0], !negated);
  case Opcode::And:
  case Opcode::Or: {
    // De Morgan: not (a and b) = (not a) or (not b).
    bool isAnd = (instruction.opcode == Opcode::And) != negated;
    LinuxcncText left = conditionText(instruction.operands[0], negated);
    LinuxcncText right = conditionText(instruction.operands[1], negated);
    return {fmt::format("{} {} {}", bracketedUnlessTighter(left, LinuxcncForm::Logical),
                        isAnd ? "AND" : "OR",
                        bracketedUnlessTighter(right, LinuxcncForm::Comparison)),
            LinuxcncForm::Logical};
  }
  default:
    break;
  }
  std::string_view name = comparisonName(instruction.opcode, negated);
  if (!name.empty()) {
    return {
        fmt::format(
            "{} {} {}",
            bracketedUnlessTighter(this->value(instruction.operands[0]), LinuxcncForm::Additive),
            name,
            bracketedUnlessTighter(this->value(instruction.operands[1]), LinuxcncForm::Additive)),
        LinuxcncForm::Comparison};
  }
  return {fmt::format("{} {} 0", operand(value), negated ? "EQ" : "NE"), LinuxcncForm::Comparison};
}

std::string LinuxcncExpressionWriter::condition(ir::ValueId value, bool negated) const {
  return "[" + conditionText(value, negated).text + "]";
}

} // namespace cncc::backends
