// Values written as Custom Macro B expressions: numbers, `#n`, table reads
// `#[base+#i]`, and single-use operations inline in brackets, with the
// operator precedence the controllers share (functions, then * /, then
// + -) so that brackets are written only where they change the meaning.
// Angles: the IR works in radians, SIN/COS/TAN/ASIN/ACOS/ATAN in degrees.
//
// macroInlineShape() is the same rule set seen from the register
// allocator: how deep and long a value's inline text would be.
#pragma once

#include "cncc/backends/controller_profile.h"
#include "cncc/ir/register_allocation.h"

#include <span>
#include <string>
#include <vector>

namespace cncc::backends {

inline constexpr double degreesPerRadian = 57.29577951308232;

// The same shape with `operations` counted as the characters of the text
// (an estimate: variables as `#nn`), for the block length limit.
ir::InlineShape macroInlineShape(const ControllerProfile& profile, const ir::Function& function,
                                 const ir::Instruction& instruction,
                                 std::span<const ir::InlineShape> operands);
ir::InlineShape macroInlineShape(const ir::Function& function, const ir::Instruction& instruction,
                                 std::span<const ir::InlineShape> operands);

// Opcodes that take statements of their own (see MacroStatementWriter).
std::vector<ir::Opcode> macroStatementOpcodes();

// A piece of expression text and how it binds.
struct MacroText {
  std::string text;
  ir::InlineForm form = ir::InlineForm::Atom;
};

class MacroExpressionWriter {
public:
  MacroExpressionWriter(const ir::Function& function, const ir::Allocation& allocation,
                        const ControllerProfile& profile, std::vector<std::string>& errors)
      : function_(function), allocation_(allocation), profile_(profile), errors_(errors) {}

  // A number with at most the profile's significant digits, always with a
  // decimal point, no leading zero: `3.`, `.5`, `-57.29578`.
  std::string constant(double value) const;
  // A literal coordinate with at most the profile's decimals.
  std::string coordinateLiteral(double value) const;

  // The value as it stands on the right of `#n=` (never bracketed).
  MacroText value(ir::ValueId value) const;
  // The value where an address or function argument list needs it whole:
  // an atom as it is, anything else in brackets.
  std::string operand(ir::ValueId value) const;
  // An address word's value: a literal coordinate when constant.
  std::string coordinate(ir::ValueId value) const;
  // The expression of the value's own instruction (ignoring its variable).
  MacroText definition(ir::ValueId value) const;
  // A bool value as a bracketed condition `[#1 LT 2.]`, or its negation.
  std::string condition(ir::ValueId value, bool negated = false) const;
  // `#5` for a value in a variable.
  std::string variable(ir::ValueId value) const;

private:
  MacroText instructionText(const ir::Instruction& instruction) const;
  MacroText arithmetic(const ir::Instruction& instruction) const;
  MacroText function(const ir::Instruction& instruction) const;
  std::string degrees(ir::ValueId radians) const;
  std::string tableRead(const ir::Instruction& instruction) const;
  std::string comparison(const ir::Instruction& instruction, bool negated) const;
  std::optional<double> constantOf(ir::ValueId value) const;

  const ir::Function& function_;
  const ir::Allocation& allocation_;
  const ControllerProfile& profile_;
  std::vector<std::string>& errors_;
};

// Wraps in brackets unless the form needs none where it is used.
std::string bracketedUnless(const MacroText& text, bool keepBare);

} // namespace cncc::backends
