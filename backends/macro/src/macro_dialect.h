// The table that makes one writer print every macro dialect of the family
// (Fanuc Custom Macro B, Mitsubishi M80, LinuxCNC o-word programs): how a
// program opens and ends, how variables, numbers, comments, loops and
// conditions are written, and how the operations a dialect has no word for
// become statements. A new dialect of the family is a new table
// (customMacroDialect and linuxcncDialect are the two there are).
#pragma once

#include "cncc/backends/controller_profile.h"
#include "cncc/backends/nurbs_blocks.h"
#include "cncc/ir/ir.h"

#include <array>
#include <climits>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace cncc::backends {

// How an expression's text binds; a position names the forms it takes bare.
enum class MacroForm : std::uint8_t {
  Atom,           // `#5`, `#[100+#3]`, `3.`, `[..]`
  Function,       // `SIN[..]`
  NegativeNumber, // `-3.`
  Negation,       // `-#5`
  Power,          // `a**b`
  Multiplicative, // `a*b`, `a/b`
  Additive,       // `a+b`, `a-b`
  Comparison,     // `a LT b`
  Logical,        // `c AND d`
};

// Where a piece of text stands in a larger one.
enum class MacroPosition : std::uint8_t {
  LeftOfAdditive,
  RightOfAdditive,
  LeftOfMultiplicative,
  RightOfMultiplicative,
  UnderNegation,
  PowerOperand,
  Compared,           // an operand of LT, EQ, ..
  LeftOfLogical,      // left of AND / OR
  RightOfLogical,     // right of AND / OR
  Operand,            // an address word's value, a function's whole argument list
  AssignedValue,      // a value assigned whole: `#5=` value
  AssignedDefinition, // an instruction's own expression assigned to its variable
  Count
};

// The forms that stand bare at a position, one bit each.
using MacroForms = std::uint16_t;
constexpr MacroForms formBit(MacroForm form) {
  return static_cast<MacroForms>(1u << static_cast<unsigned>(form));
}
template <typename... Forms> constexpr MacroForms formsOf(Forms... forms) {
  return static_cast<MacroForms>((formBit(forms) | ... | 0));
}
inline constexpr MacroForms everyForm = 0x1ff;
// The bare forms of each position.
using MacroBareForms = std::array<MacroForms, static_cast<std::size_t>(MacroPosition::Count)>;

// WHILE [c] DOm .. ENDm with IF [c] GOTO n / Nn jumps (Custom Macro B), or
// o-words: `o100 while [c]` .. `o100 endwhile`, `o101 if` .. `o101 endif`.
enum class ControlWords { WhileDoEnd, OWords };
// `(COMMENT)` or `; comment`.
enum class CommentStyle { Parenthesised, Semicolon };
// How a callable program receives its parameters and says so in its header:
// G65 argument letters (`CALL G65 P1000 A3.`), or positional o-word call
// arguments (`call: o<part> call [3.]`, `#1` the first).
enum class CallStyle { ArgumentLetters, PositionalArguments };
// a to the power b: `POW[a,b]`, `EXP[LN[a]*b]`, `a**b`.
enum class PowerStyle { PowFunction, ExpOfLn, Operator };
// min and max: `#t=a` then `IF [b LT #t] THEN #t=b`; or a choice between
// both: `o1 if [b LT a]` `#t = b` `o1 else` `#t = a` `o1 endif`.
enum class MinMaxStyle { CompareWithTarget, ChooseBetween };
// fmod: `a-FIX[a/b]*b`; or `ABS[a] MOD ABS[b]` given the sign of a.
enum class RemainderStyle { FixQuotient, SignedAbsMod };

struct MacroNumberFormat {
  int significantDigits = 8;  // of a constant
  int coordinateDecimals = 3; // of a literal coordinate
  double maximumCoordinate = std::numeric_limits<double>::infinity();
  bool limitWholeDigits = true; // a constant with more whole digits is an error
  bool dropLeadingZero = true;  // `.5` rather than `0.5`
};

