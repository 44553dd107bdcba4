// A TNC program as the virtual TNC reads it: one block a line, each of a
// kind, its values as expression trees (formula entry) or single operands
// (address words, FN operands: a number or a signed parameter).
#pragma once

#include "cncc/backends/heidenhain_controller.h"

#include <array>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::backends::heidenhain {

// A problem of the program at a line (1-based).
class TncProgramError : public std::runtime_error {
public:
  TncProgramError(int line, const std::string& message)
      : std::runtime_error(message), line_(line) {}
  int line() const { return line_; }

private:
  int line_;
};

struct TncExpression {
  enum class Kind { Number, Parameter, Function, Binary, Negation };
  Kind kind = Kind::Number;
  double number = 0;
  int parameter = 0;    // encoded (tnc_profile.h)
  std::string function; // SIN, SQRT, ...
  char op = '+';        // + - * / ^ %
  std::vector<TncExpression> operands;
};

// Parses a formula (the text right of `Qn =`); throws TncProgramError.
TncExpression parseTncFormula(std::string_view text, int line);
// `+10.5`, `-Q5`, `QL3`: a number or a signed parameter.
TncExpression parseTncOperand(std::string_view text, int line);

struct TncAxisWord {
  TncExpression value;
  bool incremental = false;
};

struct TncBlock {
  enum class Kind {
    Begin,
    End,
    BlankForm,
    ToolCall,
    Line,
    CircleCentre,
    Circle,
    Spline,
    Label,
    CallLabel,
    Assign,
    Jump,
    Error,
    Comment,
    Tolerance,
  };
  Kind kind = Kind::Comment;
  int line = 0;
  std::string text; // the line as written
  // Begin, End
  bool inches = false;
  // Line, Circle, CircleCentre
  std::optional<TncAxisWord> x, y, z;
  std::optional<TncExpression> feed; // F..
  bool rapid = false;                // FMAX
  std::optional<bool> clockwise;     // C: DR- / DR+
  // L, C: radius compensation RL ('L'), RR ('R') or R0 ('0'); none keeps it
  std::optional<char> radiusCompensation;
  // SPL: K3, K2 and K1 (in that order) of the X, Y and Z axes.
  std::array<std::array<std::optional<double>, 3>, 3> splineCoefficients;
  std::vector<int> mFunctions;
  // ToolCall
  std::optional<int> tool;
  std::optional<TncExpression> speed;
  // Label, CallLabel, Jump: the label; CallLabel: its REP
  int label = 0;
  std::optional<int> repeat;
  // Assign: target = value (FN 1..4 as a Binary); Jump: left comparison right
  int target = 0;
  TncExpression value;
  TncExpression right;
  int comparison = 9; // FN 9 EQU, 10 NE, 11 GT, 12 LT
  int errorNumber = 0;
  std::vector<int> parametersNamed; // every parameter the block names
};

// Reads every line; throws TncProgramError at the first it cannot read.
std::vector<TncBlock> readTncProgram(std::string_view text);

} // namespace cncc::backends::heidenhain
