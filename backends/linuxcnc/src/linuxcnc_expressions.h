// Values written as LinuxCNC (RS274NGC) expressions: numbers, `#31`,
// named part parameters `#<_depth>`, table reads `#[31+#40]`, and
// single-use operations inline. Inside brackets LinuxCNC has precedence
// (`**`, then `* / MOD`, then `+ -`, then `EQ NE GT GE LT LE`, then
// `AND OR XOR`), so brackets are written only where they change the
// meaning; a unary minus applies to the value right of it alone. Where a
// word or an assignment takes a value, anything but an atom is bracketed.
// Angles: the IR works in radians, SIN/COS/TAN/ASIN/ACOS/ATAN in degrees.
#pragma once

#include "cncc/ir/register_allocation.h"

#include <optional>
#include <span>
#include <string>
#include <vector>

namespace cncc::backends {

// How an expression binds, loosest last.
enum class LinuxcncForm { Atom, Negation, Power, Multiplicative, Additive, Comparison, Logical };

struct LinuxcncText {
  std::string text;
  LinuxcncForm form = LinuxcncForm::Atom;
};

// The register allocator's view of the same rules: how long a value's
// inline text would be (LinuxCNC has no small bracket-nesting limit; the
// line length is what counts).
ir::InlineShape linuxcncInlineShape(const ir::Function& function,
                                    const ir::Instruction& instruction,
                                    std::span<const ir::InlineShape> operands);

// Opcodes that take statements of their own: min, max, select, rem.
std::vector<ir::Opcode> linuxcncStatementOpcodes();

struct LinuxcncNumberFormat {
  int significantDigits = 12; // constants
  int coordinateDecimals = 4; // literal coordinates
};

class LinuxcncExpressionWriter {
public:
  LinuxcncExpressionWriter(const ir::Function& function, const ir::Allocation& allocation,
                           std::vector<std::string> parameterNames, LinuxcncNumberFormat format,
                           std::vector<std::string>& errors)
      : function_(function), allocation_(allocation), parameterNames_(std::move(parameterNames)),
        format_(format), errors_(errors) {}

  // `3.`, `0.5`, `-57.2957795131`: at most the format's significant digits;
  // a value that is not finite is an error.
  std::string constant(double value) const;
  std::string coordinateLiteral(double value) const;

  // The value as an expression (brackets only inside).
  LinuxcncText value(ir::ValueId value) const;
  // Where a word or an assignment needs one value: an atom or `[...]`.
  std::string operand(ir::ValueId value) const;
  // An address word's value: a literal coordinate when constant.
  std::string coordinate(ir::ValueId value) const;
  // The expression of the value's own instruction, ignoring its variable.
  LinuxcncText definition(ir::ValueId value) const;
  // A bool value as a bracketed condition `[#31 LT 2.]`, or its negation.
  std::string condition(ir::ValueId value, bool negated = false) const;
  // `#31` for a value in a numbered parameter, `#<_depth>` for a part parameter.
  std::string variable(ir::ValueId value) const;
  std::optional<double> constantOf(ir::ValueId value) const;

private:
  LinuxcncText instructionText(const ir::Instruction& instruction) const;
  LinuxcncText arithmetic(const ir::Instruction& instruction) const;
  LinuxcncText function(const ir::Instruction& instruction) const;
  LinuxcncText conditionText(ir::ValueId value, bool negated) const;
  std::string degrees(ir::ValueId radians) const;
  std::string tableRead(const ir::Instruction& instruction) const;

  const ir::Function& function_;
  const ir::Allocation& allocation_;
  std::vector<std::string> parameterNames_;
  LinuxcncNumberFormat format_;
  std::vector<std::string>& errors_; // a number LinuxCNC cannot read (not finite)
};

// The text bracketed unless it binds at least as tightly as `loosest`.
std::string bracketedUnlessTighter(const LinuxcncText& text, LinuxcncForm loosest);

} // namespace cncc::backends