struct MacroDialect {
  std::string name;           // "fanuc", "m80", "linuxcnc"
  std::string controllerName; // in messages: "the controller", "LinuxCNC"
  std::string linesName;      // in messages: "blocks", "lines"
  // ---- program frame
  std::vector<std::string> programStart; // `{number}` is the program number
  std::vector<std::string> mainEnd;      // `{name}` the subroutine's name
  std::vector<std::string> callableEnd;
  std::string subroutineStart; // after the header of a callable program; may be empty
  CallStyle callStyle = CallStyle::ArgumentLetters;
  int maximumCallArguments = INT_MAX;
  bool parametersBeforeSetUp = false; // parameters assigned before the start blocks
  bool fillsVacantParameters = true;  // `#0` is vacant: a macro keeps what its caller set
  bool listsVariables = true;         // header lines: which variables hold what
  // ---- lines
  CommentStyle comments = CommentStyle::Parenthesised;
  bool upperCaseComments = true; // the header's own words
  bool diameterOnToolBlock = true;
  int maximumLineLength = 128;
  std::string assignment = "="; // between the variable and its value
  std::string alarmStart = "#3000=1 (";
  std::string alarmEnd = ")";
  // ---- control flow
  ControlWords control = ControlWords::WhileDoEnd;
  bool hasThen = true; // `IF [c] THEN statement`
  int firstLabel = 1;
  int maximumLabel = INT_MAX;
  int maximumLoopNesting = INT_MAX;
  // Modal words survive loops (printed from what holds at entry and after a
  // pass), and a value in a variable counts as in force: SSA values do not
  // change while they are used.
  bool keepsWordsThroughLoops = true;
  // ---- expressions
  MacroNumberFormat numbers;
  MacroBareForms bareForms{};
  std::vector<std::pair<ir::Opcode, std::string_view>> functionWords; // SIN, FIX, ..
  PowerStyle power = PowerStyle::ExpOfLn;
  MinMaxStyle minMax = MinMaxStyle::CompareWithTarget;
  RemainderStyle remainder = RemainderStyle::FixQuotient;
  std::vector<ir::Opcode> statementOpcodes; // operations written as statements of their own
  std::string one = "1.";                   // a loop index's step, ATAN's x where it has none
  std::string trueComparison = "1 EQ 1";
  std::string falseComparison = "0 EQ 1";
  // A bool in a variable is compared with 0 rather than recomputed.
  bool comparesBoolVariables = false;
  // ---- moves
  bool hasNurbsBlocks = true; // G06.2
  NurbsDialect nurbs = NurbsDialect::Fanuc;
  // Cutter radius compensation with the tool's own register is printed as
  // `G41.1/G42.1 D<diameter>` (LinuxCNC's dynamic compensation) rather than
  // `G41/G42 D<register>`.
  bool dynamicCompensation = false;

  bool bare(MacroForm form, MacroPosition position) const {
    return (bareForms[static_cast<std::size_t>(position)] & formBit(form)) != 0;
  }
  bool isStatement(ir::Opcode opcode) const;
  // The word of a function of one operand (SIN, SQRT, FIX); empty if none.
  std::string_view functionWord(ir::Opcode opcode) const;
};

// The bare forms of the positions named (none bare at the others).
MacroBareForms bareFormsOf(std::initializer_list<std::pair<MacroPosition, MacroForms>> positions);

// Custom Macro B's bracket rules (the register allocator's estimate reads
// them too).
MacroBareForms customMacroBareForms();

// Fanuc Custom Macro B and Mitsubishi M80, with the controller's limits.
MacroDialect customMacroDialect(const ControllerProfile& profile);

// Opcodes Custom Macro B writes as statements of their own.
std::vector<ir::Opcode> macroStatementOpcodes();

} // namespace cncc::backends
