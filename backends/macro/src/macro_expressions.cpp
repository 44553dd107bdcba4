#include "macro_expressions.h"

#include "controller_words.h"

#include "cncc/backends/gcode_writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace cncc::backends {

namespace {

using ir::InlineForm;
using ir::InlineShape;
using ir::Opcode;

// Where an operand stands decides whether it needs brackets.
enum class Position {
  LeftOfAdditive,
  RightOfAdditive,
  LeftOfMultiplicative,
  RightOfMultiplicative,
  UnderNegation,
  Compared
};

bool bareAt(InlineForm form, Position position) {
  switch (position) {
  case Position::LeftOfAdditive:
    return form != InlineForm::Negation;
  case Position::RightOfAdditive:
  case Position::LeftOfMultiplicative:
    return form == InlineForm::Atom || form == InlineForm::Multiplicative;
  case Position::RightOfMultiplicative:
  case Position::UnderNegation:
  case Position::Compared:
    return form == InlineForm::Atom;
  }
  return false;
}

int depthAt(const InlineShape& shape, Position position) {
  return bareAt(shape.form, position) ? shape.bracketDepth : shape.bracketDepth + 1;
}

std::string textAt(const MacroText& text, Position position) {
  return bracketedUnless(text, bareAt(text.form, position));
}

// The right operand of a binary operator: a sign right after the operator
// (`#1*-.5`) is not read by every control, the bracketed form is
// (TARGETS.md: `#1*[-.5]`).
std::string rightOperand(const MacroText& text, Position position) {
  std::string written = textAt(text, position);
  return written.starts_with('-') ? "[" + written + "]" : written;
}

int operationsOf(std::span<const InlineShape> operands) {
  int operations = 1;
  for (const InlineShape& operand : operands) {
    operations += operand.operations;
  }
  return operations;
}

} // namespace

std::string bracketedUnless(const MacroText& text, bool keepBare) {
  return keepBare ? text.text : "[" + text.text + "]";
}

std::vector<ir::Opcode> macroStatementOpcodes() {
  return {Opcode::Min,  Opcode::Max, Opcode::Select, Opcode::Floor,
          Opcode::Ceil, Opcode::Rem, Opcode::Atan,   Opcode::Atan2};
}

namespace {

// The characters of an expression's own text: its operator or function
// name, and the operands that are atoms (a literal, `#nn`).
int ownCharacters(const ir::Function& function, const ir::Instruction& instruction,
                  std::span<const InlineShape> operands, int significantDigits) {
  int characters = 1;
  std::string_view name = sharedFunctionName(instruction.opcode);
  if (!name.empty()) {
    characters = static_cast<int>(name.size()) + 2;
  }
  if (isTrigonometric(instruction.opcode) || isInverseTrigonometric(instruction.opcode)) {
    characters += 10; // *57.29578 or *.01745329, and brackets
  }
  bool additive = instruction.opcode == Opcode::Add || instruction.opcode == Opcode::Sub;
  bool multiplicative = instruction.opcode == Opcode::Mul || instruction.opcode == Opcode::Div;
  for (std::size_t i = 0; i < operands.size(); ++i) {
    if (operands[i].operations > 0) {
      Position position = additive ? (i == 0 ? Position::LeftOfAdditive : Position::RightOfAdditive)
                          : multiplicative ? (i == 0 ? Position::LeftOfMultiplicative
                                                     : Position::RightOfMultiplicative)
                                           : Position::Compared;
      characters += bareAt(operands[i].form, position) ? 0 : 2;
      continue;
    }
    const ir::Instruction& definition = function.definition(instruction.operands[i]);
    if (definition.opcode == Opcode::Const) {
      // As MacroExpressionWriter::constant prints it.
      double magnitude = std::abs(definition.number);
      int whole = magnitude < 1 ? 0 : static_cast<int>(std::floor(std::log10(magnitude))) + 1;
      std::string text =
          formatGcodeNumber(definition.number, std::max(0, significantDigits - whole));
      bool leadingZero = text.starts_with("0.") || text.starts_with("-0.");
      characters += static_cast<int>(text.size()) - (leadingZero && text.size() > 2 ? 1 : 0);
      characters += multiplicative && i == 1 && definition.number < 0 ? 2 : 0; // `*[-.5]`
    } else {
      characters += 3; // #nn
    }
  }
  return characters;
}

} // namespace

