#include "sinumerik_expression.h"

#include <fmt/format.h>

#include <array>
#include <charconv>
#include <cmath>
#include <numbers>
#include <string>

namespace cncc::backends::sinumerik {

namespace {

bool isDigit(char c) {
  return c >= '0' && c <= '9';
}

bool isLetter(char c) {
  return (c >= 'A' && c <= 'Z') || c == '_';
}

double radians(double degrees) {
  return degrees * std::numbers::pi / 180;
}

double degrees(double radians) {
  return radians * 180 / std::numbers::pi;
}

class ExpressionParser {
public:
  ExpressionParser(std::string_view text, const std::function<double(int)>& parameter)
      : text_(text), parameter_(parameter) {}

  double parse() {
    double value = logicalOr();
    skipSpaces();
    if (at_ < text_.size()) {
      fail(fmt::format("unexpected '{}'", text_[at_]));
    }
    return value;
  }

private:
  [[noreturn]] void fail(const std::string& message) const {
    throw ExpressionError(fmt::format("{} in '{}'", message, text_));
  }

  void skipSpaces() {
    while (at_ < text_.size() && text_[at_] == ' ') {
      ++at_;
    }
  }

  // Consumes `symbol`; a word must not run on into a name (ANDX).
  bool consume(std::string_view symbol) {
    skipSpaces();
    if (text_.substr(at_, symbol.size()) != symbol) {
      return false;
    }
    bool word = isLetter(symbol.front());
    if (word && at_ + symbol.size() < text_.size() && isLetter(text_[at_ + symbol.size()])) {
      return false;
    }
    at_ += symbol.size();
    return true;
  }

  double logicalOr() {
    double value = logicalAnd();
    while (consume("OR")) {
      double right = logicalAnd();
      value = (value != 0 || right != 0) ? 1 : 0;
    }
    return value;
  }

  double logicalAnd() {
    double value = logicalNot();
    while (consume("AND")) {
      double right = logicalNot();
      value = (value != 0 && right != 0) ? 1 : 0;
    }
    return value;
  }

  double logicalNot() {
    if (consume("NOT")) {
      return logicalNot() == 0 ? 1 : 0;
    }
    return comparison();
  }

  double comparison() {
    double left = sum();
    // Two-character operators first: >= is not > followed by =.
    if (consume("==")) {
      return left == sum() ? 1 : 0;
    }
    if (consume("<>")) {
      return left != sum() ? 1 : 0;
    }
    if (consume(">=")) {
      return left >= sum() ? 1 : 0;
    }
    if (consume("<=")) {
      return left <= sum() ? 1 : 0;
    }
    if (consume(">")) {
      return left > sum() ? 1 : 0;
    }
    if (consume("<")) {
      return left < sum() ? 1 : 0;
    }
    return left;
  }

  double sum() {
    double value = product();
    while (true) {
      if (consume("+")) {
        value += product();
      } else if (consume("-")) {
        value -= product();
      } else {
        return value;
      }
    }
  }

  double product() {
    double value = unary();
    while (true) {
      if (consume("*")) {
        value *= unary();
      } else if (consume("/")) {
        value = divide(value, unary());
      } else if (consume("DIV")) {
        value = std::trunc(divide(value, unary()));
      } else if (consume("MOD")) {
        double divisor = unary();
        divide(value, divisor);
        value = std::fmod(value, divisor);
      } else {
        return value;
      }
    }
  }

  double divide(double dividend, double divisor) const {
    if (divisor == 0) {
      fail("division by zero");
    }
    return dividend / divisor;
  }

  double unary() {
    if (consume("-")) {
      return -unary();
    }
    if (consume("+")) {
      return unary();
    }
    return primary();
  }

