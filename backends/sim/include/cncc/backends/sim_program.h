// A Fanuc Custom Macro B / Mitsubishi M80 program as the virtual controller
// reads it: one Block per line, each a macro statement (`#1 = ...`, `IF`,
// `GOTO`, `WHILE .. DOm`, `ENDm`) or a list of address words (`G01 X#1`).
// Reading checks everything a controller checks before running a block:
// the character set, comments, bracket depth, block length, constant
// digits, loop structure (DOm identifiers, nesting, no crossing).
#pragma once

#include "cncc/backends/controller_profile.h"

#include <cstddef>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::backends::sim {

// A problem in the program, on the line it names (1-based; 0 when the
// problem belongs to no line, such as a bad argument). Reading and running
// report every error this way.
class SimulationError : public std::runtime_error {
public:
  SimulationError(int line, std::string lineText, const std::string& message)
      : std::runtime_error(message), line_(line), lineText_(std::move(lineText)) {}
  int line() const { return line_; }
  const std::string& lineText() const { return lineText_; }

private:
  int line_;
  std::string lineText_;
};

enum class Operator {
  Add,
  Subtract,
  Multiply,
  Divide,
  Modulo,
  And,
  Or,
  Xor,
  Equal,
  NotEqual,
  Greater,
  Less,
  GreaterOrEqual,
  LessOrEqual,
};

enum class Function {
  Sin,
  Cos,
  Tan,
  Asin,
  Acos,
  ArcTangent, // ATAN[a]/[b], or ATAN[a,b] where the profile allows it
  Sqrt,
  Abs,
  Round,
  Fix,
  Fup,
  Ln,
  Exp,
  Power, // POW[a,b], where the profile allows it
};

struct Expression {
  enum class Kind {
    Number,   // `number`
    Variable, // `#n` or `#[e]`: operands[0] is the variable number
    Negate,   // `-e`
    Binary,   // operands[0] `op` operands[1]
    Call,     // `function[operands...]`
  };
  Kind kind = Kind::Number;
  double number = 0;
  Operator op = Operator::Add;
  Function function = Function::Sin;
  std::vector<Expression> operands;
};

// An address word `X1.5`, `X#1`, `X-[#1*2]`.
struct Word {
  char letter = 'G';
  Expression value;
  bool isLiteral = false; // a plain number, not an expression
  bool literalHasPoint = false;
  int literalDecimals = 0;    // digits after the decimal point
  bool containsRound = false; // ROUND inside the value (its meaning differs by controller)
};

struct Block {
  enum class Kind {
    Empty,       // nothing but a sequence number, a comment or spaces
    ProgramName, // `O1234`
    EndOfRecord, // `%` after the program
    Assignment,  // `#n = e`, `#[e] = e`
    Goto,        // `GOTO n`
    IfGoto,      // `IF [c] GOTO n`
    IfThen,      // `IF [c] THEN #n = e`
    While,       // `WHILE [c] DOm`, or a bare `DOm` (an endless loop)
    End,         // `ENDm`
    Words,       // address words
  };
  Kind kind = Kind::Empty;
  int line = 0;
  std::string text;    // the line as written, for messages
  std::string comment; // the first comment's text, without brackets
  std::optional<int> sequenceNumber;
  int programNumber = 0; // ProgramName

  Expression condition;      // IfGoto, IfThen, While (absent for a bare DO)
  bool hasCondition = false; // While: false for a bare DOm
  Expression target;         // Goto, IfGoto: the sequence number
  Expression variable;       // Assignment, IfThen: the variable number
  Expression value;          // Assignment, IfThen: the value
  int loopIdentifier = 0;    // While, End: m of DOm / ENDm
  std::size_t partner = 0;   // While: its End; End: its While
  // The While blocks of the loops this block is inside, outermost first. An
  // End block is inside its own loop; a While block is not.
  std::vector<std::size_t> loops;
  std::vector<Word> words;
};

// One `O` program of the file: its blocks are [first, end).
struct ProgramUnit {
  int number = 0; // 0: the file has no `O` line before its first block
  int line = 0;
  std::size_t first = 0;
  std::size_t end = 0;
};

struct ProgramText {
  std::vector<Block> blocks;
  std::vector<ProgramUnit> programs; // in file order; the first is the main program
};

// The controller family whose reading rules and call syntax apply beyond the
// profile's limits (backends/sim/README.md has the table and its sources).
enum class ControllerFamily { Fanuc, Mitsubishi };

// How the reader takes a program. Strict (the default) is the conservative
// reading the compiler's own output must pass: `( )` comments in upper case,
// one block a line, macro words written in full. Otherwise the program is
// read as the family's controller reads shop programs: `;` ends a block,
// comments may hold lower-case letters, and where the profile says the
// control reads them (ControllerProfile::macroWordAbbreviations) the
// two-letter abbreviations of macro words (WH for WHILE) are accepted.
struct ReadingRules {
  bool strict = true;
  ControllerFamily family = ControllerFamily::Fanuc;
  // Strict, but comments may hold lower case: the compiler's output for a
  // machine that writes comments as the source has them.
  bool lowerCaseComments = false;

  bool allowsAbbreviations(const ControllerProfile& profile) const {
    return !strict && profile.macroWordAbbreviations;
  }
};

// The family of a controller profile ("m80": Mitsubishi, every other Fanuc).
ControllerFamily controllerFamilyOf(std::string_view profile);

// Reads a whole program file; throws SimulationError at the first problem.
ProgramText readProgram(std::string_view text, const ControllerProfile& profile,
                        const ReadingRules& rules = {});

} // namespace cncc::backends::sim