InlineShape macroInlineShape(const ControllerProfile& profile, const ir::Function& function,
                             const ir::Instruction& instruction,
                             std::span<const InlineShape> operands) {
  InlineShape shape = macroInlineShape(function, instruction, operands);
  if (shape.operations > 0) {
    int characters = ownCharacters(function, instruction, operands, profile.significantDigits);
    for (const InlineShape& operand : operands) {
      characters += operand.operations;
    }
    shape.operations = characters;
  }
  return shape;
}

InlineShape macroInlineShape(const ir::Function& function, const ir::Instruction& instruction,
                             std::span<const InlineShape> operands) {
  Opcode opcode = instruction.opcode;
  int operations = operationsOf(operands);
  auto at = [&](std::size_t i, Position position) { return depthAt(operands[i], position); };
  // `#1*[-.5]`: a negative literal right of `*` or `/` is bracketed.
  auto negativeLiteral = [&](std::size_t i) {
    const ir::Instruction& definition = function.definition(instruction.operands[i]);
    return definition.opcode == Opcode::Const && definition.number < 0 ? 1 : 0;
  };
  switch (opcode) {
  case Opcode::Const:
  case Opcode::Param:
  case Opcode::Loop:
    return {};
  case Opcode::TableLoad:
    return {1 + at(0, Position::RightOfAdditive), InlineForm::Atom, operations};
  case Opcode::Add:
  case Opcode::Sub:
    return {std::max(at(0, Position::LeftOfAdditive), at(1, Position::RightOfAdditive)),
            InlineForm::Additive, operations};
  case Opcode::Mul:
  case Opcode::Div:
    return {std::max(at(0, Position::LeftOfMultiplicative),
                     at(1, Position::RightOfMultiplicative) + negativeLiteral(1)),
            InlineForm::Multiplicative, operations};
  case Opcode::Neg:
    return {at(0, Position::UnderNegation), InlineForm::Negation, operations};
  case Opcode::Pow: // EXP[LN[a]*b] when the controller has no POW
    return {std::max(2 + operands[0].bracketDepth, 1 + at(1, Position::RightOfMultiplicative)),
            InlineForm::Atom, operations + 1};
  case Opcode::Lt:
  case Opcode::Le:
  case Opcode::Gt:
  case Opcode::Ge:
  case Opcode::Eq:
  case Opcode::Ne:
    return {1 + std::max(at(0, Position::Compared), at(1, Position::Compared)), InlineForm::Atom,
            operations};
  case Opcode::And:
  case Opcode::Or:
    return {1 + std::max(operands[0].bracketDepth, operands[1].bracketDepth), InlineForm::Atom,
            operations};
  case Opcode::Not:
    return operands[0];
  case Opcode::ConstBool:
    return {1, InlineForm::Atom, 1};
  default:
    break;
  }
  if (isTrigonometric(opcode)) { // SIN[x*57.29578]
    return {1 + at(0, Position::LeftOfMultiplicative), InlineForm::Atom, operations + 1};
  }
  if (isInverseTrigonometric(opcode)) { // ASIN[x]*.01745329
    return {1 + operands[0].bracketDepth, InlineForm::Multiplicative, operations + 1};
  }
  // A function of one argument, or an operation printed as statements
  // (its operands are then atoms): one bracket level around the operands.
  int depth = 0;
  for (const InlineShape& operand : operands) {
    depth = std::max(depth, operand.bracketDepth);
  }
  return {1 + depth, InlineForm::Atom, operations};
}