  double primary() {
    skipSpaces();
    if (at_ >= text_.size()) {
      fail("a value is missing at the end");
    }
    if (consume("(")) {
      enterBrackets();
      double value = logicalOr();
      close();
      return value;
    }
    char next = text_[at_];
    if (isDigit(next) || next == '.') {
      return number();
    }
    if (!isLetter(next)) {
      fail(fmt::format("unexpected '{}'", next));
    }
    std::size_t begin = at_;
    while (at_ < text_.size() && isLetter(text_[at_])) {
      ++at_;
    }
    if (at_ - begin == 1 && text_[begin] == 'R' && at_ < text_.size() && isDigit(text_[at_])) {
      return parameter_(static_cast<int>(number()));
    }
    while (at_ < text_.size() && (isLetter(text_[at_]) || isDigit(text_[at_]))) {
      ++at_; // ATAN2
    }
    return call(text_.substr(begin, at_ - begin));
  }

  double number() {
    std::size_t begin = at_;
    while (at_ < text_.size() && (isDigit(text_[at_]) || text_[at_] == '.')) {
      ++at_;
    }
    std::string digits(text_.substr(begin, at_ - begin));
    if (digits.front() == '.') {
      digits.insert(digits.begin(), '0');
    }
    if (digits.back() == '.') {
      digits.pop_back();
    }
    double value = 0;
    auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (error != std::errc() || end != digits.data() + digits.size()) {
      fail(fmt::format("'{}' is not a number", text_.substr(begin, at_ - begin)));
    }
    return value;
  }

  double call(std::string_view name) {
    if (!consume("(")) {
      fail(fmt::format("'{}' is not known to this model", name));
    }
    enterBrackets();
    double first = logicalOr();
    if (name == "ATAN2") {
      if (!consume(",")) {
        fail("ATAN2 takes two values, ATAN2(y,x)");
      }
      double second = logicalOr();
      close();
      if (first == 0 && second == 0) {
        fail("ATAN2(0,0) has no angle");
      }
      return degrees(std::atan2(first, second));
    }
    close();
    return apply(name, first);
  }

  // Brackets nest at most this deep (a bound for the recursion).
  static constexpr int maximumDepth = 32;

  void enterBrackets() {
    if (++depth_ > maximumDepth) {
      fail(fmt::format("brackets nested deeper than {}", maximumDepth));
    }
  }

  void close() {
    if (!consume(")")) {
      fail("a '(' without ')'");
    }
    --depth_;
  }

  double apply(std::string_view name, double value) const {
    if (name == "SIN") {
      return std::sin(radians(value));
    }
    if (name == "COS") {
      return std::cos(radians(value));
    }
    if (name == "TAN") {
      return std::tan(radians(value));
    }
    if ((name == "ASIN" || name == "ACOS") && (value < -1 || value > 1)) {
      fail(fmt::format("{}({:g}) is outside the function's domain", name, value));
    }
    if (name == "ASIN") {
      return degrees(std::asin(value));
    }
    if (name == "ACOS") {
      return degrees(std::acos(value));
    }
    if (name == "SQRT" && value < 0) {
      fail(fmt::format("SQRT({:g}) is outside the function's domain", value));
    }
    if (name == "SQRT") {
      return std::sqrt(value);
    }
    if (name == "ABS") {
      return std::abs(value);
    }
    if (name == "POT") {
      return value * value;
    }
    if (name == "TRUNC") {
      return std::trunc(value);
    }
    if (name == "ROUND") {
      return std::round(value);
    }
    if (name == "LN" && value <= 0) {
      fail(fmt::format("LN({:g}) is outside the function's domain", value));
    }
    if (name == "LN") {
      return std::log(value);
    }
    if (name == "EXP") {
      return std::exp(value);
    }
    fail(fmt::format("the function '{}' is not known to this model", name));
  }

  std::string_view text_;
  const std::function<double(int)>& parameter_;
  std::size_t at_ = 0;
  int depth_ = 0;
};

} // namespace

double evaluateExpression(std::string_view text, const std::function<double(int)>& parameter) {
  double value = ExpressionParser(text, parameter).parse();
  if (!std::isfinite(value)) {
    throw ExpressionError(fmt::format("'{}' is out of range", text));
  }
  return value;
}

} // namespace cncc::backends::sinumerik
