#include "heidenhain_formulas.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace cncc::backends {

namespace {

using ir::Opcode;

constexpr double degreesPerRadian = 57.29577951308232;

// Fixed-point with at most `decimals` decimals, no trailing zeros, no
// point without decimals, never `-0`.
std::string fixed(double value, int decimals) {
  std::string text = fmt::format("{:.{}f}", value, std::max(0, decimals));
  if (text.find('.') != std::string::npos) {
    while (text.back() == '0') {
      text.pop_back();
    }
    if (text.back() == '.') {
      text.pop_back();
    }
  }
  return text == "-0" ? "0" : text;
}

std::string_view functionName(Opcode opcode) {
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
  case Opcode::Atan:
    return "ATAN";
  case Opcode::Sqrt:
    return "SQRT";
  case Opcode::Abs:
    return "ABS";
  case Opcode::Exp:
    return "EXP";
  case Opcode::Ln:
    return "LN";
  case Opcode::Neg:
    return "NEG";
  default:
    return "";
  }
}

} // namespace

std::string tncBracketedUnlessTighter(const TncText& text, TncForm loosest) {
  return text.form <= loosest ? text.text : "( " + text.text + " )";
}

std::vector<Opcode> tncStatementOpcodes() {
  return {Opcode::Min,   Opcode::Max,   Opcode::Select, Opcode::Floor,    Opcode::Ceil,
          Opcode::Round, Opcode::Atan2, Opcode::Rem,    Opcode::TableLoad};
}

ir::InlineShape tncInlineShape(const ir::Function&, const ir::Instruction& instruction,
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
  // Trigonometry adds its conversion to or from degrees.
  Opcode opcode = instruction.opcode;
  bool converts = opcode == Opcode::Sin || opcode == Opcode::Cos || opcode == Opcode::Tan ||
                  opcode == Opcode::Asin || opcode == Opcode::Acos || opcode == Opcode::Atan;
  return {depth + 1, ir::InlineForm::Atom, operations + (converts ? 1 : 0)};
}

std::string TncFormulaWriter::number(double value) const {
  if (!std::isfinite(value) || std::abs(value) > profile_.maximumMagnitude) {
    errors_.push_back(fmt::format("the program needs the number {}, beyond the TNC's +-{:.0f}",
                                  value, profile_.maximumMagnitude));
    return "0";
  }
  double magnitude = std::abs(value);
  int wholeDigits = magnitude < 1 ? 1 : static_cast<int>(std::floor(std::log10(magnitude))) + 1;
  return fixed(value, profile_.significantDigits - wholeDigits);
}

std::string TncFormulaWriter::signedNumber(double value) const {
  std::string text = number(value);
  return text.starts_with('-') ? text : "+" + text;
}

std::string TncFormulaWriter::splineCoefficient(double value) const {
  constexpr int decimals = 8; // as the TNC's largest K, 9.99999999, has
  constexpr int largestExponent = 255;
  if (!std::isfinite(value)) {
    errors_.push_back(fmt::format("an SPL coefficient {} is not a number", value));
    return "+0";
  }
  auto signedText = [](std::string text) { return text.starts_with('-') ? text : "+" + text; };
  double largest = profile_.maximumSplineCoefficient;
  if (std::abs(std::stod(fixed(value, decimals))) <= largest) {
    return signedText(fixed(value, decimals));
  }
  // Rescaled: a mantissa from 1 to under 10 (rounded up to 10: one more power).
  int exponent = static_cast<int>(std::floor(std::log10(std::abs(value))));
  std::string mantissa = fixed(value / std::pow(10.0, exponent), decimals);
  if (std::abs(std::stod(mantissa)) > largest) {
    ++exponent;
    mantissa = fixed(value / std::pow(10.0, exponent), decimals);
  }
  if (exponent > largestExponent) {
    errors_.push_back(fmt::format("an SPL coefficient {:g} is beyond the TNC's exponent of {}",
                                  value, largestExponent));
  }
  return fmt::format("{} E+{}", signedText(mantissa), exponent);
}

std::string TncFormulaWriter::signedCoordinate(double value) const {
  if (!std::isfinite(value)) {
    return signedNumber(value);
  }
  std::string text = fixed(value, profile_.coordinateDecimals + (inches_ ? 1 : 0));
  return text.starts_with('-') ? text : "+" + text;
}

std::optional<double> TncFormulaWriter::constantOf(ir::ValueId value) const {
  const ir::Instruction& instruction = function_.definition(value);
  if (instruction.opcode == Opcode::Const) {
    return instruction.number;
  }
  return std::nullopt;
}

bool TncFormulaWriter::atom(ir::ValueId value) const {
  return constantOf(value) || allocation_.inVariable(value);
}

std::string TncFormulaWriter::variable(ir::ValueId value) const {
  return tncParameterName(allocation_.variableOfValue[value.index]);
}