std::string MacroExpressionWriter::constant(double value) const {
  double magnitude = std::abs(value);
  int digits = profile_.significantDigits;
  if (magnitude >= std::pow(10.0, digits) || !std::isfinite(value)) {
    errors_.push_back(
        fmt::format("the number {} needs more than the controller's {} digits", value, digits));
    return "0.";
  }
  int wholeDigits = magnitude < 1 ? 0 : static_cast<int>(std::floor(std::log10(magnitude))) + 1;
  std::string text = formatGcodeNumber(value, std::max(0, digits - wholeDigits));
  // `0.5` -> `.5`, `-0.5` -> `-.5`: the leading zero is no digit of precision.
  if (text.starts_with("0.") && text.size() > 2) {
    text.erase(0, 1);
  } else if (text.starts_with("-0.")) {
    text.erase(1, 1);
  }
  return text;
}

std::string MacroExpressionWriter::coordinateLiteral(double value) const {
  if (std::abs(value) > profile_.maximumCoordinate || !std::isfinite(value)) {
    errors_.push_back(fmt::format("the coordinate {} is beyond the controller's range +-{}", value,
                                  profile_.maximumCoordinate));
    return "0.";
  }
  std::string text = formatGcodeNumber(value, profile_.coordinateDecimals);
  if (text.starts_with("0.") && text.size() > 2) {
    text.erase(0, 1);
  } else if (text.starts_with("-0.")) {
    text.erase(1, 1);
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

std::string MacroExpressionWriter::variable(ir::ValueId value) const {
  return fmt::format("#{}", allocation_.variableOfValue[value.index]);
}

MacroText MacroExpressionWriter::value(ir::ValueId value) const {
  if (std::optional<double> number = constantOf(value)) {
    return {constant(*number), InlineForm::Atom};
  }
  if (allocation_.inVariable(value)) {
    return {variable(value), InlineForm::Atom};
  }
  return definition(value);
}

std::string MacroExpressionWriter::operand(ir::ValueId value) const {
  return textAt(this->value(value), Position::Compared);
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
    return {constant(instruction.number), InlineForm::Atom};
  case Opcode::TableLoad:
    return {tableRead(instruction), InlineForm::Atom};
  case Opcode::Add:
  case Opcode::Sub:
  case Opcode::Mul:
  case Opcode::Div:
  case Opcode::Neg:
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
    return {condition(instruction.result), InlineForm::Atom};
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
  return fmt::format("#[{}+{}]", base, textAt(value(index), Position::RightOfAdditive));
}

MacroText MacroExpressionWriter::arithmetic(const ir::Instruction& instruction) const {
  const std::vector<ir::ValueId>& operands = instruction.operands;
  MacroText left = value(operands[0]);
  if (instruction.opcode == Opcode::Neg) {
    return {"-" + textAt(left, Position::UnderNegation), InlineForm::Negation};
  }
  MacroText right = value(operands[1]);
  bool additive = instruction.opcode == Opcode::Add || instruction.opcode == Opcode::Sub;
  if (additive) {
    char sign = instruction.opcode == Opcode::Add ? '+' : '-';
    std::optional<double> number = constantOf(operands[1]);
    if (number && *number < 0) { // a+-3. is written a-3.
      sign = sign == '+' ? '-' : '+';
      right = {constant(-*number), InlineForm::Atom};
    }
    return {textAt(left, Position::LeftOfAdditive) + sign +
                rightOperand(right, Position::RightOfAdditive),
            InlineForm::Additive};
  }
  char sign = instruction.opcode == Opcode::Mul ? '*' : '/';
  return {textAt(left, Position::LeftOfMultiplicative) + sign +
              rightOperand(right, Position::RightOfMultiplicative),
          InlineForm::Multiplicative};
}

// The argument of SIN/COS/TAN in degrees, a constant factor folded into the
// conversion: `#3*114.59156` rather than `[#3*2.]*57.29578`.
std::string MacroExpressionWriter::degrees(ir::ValueId radians) const {
  const ir::Instruction& instruction = function_.definition(radians);
  if (!allocation_.inVariable(radians) &&
      (instruction.opcode == Opcode::Mul || instruction.opcode == Opcode::Div)) {
    std::optional<double> left = constantOf(instruction.operands[0]);
    std::optional<double> right = constantOf(instruction.operands[1]);
    if (instruction.opcode == Opcode::Mul && (left || right)) {
      ir::ValueId other = left ? instruction.operands[1] : instruction.operands[0];
      double factor = (left ? *left : *right) * degreesPerRadian;
      return textAt(value(other), Position::LeftOfMultiplicative) + "*" + constant(factor);
    }
    if (instruction.opcode == Opcode::Div && right && *right != 0) {
      return textAt(value(instruction.operands[0]), Position::LeftOfMultiplicative) + "*" +
             constant(degreesPerRadian / *right);
    }
  }
  return textAt(value(radians), Position::LeftOfMultiplicative) + "*" + constant(degreesPerRadian);
}

MacroText MacroExpressionWriter::function(const ir::Instruction& instruction) const {
  Opcode opcode = instruction.opcode;
  const std::vector<ir::ValueId>& operands = instruction.operands;
  if (isTrigonometric(opcode)) {
    return {fmt::format("{}[{}]", sharedFunctionName(opcode), degrees(operands[0])),
            InlineForm::Atom};
  }
  if (isInverseTrigonometric(opcode)) {
    return {fmt::format("{}[{}]*{}", sharedFunctionName(opcode), value(operands[0]).text,
                        constant(1 / degreesPerRadian)),
            InlineForm::Multiplicative};
  }
  if (opcode == Opcode::Pow) {
    if (profile_.hasPowerFunction) {
      return {fmt::format("POW[{},{}]", value(operands[0]).text, value(operands[1]).text),
              InlineForm::Atom};
    }
    return {fmt::format("EXP[LN[{}]*{}]", value(operands[0]).text,
                        textAt(value(operands[1]), Position::RightOfMultiplicative)),
            InlineForm::Atom};
  }
  std::string_view name = sharedFunctionName(opcode);
  if (name.empty() || operands.size() != 1) {
    errors_.push_back(
        fmt::format("internal: '{}' cannot be written inline", ir::opcodeInfo(opcode).spelling));
    return {"0.", InlineForm::Atom};
  }
  return {fmt::format("{}[{}]", name, value(operands[0]).text), InlineForm::Atom};
}

std::string MacroExpressionWriter::comparison(const ir::Instruction& instruction,
                                              bool negated) const {
  return fmt::format("[{} {} {}]", operand(instruction.operands[0]),
                     comparisonName(instruction.opcode, negated), operand(instruction.operands[1]));
}

std::string MacroExpressionWriter::condition(ir::ValueId value, bool negated) const {
  const ir::Instruction& instruction = function_.definition(value);
  switch (instruction.opcode) {
  case Opcode::ConstBool:
    return (instruction.number != 0) != negated ? "[1 EQ 1]" : "[0 EQ 1]";
  case Opcode::Not:
    return condition(instruction.operands[0], !negated);
  case Opcode::And:
  case Opcode::Or: {
    // De Morgan: not (a and b) = (not a) or (not b).
    bool isAnd = (instruction.opcode == Opcode::And) != negated;
    return fmt::format("[{} {} {}]", condition(instruction.operands[0], negated),
                       isAnd ? "AND" : "OR", condition(instruction.operands[1], negated));
  }
  default:
    if (!comparisonName(instruction.opcode, false).empty()) {
      return comparison(instruction, negated);
    }
    // A bool that is no comparison (a parameter cannot be one): compare.
    return fmt::format("[{} {} 0]", operand(value), negated ? "EQ" : "NE");
  }
}

} // namespace cncc::backends
