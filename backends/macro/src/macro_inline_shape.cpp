#include "macro_inline_shape.h"

#include "controller_words.h"
#include "macro_dialect.h"

#include "cncc/backends/gcode_writer.h"

#include <algorithm>
#include <cmath>

namespace cncc::backends {

namespace {

using ir::InlineForm;
using ir::InlineShape;
using ir::Opcode;
using Position = MacroPosition;

// Custom Macro B's bracket rules (MacroDialect::bareForms), seen from the
// register allocator.
bool bareAt(InlineForm form, Position position) {
  static const MacroBareForms bareForms = customMacroBareForms();
  MacroForm macroForm = form == InlineForm::Additive         ? MacroForm::Additive
                        : form == InlineForm::Multiplicative ? MacroForm::Multiplicative
                        : form == InlineForm::Negation       ? MacroForm::Negation
                                                             : MacroForm::Atom;
  return (bareForms[static_cast<std::size_t>(position)] & formBit(macroForm)) != 0;
}

int depthAt(const InlineShape& shape, Position position) {
  return bareAt(shape.form, position) ? shape.bracketDepth : shape.bracketDepth + 1;
}

int operationsOf(std::span<const InlineShape> operands) {
  int operations = 1;
  for (const InlineShape& operand : operands) {
    operations += operand.operations;
  }
  return operations;
}

} // namespace

namespace {

// The characters of an expression's own text: its operator or function
// name, and the operands that are literals.
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
    }
    // A variable's `#nn` is the allocator's to count (AllocationOptions::readCharacters).
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

} // namespace cncc::backends