TncText TncFormulaWriter::value(ir::ValueId value) const {
  if (std::optional<double> constant = constantOf(value)) {
    std::string text = number(*constant);
    return {text, text.starts_with('-') ? TncForm::Signed : TncForm::Atom};
  }
  if (allocation_.inVariable(value)) {
    return {variable(value), TncForm::Atom};
  }
  return definition(value);
}

TncText TncFormulaWriter::definition(ir::ValueId value) const {
  return instructionText(function_.definition(value));
}

TncText TncFormulaWriter::instructionText(const ir::Instruction& instruction) const {
  switch (instruction.opcode) {
  case Opcode::Const:
  case Opcode::Param:
  case Opcode::Loop:
    return value(instruction.result);
  case Opcode::Add:
  case Opcode::Sub:
  case Opcode::Mul:
  case Opcode::Div:
  case Opcode::Pow:
    return arithmetic(instruction);
  case Opcode::TableLoad:
    // Never inline: the printer writes a table read as blocks of its own
    // (tncStatementOpcodes).
    errors_.push_back("a table read inside a formula (table.load)");
    return {"0", TncForm::Atom};
  default:
    return function(instruction);
  }
}

TncText TncFormulaWriter::arithmetic(const ir::Instruction& instruction) const {
  const std::vector<ir::ValueId>& operands = instruction.operands;
  TncText left = value(operands[0]);
  TncText right = value(operands[1]);
  switch (instruction.opcode) {
  case Opcode::Pow:
    return {tncBracketedUnlessTighter(left, TncForm::Atom) + " ^ " +
                tncBracketedUnlessTighter(right, TncForm::Atom),
            TncForm::Power};
  case Opcode::Mul:
  case Opcode::Div:
    return {tncBracketedUnlessTighter(left, TncForm::Multiplicative) +
                (instruction.opcode == Opcode::Mul ? " * " : " / ") +
                tncBracketedUnlessTighter(right, TncForm::Power),
            TncForm::Multiplicative};
  default:
    break;
  }
  char sign = instruction.opcode == Opcode::Add ? '+' : '-';
  std::optional<double> constant = constantOf(operands[1]);
  if (constant && *constant < 0) { // a + -3 is written a - 3
    sign = sign == '+' ? '-' : '+';
    right = {number(-*constant), TncForm::Atom};
  }
  return {tncBracketedUnlessTighter(left, TncForm::Additive) + " " + sign + " " +
              tncBracketedUnlessTighter(right, TncForm::Multiplicative),
          TncForm::Additive};
}

// The argument of SIN/COS/TAN in degrees, a constant factor folded into the
// conversion: `QL1 * 114.591559026` rather than `( QL1 * 2 ) * 57.29..`.
std::string TncFormulaWriter::degrees(ir::ValueId radians) const {
  const ir::Instruction& instruction = function_.definition(radians);
  if (!atom(radians) && instruction.opcode == Opcode::Mul) {
    std::optional<double> left = constantOf(instruction.operands[0]);
    std::optional<double> right = constantOf(instruction.operands[1]);
    if (left || right) {
      ir::ValueId other = left ? instruction.operands[1] : instruction.operands[0];
      double factor = (left ? *left : *right) * degreesPerRadian;
      return tncBracketedUnlessTighter(value(other), TncForm::Multiplicative) + " * " +
             tncBracketedUnlessTighter({number(factor), TncForm::Signed}, TncForm::Power);
    }
  }
  return tncBracketedUnlessTighter(value(radians), TncForm::Multiplicative) + " * " +
         number(degreesPerRadian);
}

std::string TncFormulaWriter::functionOf(std::string_view name, ir::ValueId argument) const {
  TncText text = value(argument);
  return fmt::format("{} {}", name, tncBracketedUnlessTighter(text, TncForm::Atom));
}

std::string TncFormulaWriter::fromDegrees(std::string_view name, ir::ValueId argument) const {
  return functionOf(name, argument) + " * " + number(1 / degreesPerRadian);
}

TncText TncFormulaWriter::function(const ir::Instruction& instruction) const {
  Opcode opcode = instruction.opcode;
  const std::vector<ir::ValueId>& operands = instruction.operands;
  std::string_view name = functionName(opcode);
  switch (opcode) {
  case Opcode::Sin:
  case Opcode::Cos:
  case Opcode::Tan:
    return {fmt::format("{} ( {} )", name, degrees(operands[0])), TncForm::Atom};
  case Opcode::Asin:
  case Opcode::Acos:
  case Opcode::Atan:
    return {fromDegrees(name, operands[0]), TncForm::Multiplicative};
  default:
    break;
  }
  if (name.empty() || operands.size() != 1) {
    // The printer writes the other operations as blocks of their own.
    return {"0", TncForm::Atom};
  }
  return {functionOf(name, operands[0]), TncForm::Atom};
}

} // namespace cncc::backends
