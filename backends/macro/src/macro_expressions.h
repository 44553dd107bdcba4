// Values written as expressions of a macro dialect (MacroDialect): numbers,
// `#n` (LinuxCNC's part parameters `#<_depth>`), table reads
// `#[base+#i]`, and single-use operations inline, bracketed only where the
// dialect's precedence needs it (MacroDialect::bareForms).
// Angles: the IR works in radians, SIN/COS/TAN/ASIN/ACOS/ATAN in degrees.
#pragma once

#include "macro_dialect.h"

#include "cncc/ir/register_allocation.h"

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace cncc::backends {

inline constexpr double degreesPerRadian = 57.29577951308232;

// A piece of expression text and how it binds.
struct MacroText {
  std::string text;
  MacroForm form = MacroForm::Atom;
};

class MacroExpressionWriter {
public:
  // `parameterNames`: the names of the part's parameters where the dialect
  // names them (`#<_depth>`); empty where they are numbered variables.
  MacroExpressionWriter(const ir::Function& function, const ir::Allocation& allocation,
                        const MacroDialect& dialect, std::vector<std::string> parameterNames,
                        std::vector<std::string>& errors)
      : function_(function), allocation_(allocation), dialect_(dialect),
        parameterNames_(std::move(parameterNames)), errors_(errors) {}

  // A number with at most the dialect's significant digits, always with a
  // decimal point: `3.`, `.5` (`0.5` in LinuxCNC), `-57.29578`.
  std::string constant(double value) const;
  // A literal coordinate with at most the dialect's decimals.
  std::string coordinateLiteral(double value) const;

  // The value as an expression (brackets only inside).
  MacroText value(ir::ValueId value) const;
  // The value where an address word or a statement needs it whole.
  std::string operand(ir::ValueId value) const;
  // An address word's value: a literal coordinate when constant.
  std::string coordinate(ir::ValueId value) const;
  // The expression of the value's own instruction (ignoring its variable).
  MacroText definition(ir::ValueId value) const;
  // A bool value as a bracketed condition `[#1 LT 2.]`, or its negation.
  std::string condition(ir::ValueId value, bool negated = false) const;
  // `#5` for a value in a variable, `#<_depth>` for a named parameter.
  std::string variable(ir::ValueId value) const;
  // The variable of the part's parameter `index`.
  std::string parameterVariable(std::size_t index) const;
  std::optional<double> constantOf(ir::ValueId value) const;
  // The text, bracketed unless it stands bare at `position`.
  std::string at(const MacroText& text, MacroPosition position) const;
  // The right operand of a binary operator: a sign right after the operator
  // (`#1*-.5`) is not read by every control; the bracketed form is
  // (TARGETS.md: `#1*[-.5]`).
  std::string rightOperand(const MacroText& text, MacroPosition position) const;

private:
  MacroText instructionText(const ir::Instruction& instruction) const;
  MacroText arithmetic(const ir::Instruction& instruction) const;
  MacroText power(const ir::Instruction& instruction) const;
  MacroText function(const ir::Instruction& instruction) const;
  MacroText conditionText(ir::ValueId value, bool negated) const;
  std::string degrees(ir::ValueId radians) const;
  std::string tableRead(const ir::Instruction& instruction) const;
  bool isNamedParameter(ir::ValueId value) const;

  const ir::Function& function_;
  const ir::Allocation& allocation_;
  const MacroDialect& dialect_;
  std::vector<std::string> parameterNames_;
  std::vector<std::string>& errors_;
};

} // namespace cncc::backends
