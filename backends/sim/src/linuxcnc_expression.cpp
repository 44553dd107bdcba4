#include "linuxcnc_expression.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <numbers>
#include <utility>

namespace cncc::backends::sim::linuxcnc {

namespace {

// Deeper nesting than this is refused rather than risking the stack.
constexpr int maximumNesting = 64;
// LinuxCNC's parameters run from #1 to #5601 (RS274NGC_MAX_PARAMETERS).
constexpr int largestParameter = 5601;
// LinuxCNC's TOLERANCE_EQUAL, used by eq and ne.
constexpr double equalTolerance = 0.0001;

struct OperatorWord {
  std::string_view text;
  BinaryOperator op;
  int precedence;
};

// Longer spellings first, so that `**` is not read as `*`.
constexpr std::array<OperatorWord, 15> operatorWords{{
    {"**", BinaryOperator::Power, 4},
    {"*", BinaryOperator::Multiply, 3},
    {"/", BinaryOperator::Divide, 3},
    {"mod", BinaryOperator::Modulo, 3},
    {"+", BinaryOperator::Add, 2},
    {"-", BinaryOperator::Subtract, 2},
    {"eq", BinaryOperator::Equal, 1},
    {"ne", BinaryOperator::NotEqual, 1},
    {"gt", BinaryOperator::Greater, 1},
    {"ge", BinaryOperator::GreaterOrEqual, 1},
    {"lt", BinaryOperator::Less, 1},
    {"le", BinaryOperator::LessOrEqual, 1},
    {"and", BinaryOperator::And, 0},
    {"or", BinaryOperator::Or, 0},
    {"xor", BinaryOperator::Xor, 0},
}};

struct FunctionWord {
  std::string_view text;
  UnaryFunction function;
};

constexpr std::array<FunctionWord, 12> functionWords{{
    {"abs", UnaryFunction::Abs},
    {"acos", UnaryFunction::Acos},
    {"asin", UnaryFunction::Asin},
    {"cos", UnaryFunction::Cos},
    {"exp", UnaryFunction::Exp},
    {"fix", UnaryFunction::Fix},
    {"fup", UnaryFunction::Fup},
    {"ln", UnaryFunction::Ln},
    {"round", UnaryFunction::Round},
    {"sin", UnaryFunction::Sin},
    {"sqrt", UnaryFunction::Sqrt},
    {"tan", UnaryFunction::Tan},
}};

bool isDigit(char c) {
  return c >= '0' && c <= '9';
}

Expression parseNumber(Cursor& cursor) {
  std::string_view rest = cursor.rest();
  std::size_t length = 0;
  bool point = false;
  int digits = 0;
  while (length < rest.size() && (isDigit(rest[length]) || (rest[length] == '.' && !point))) {
    point = point || rest[length] == '.';
    digits += isDigit(rest[length]) ? 1 : 0;
    ++length;
  }
  if (digits == 0) {
    cursor.fail(rest.empty() ? "a value is missing at the end of the line"
                             : fmt::format("'{}' is not a value", rest.substr(0, 1)));
  }
  if (digits > 17) {
    cursor.fail(
        fmt::format("the number '{}' has more digits than a double holds", rest.substr(0, length)));
  }
  Expression number;
  number.number = std::stod(std::string(rest.substr(0, length)));
  for (std::size_t i = 0; i < length; ++i) {
    cursor.consume(rest[i]);
  }
  return number;
}

Expression parseExpressionInBrackets(Cursor& cursor);

Expression parseFunction(Cursor& cursor) {
  if (cursor.consumeWord("atan")) {
    Expression call{.kind = Expression::Kind::ArcTangent};
    call.operands.push_back(parseExpressionInBrackets(cursor));
    cursor.expect('/', "'/' between atan's two expressions");
    call.operands.push_back(parseExpressionInBrackets(cursor));
    return call;
  }
  if (cursor.consumeWord("exists")) {
    cursor.expect('[', "'[' after exists");
    cursor.expect('#', "a named parameter in exists[#<name>]");
    cursor.expect('<', "a named parameter in exists[#<name>]");
    Expression test{.kind = Expression::Kind::Exists};
    test.name = parseParameterName(cursor);
    cursor.expect(']', "']' after exists's parameter");
    return test;
  }
  for (const FunctionWord& word : functionWords) {
    if (cursor.consumeWord(word.text)) {
      Expression call{.kind = Expression::Kind::Function};
      call.function = word.function;
      call.operands.push_back(parseExpressionInBrackets(cursor));
      return call;
    }
  }
  std::string_view rest = cursor.rest();
  std::size_t letters = 0;
  while (letters < rest.size() && rest[letters] >= 'a' && rest[letters] <= 'z') {
    ++letters;
  }
  cursor.fail(fmt::format("unknown function '{}'", rest.substr(0, letters)));
}

Expression parseExpressionInBrackets(Cursor& cursor) {
  cursor.expect('[', "'['");
  cursor.enter();
  // Precedence climbing over a list of values and operators.
  std::vector<Expression> values;
  std::vector<OperatorWord> operators;
  auto reduce = [&] {
    Expression binary{.kind = Expression::Kind::Binary};
    binary.op = operators.back().op;
    operators.pop_back();
    binary.operands.resize(2);
    binary.operands[1] = std::move(values.back());
    values.pop_back();
    binary.operands[0] = std::move(values.back());
    values.back() = std::move(binary);
  };
  values.push_back(parseValue(cursor));
  while (!cursor.consume(']')) {
    const OperatorWord* found = nullptr;
    for (const OperatorWord& word : operatorWords) {
      if (cursor.consumeWord(word.text)) {
        found = &word;
        break;
      }
    }
    if (found == nullptr) {
      cursor.fail(cursor.atEnd() ? "']' is missing"
                                 : fmt::format("an operator or ']' expected at '{}'",
                                               cursor.rest().substr(0, 8)));
    }
    while (!operators.empty() && operators.back().precedence >= found->precedence) {
      reduce();
    }
    operators.push_back(*found);
    values.push_back(parseValue(cursor));
  }
  while (!operators.empty()) {
    reduce();
  }
  cursor.leave();
  return std::move(values.front());
}

double radians(double degrees) {
  return degrees * std::numbers::pi / 180.0;
}
double degrees(double radians) {
  return radians * 180.0 / std::numbers::pi;
}

double applyFunction(UnaryFunction function, double a, const LineContext& context) {
  auto domain = [&](std::string_view name) {
    failAt(context, fmt::format("{}[{}] is outside the function's domain", name, a));
  };
  switch (function) {
  case UnaryFunction::Abs:
    return std::abs(a);
  case UnaryFunction::Acos:
    if (a < -1 || a > 1) {
      domain("acos");
    }
    return degrees(std::acos(a));
  case UnaryFunction::Asin:
    if (a < -1 || a > 1) {
      domain("asin");
    }
    return degrees(std::asin(a));
  case UnaryFunction::Cos:
    return std::cos(radians(a));
  case UnaryFunction::Exp:
    return std::exp(a);
  case UnaryFunction::Fix:
    return std::floor(a);
  case UnaryFunction::Fup:
    return std::ceil(a);
  case UnaryFunction::Ln:
    if (a <= 0) {
      domain("ln");
    }
    return std::log(a);
  case UnaryFunction::Round:
    return std::round(a); // half away from zero
  case UnaryFunction::Sin:
    return std::sin(radians(a));
  case UnaryFunction::Sqrt:
    if (a < 0) {
      domain("sqrt");
    }
    return std::sqrt(a);
  case UnaryFunction::Tan:
    return std::tan(radians(a));
  }
  return 0;
}

double applyOperator(BinaryOperator op, double a, double b, const LineContext& context) {
  switch (op) {
  case BinaryOperator::Power:
    if (a < 0 && b != std::floor(b)) {
      failAt(context,
             fmt::format("{} ** {}: a negative number to a power that is not whole", a, b));
    }
    return std::pow(a, b);
  case BinaryOperator::Multiply:
    return a * b;
  case BinaryOperator::Divide:
  case BinaryOperator::Modulo: {
    if (b == 0) {
      failAt(context, op == BinaryOperator::Divide ? "division by zero" : "mod by zero");
    }
    if (op == BinaryOperator::Divide) {
      return a / b;
    }
    double rest = std::fmod(a, b);
    return rest != 0 && ((rest < 0) != (b < 0)) ? rest + b : rest;
  }
  case BinaryOperator::Add:
    return a + b;
  case BinaryOperator::Subtract:
    return a - b;
  case BinaryOperator::Equal:
    return std::abs(a - b) < equalTolerance ? 1 : 0;
  case BinaryOperator::NotEqual:
    return std::abs(a - b) < equalTolerance ? 0 : 1;
  case BinaryOperator::Greater:
    return a > b ? 1 : 0;
  case BinaryOperator::GreaterOrEqual:
    return a >= b ? 1 : 0;
  case BinaryOperator::Less:
    return a < b ? 1 : 0;
  case BinaryOperator::LessOrEqual:
    return a <= b ? 1 : 0;
  case BinaryOperator::And:
    return a != 0 && b != 0 ? 1 : 0;
  case BinaryOperator::Or:
    return a != 0 || b != 0 ? 1 : 0;
  case BinaryOperator::Xor:
    return (a != 0) != (b != 0) ? 1 : 0;
  }
  return 0;
}

} // namespace

void failAt(const LineContext& context, const std::string& message) {
  throw SimulationError(context.line, std::string(context.text), message);
}

bool Cursor::consume(char expected) {
  if (peek() != expected) {
    return false;
  }
  ++position_;
  return true;
}

bool Cursor::consumeWord(std::string_view word) {
  if (rest().substr(0, word.size()) != word) {
    return false;
  }
  position_ += word.size();
  return true;
}

void Cursor::expect(char expected, std::string_view what) {
  if (!consume(expected)) {
    fail(fmt::format("{} expected{}", what,
                     atEnd() ? " at the end of the line"
                             : fmt::format(" at '{}'", rest().substr(0, 8))));
  }
}

void Cursor::enter() {
  if (++depth_ > maximumNesting) {
    fail(fmt::format("expressions nest more than {} deep", maximumNesting));
  }
}

std::string parseParameterName(Cursor& cursor) {
  std::string name;
  while (!cursor.consume('>')) {
    char c = cursor.peek();
    if (c == '\0') {
      cursor.fail("'>' is missing after a parameter name");
    }
    if (c == '<' || c == '[' || c == ']' || c == '#') {
      cursor.fail(fmt::format("'{}' in a parameter name", c));
    }
    name.push_back(c);
    cursor.consume(c);
  }
  if (name.empty()) {
    cursor.fail("the parameter name #<> is empty");
  }
  return name;
}

Expression parseValue(Cursor& cursor) {
  cursor.enter();
  Expression value;
  char c = cursor.peek();
  if (c == '-' || c == '+') {
    cursor.consume(c);
    Expression operand = parseValue(cursor);
    if (c == '+') {
      value = std::move(operand);
    } else {
      value.kind = Expression::Kind::Negate;
      value.operands.push_back(std::move(operand));
    }
  } else if (c == '[') {
    value = parseExpressionInBrackets(cursor);
  } else if (cursor.consume('#')) {
    if (cursor.consume('<')) {
      value.kind = Expression::Kind::NamedParameter;
      value.name = parseParameterName(cursor);
    } else {
      value.kind = Expression::Kind::Parameter;
      value.operands.push_back(parseValue(cursor));
    }
  } else if (c >= 'a' && c <= 'z') {
    value = parseFunction(cursor);
  } else {
    value = parseNumber(cursor);
  }
  cursor.leave();
  return value;
}

bool isLiteral(const Expression& expression) {
  return expression.kind == Expression::Kind::Number ||
         (expression.kind == Expression::Kind::Negate && isLiteral(expression.operands[0]));
}

int parameterNumber(double value, const LineContext& context) {
  double whole = std::round(value);
  if (std::abs(value - whole) > 1e-6 || whole < 1 || whole > largestParameter) {
    failAt(context,
           fmt::format("#{} is no parameter: they run from #1 to #{}", value, largestParameter));
  }
  return static_cast<int>(whole);
}

double evaluate(const Expression& expression, const ParameterSource& parameters,
                const LineContext& context) {
  const std::vector<Expression>& operands = expression.operands;
  double result = 0;
  switch (expression.kind) {
  case Expression::Kind::Number:
    return expression.number;
  case Expression::Kind::Parameter:
    return parameters.numbered(parameterNumber(evaluate(operands[0], parameters, context), context),
                               context);
  case Expression::Kind::NamedParameter:
    return parameters.named(expression.name, context);
  case Expression::Kind::Negate:
    return -evaluate(operands[0], parameters, context);
  case Expression::Kind::Binary:
    result = applyOperator(expression.op, evaluate(operands[0], parameters, context),
                           evaluate(operands[1], parameters, context), context);
    break;
  case Expression::Kind::Function:
    result =
        applyFunction(expression.function, evaluate(operands[0], parameters, context), context);
    break;
  case Expression::Kind::ArcTangent:
    result = degrees(std::atan2(evaluate(operands[0], parameters, context),
                                evaluate(operands[1], parameters, context)));
    break;
  case Expression::Kind::Exists:
    return parameters.exists(expression.name) ? 1 : 0;
  }
  if (!std::isfinite(result)) {
    failAt(context, "the expression's value is out of range");
  }
  return result;
}

} // namespace cncc::backends::sim::linuxcnc
