// LinuxCNC's expressions (the RS274/NGC language as LinuxCNC's interpreter
// reads it), on a line already lower-cased and without spaces:
//
//   value      := [+|-] value | number | #value | #<name> | [expression]
//                 | function[expression] | atan[expression]/[expression]
//                 | exists[#<name>]
//   expression := value { operator value }, by precedence, left to right:
//                 ** ; * / mod ; + - ; eq ne gt ge lt le ; and or xor
//
// The meanings are LinuxCNC's, not Custom Macro B's (sim_evaluator.cpp):
// every parameter holds a number (0 until set), no vacant value; eq and ne
// compare within 0.0001; fix rounds down and fup up; atan gives -180..180
// degrees; mod's result takes the sign of the divisor; a named parameter
// read before it is set is an error.
#pragma once

#include "cncc/backends/sim_program.h"

#include <string>
#include <string_view>
#include <vector>

namespace cncc::backends::sim::linuxcnc {

// Where an error belongs: a line of the program.
struct LineContext {
  int line = 0;
  std::string_view text;
};

[[noreturn]] void failAt(const LineContext& context, const std::string& message);

enum class BinaryOperator {
  Power,
  Multiply,
  Divide,
  Modulo,
  Add,
  Subtract,
  Equal,
  NotEqual,
  Greater,
  GreaterOrEqual,
  Less,
  LessOrEqual,
  And,
  Or,
  Xor,
};

enum class UnaryFunction { Abs, Acos, Asin, Cos, Exp, Fix, Fup, Ln, Round, Sin, Sqrt, Tan };

struct Expression {
  enum class Kind {
    Number,
    Parameter,      // `#value`: operands[0] is the number
    NamedParameter, // `#<name>`
    Negate,         // `-value`
    Binary,         // operands[0] op operands[1]
    Function,       // function[operands[0]]
    ArcTangent,     // atan[operands[0]]/[operands[1]]
    Exists,         // exists[#<name>]
  };
  Kind kind = Kind::Number;
  double number = 0;
  std::string name{}; // NamedParameter, Exists
  BinaryOperator op = BinaryOperator::Add;
  UnaryFunction function = UnaryFunction::Abs;
  std::vector<Expression> operands{};
};

// A position in the normalised code of one line.
class Cursor {
public:
  Cursor(std::string_view code, LineContext context) : code_(code), context_(context) {}
  bool atEnd() const { return position_ >= code_.size(); }
  char peek() const { return atEnd() ? '\0' : code_[position_]; }
  bool consume(char expected);
  bool consumeWord(std::string_view word);
  void expect(char expected, std::string_view what);
  [[noreturn]] void fail(const std::string& message) const { failAt(context_, message); }
  const LineContext& context() const { return context_; }
  std::string_view rest() const { return code_.substr(position_); }
  // Counts a level of nesting (brackets, signs, #): deep nesting is an error.
  void enter();
  void leave() { --depth_; }

private:
  std::string_view code_;
  std::size_t position_ = 0;
  LineContext context_;
  int depth_ = 0;
};

// `[+|-] value` as a word or an assignment takes it.
Expression parseValue(Cursor& cursor);
// What follows `<` of `#<name>`: the name up to `>`.
std::string parseParameterName(Cursor& cursor);
// Whether `expression` is a plain number (a literal word such as `X1.5`).
bool isLiteral(const Expression& expression);

// The parameters an expression reads.
class ParameterSource {
public:
  virtual double numbered(int number, const LineContext& context) const = 0;
  virtual double named(const std::string& name, const LineContext& context) const = 0;
  virtual bool exists(const std::string& name) const = 0;

protected:
  ~ParameterSource() = default;
};

double evaluate(const Expression& expression, const ParameterSource& parameters,
                const LineContext& context);
// The number of a parameter `#value` refers to: whole, 1..5601.
int parameterNumber(double value, const LineContext& context);

} // namespace cncc::backends::sim::linuxcnc
