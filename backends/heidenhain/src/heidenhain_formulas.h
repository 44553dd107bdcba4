// Values written as TNC formulas (formula entry, iTNC 530 / TNC 640):
// `Q5 = QL1 * 0.6 + SIN ( QL2 * 57.2957795131 )`. Multiplication and
// division bind before addition and subtraction, `^` before both; a
// function (SIN, SQRT, INT, NEG, ...) applies to the term right of it, so
// anything but a number or a parameter is bracketed after it. A negative
// number is bracketed wherever it is not the first term. Angles: the IR
// works in radians, the TNC's SIN/COS/TAN/ASIN/ACOS/ATAN in degrees.
//
// An address word or a jump's comparison takes a number or one parameter,
// never a formula: `atom()` says whether a value is written so.
#pragma once

#include "cncc/backends/tnc_profile.h"
#include "cncc/ir/register_allocation.h"

#include <optional>
#include <span>
#include <string>
#include <vector>

namespace cncc::backends {

// How a formula binds, loosest last; Signed is a leading minus.
enum class TncForm { Atom, Power, Multiplicative, Signed, Additive };

struct TncText {
  std::string text;
  TncForm form = TncForm::Atom;
};

// The register allocator's view: how many operations a value's formula
// writes (the block length is what limits it).
ir::InlineShape tncInlineShape(const ir::Function& function, const ir::Instruction& instruction,
                               std::span<const ir::InlineShape> operands);

// Operations the printer writes as several blocks (jumps around
// assignments): min, max, select, floor, ceil, round, atan2, rem, and
// table.load (jumps to the entry's value).
std::vector<ir::Opcode> tncStatementOpcodes();

class TncFormulaWriter {
public:
  TncFormulaWriter(const ir::Function& function, const ir::Allocation& allocation,
                   const TncProfile& profile, bool inches, std::vector<std::string>& errors)
      : function_(function), allocation_(allocation), profile_(profile), inches_(inches),
        errors_(errors) {}

  // `+3`, `-0.5`: signed, as FN 0 and address words take numbers; a value
  // beyond the profile's magnitude or not finite is an error.
  std::string signedNumber(double value) const;
  // A coordinate to the profile's decimals (one more in inches), signed.
  std::string signedCoordinate(double value) const;
  // An SPL coefficient: `+0.12345678`, or beyond the profile's largest
  // |K| a mantissa within it and an exponent word, `+1.2345678 E+2`.
  std::string splineCoefficient(double value) const;
  // `3`, `-0.5`: a number inside a formula.
  std::string number(double value) const;

  std::optional<double> constantOf(ir::ValueId value) const;
  const ir::Instruction& definitionOf(ir::ValueId value) const {
    return function_.definition(value);
  }
  // A constant, a part parameter or a value in a parameter.
  bool atom(ir::ValueId value) const;
  // The parameter that holds the value: `Q1`, `QL7`.
  std::string variable(ir::ValueId value) const;
  // The value as a formula (brackets only inside).
  TncText value(ir::ValueId value) const;
  // The formula of the value's own instruction, ignoring its parameter.
  TncText definition(ir::ValueId value) const;

private:
  TncText instructionText(const ir::Instruction& instruction) const;
  TncText arithmetic(const ir::Instruction& instruction) const;
  TncText function(const ir::Instruction& instruction) const;
  std::string degrees(ir::ValueId radians) const;
  std::string functionOf(std::string_view name, ir::ValueId value) const;
  std::string fromDegrees(std::string_view name, ir::ValueId value) const;

  const ir::Function& function_;
  const ir::Allocation& allocation_;
  const TncProfile& profile_;
  bool inches_;
  std::vector<std::string>& errors_;
};

// The text bracketed unless it binds at least as tightly as `loosest`.
std::string tncBracketedUnlessTighter(const TncText& text, TncForm loosest);

} // namespace cncc::backends
