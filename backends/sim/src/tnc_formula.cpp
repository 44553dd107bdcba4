// Formula entry as the TNC reads it: `*`, `/` and `%` before `+` and `-`,
// `^` before those; a function applies to the term right of it (a number,
// a parameter, a function of one, or a bracket).
#include "tnc_program_text.h"

#include <fmt/format.h>

#include <array>
#include <cctype>
#include <charconv>

namespace cncc::backends::heidenhain {

namespace {

constexpr std::array functionNames = {"ASIN", "ACOS", "ATAN", "SQRT", "FRAC", "SIN", "COS", "TAN",
                                      "SQ",   "LN",   "LOG",  "EXP",  "NEG",  "INT", "ABS", "SGN"};

// Bounds the recursion of nested brackets and functions.
constexpr int maximumNesting = 64;

class FormulaParser {
public:
  FormulaParser(std::string_view text, int line) : text_(text), line_(line) {}

  TncExpression parse() {
    TncExpression expression = additive();
    skipSpaces();
    if (position_ != text_.size()) {
      fail(fmt::format("unexpected '{}' in the formula", text_.substr(position_)));
    }
    return expression;
  }

private:
  [[noreturn]] void fail(const std::string& message) const {
    throw TncProgramError(line_, message);
  }

  void skipSpaces() {
    while (position_ < text_.size() && text_[position_] == ' ') {
      ++position_;
    }
  }

  bool accept(char c) {
    skipSpaces();
    if (position_ < text_.size() && text_[position_] == c) {
      ++position_;
      return true;
    }
    return false;
  }

  static TncExpression binary(char op, TncExpression left, TncExpression right) {
    TncExpression expression;
    expression.kind = TncExpression::Kind::Binary;
    expression.op = op;
    expression.operands = {std::move(left), std::move(right)};
    return expression;
  }

  TncExpression additive() {
    TncExpression left = multiplicative();
    for (;;) {
      if (accept('+')) {
        left = binary('+', std::move(left), multiplicative());
      } else if (accept('-')) {
        left = binary('-', std::move(left), multiplicative());
      } else {
        return left;
      }
    }
  }

  TncExpression multiplicative() {
    TncExpression left = power();
    for (;;) {
      char op = 0;
      for (char candidate : {'*', '/', '%'}) {
        if (op == 0 && accept(candidate)) {
          op = candidate;
        }
      }
      if (op == 0) {
        return left;
      }
      left = binary(op, std::move(left), power());
    }
  }

  TncExpression power() {
    TncExpression left = signedTerm();
    while (accept('^')) {
      left = binary('^', std::move(left), signedTerm());
    }
    return left;
  }

  TncExpression signedTerm() {
    if (accept('-')) {
      TncExpression negation;
      negation.kind = TncExpression::Kind::Negation;
      negation.operands = {nested([&] { return signedTerm(); })};
      return negation;
    }
    accept('+');
    return primary();
  }

  template <typename Parse> TncExpression nested(Parse parse) {
    if (++depth_ > maximumNesting) {
      fail(fmt::format("the formula nests deeper than {} levels", maximumNesting));
    }
    TncExpression expression = parse();
    --depth_;
    return expression;
  }

  TncExpression primary() {
    skipSpaces();
    if (accept('(')) {
      TncExpression inner = nested([&] { return additive(); });
      if (!accept(')')) {
        fail("a '(' without its ')' in the formula");
      }
      return inner;
    }
    std::size_t start = position_;
    while (position_ < text_.size() && std::isalnum(static_cast<unsigned char>(text_[position_]))) {
      ++position_;
    }
    std::string_view word = text_.substr(start, position_ - start);
    if (word.empty() || std::isdigit(static_cast<unsigned char>(word[0]))) {
      position_ = start;
      return number();
    }
    if (word == "PI") {
      TncExpression pi;
      pi.number = 3.14159265358979323846;
      return pi;
    }
    for (const char* name : functionNames) {
      if (word == name) {
        TncExpression function;
        function.kind = TncExpression::Kind::Function;
        function.function = std::string(word);
        function.operands = {nested([&] { return signedTerm(); })};
        return function;
      }
    }
    if (word[0] == 'Q') {
      return parseTncOperand(word, line_);
    }
    fail(fmt::format("'{}' is no number, parameter or function of a formula", word));
  }

  TncExpression number() {
    std::size_t start = position_;
    while (
        position_ < text_.size() &&
        (std::isdigit(static_cast<unsigned char>(text_[position_])) || text_[position_] == '.')) {
      ++position_;
    }
    if (start == position_) {
      fail(position_ < text_.size()
               ? fmt::format("unexpected '{}' in the formula", text_.substr(position_))
               : std::string("the formula ends where a value is expected"));
    }
    return parseTncOperand(text_.substr(start, position_ - start), line_);
  }

  std::string_view text_;
  int line_;
  std::size_t position_ = 0;
  int depth_ = 0;
};

std::optional<double> parseNumber(std::string_view text) {
  if (text.starts_with('.')) {
    std::string padded = "0" + std::string(text);
    return parseNumber(padded);
  }
  double value = 0;
  auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size()) {
    return std::nullopt;
  }
  return value;
}

std::optional<int> parameterNumber(std::string_view digits) {
  int value = 0;
  auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (digits.empty() || error != std::errc() || end != digits.data() + digits.size() || value < 0 ||
      value > 9999) {
    return std::nullopt;
  }
  return value;
}

} // namespace

TncExpression parseTncFormula(std::string_view text, int line) {
  return FormulaParser(text, line).parse();
}

TncExpression parseTncOperand(std::string_view text, int line) {
  bool negative = text.starts_with('-');
  if (negative || text.starts_with('+')) {
    text.remove_prefix(1);
  }
  TncExpression operand;
  if (text.starts_with('Q')) {
    int base = 0;
    std::string_view digits = text.substr(1);
    if (digits.starts_with('L') || digits.starts_with('R')) {
      base = digits[0] == 'L' ? tncLocalBase : tncRetainedBase;
      digits.remove_prefix(1);
    }
    std::optional<int> number = parameterNumber(digits);
    if (!number || (base != 0 && *number > 9999)) {
      throw TncProgramError(line, fmt::format("'{}' is no Q parameter", text));
    }
    operand.kind = TncExpression::Kind::Parameter;
    operand.parameter = base + *number;
  } else {
    std::optional<double> number = parseNumber(text);
    if (!number) {
      throw TncProgramError(line, fmt::format("'{}' is no number", text));
    }
    operand.number = *number;
  }
  if (!negative) {
    return operand;
  }
  TncExpression negation;
  negation.kind = TncExpression::Kind::Negation;
  negation.operands = {std::move(operand)};
  return negation;
}

} // namespace cncc::backends::heidenhain
