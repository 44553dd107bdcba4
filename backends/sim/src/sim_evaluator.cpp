#include "sim_evaluator.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace cncc::backends::sim {

namespace {

// Fanuc's variables hold about +-1e47; beyond that is an alarm.
constexpr double largestValue = 1e47;
constexpr double wholeNumberTolerance = 1e-9;

double radians(double degrees) {
  return degrees * std::numbers::pi / 180.0;
}
double degrees(double radians) {
  return radians * 180.0 / std::numbers::pi;
}

bool isWhole(double value) {
  return std::abs(value - std::round(value)) <= wholeNumberTolerance;
}

// AND, OR, XOR and MOD are defined here on whole numbers that are not
// negative only: controllers differ on the rest, so a program must not rely
// on them.
long long wholeOperand(double value, std::string_view operation, const Block& block) {
  if (!isWhole(value) || value < 0 || value > 1e15) {
    failInBlock(block,
                fmt::format("{} of {}: only whole numbers from 0 are portable", operation, value));
  }
  return std::llround(value);
}

double applyFunction(Function function, const std::vector<double>& arguments, const Block& block) {
  double a = arguments[0];
  auto domainError = [&](std::string_view name) {
    failInBlock(block, fmt::format("{}[{}] is outside the function's domain", name, a));
  };
  switch (function) {
  case Function::Sin:
    return std::sin(radians(a));
  case Function::Cos:
    return std::cos(radians(a));
  case Function::Tan:
    if (std::abs(std::cos(radians(a))) < 1e-12) {
      domainError("TAN");
    }
    return std::tan(radians(a));
  case Function::Asin:
    if (a < -1 || a > 1) {
      domainError("ASIN");
    }
    return degrees(std::asin(a));
  case Function::Acos:
    if (a < -1 || a > 1) {
      domainError("ACOS");
    }
    return degrees(std::acos(a));
  case Function::ArcTangent: {
    if (a == 0 && arguments[1] == 0) {
      failInBlock(block, "ATAN[0]/[0] has no angle");
    }
    // Fanuc's default (parameter NAT = 0): 0 to 360 degrees.
    double angle = degrees(std::atan2(a, arguments[1]));
    return angle < 0 ? angle + 360.0 : angle;
  }
  case Function::Sqrt:
    if (a < 0) {
      domainError("SQRT");
    }
    return std::sqrt(a);
  case Function::Abs:
    return std::abs(a);
  case Function::Round:
    return std::round(a); // half away from zero
  case Function::Fix:
    return std::trunc(a);
  case Function::Fup:
    return a < 0 ? std::floor(a) : std::ceil(a);
  case Function::Ln:
    if (a <= 0) {
      domainError("LN");
    }
    return std::log(a);
  case Function::Exp:
    return std::exp(a);
  case Function::Power:
    if (a < 0 && !isWhole(arguments[1])) {
      failInBlock(block, fmt::format("POW[{},{}] has no real value", a, arguments[1]));
    }
    if (a == 0 && arguments[1] < 0) {
      failInBlock(block, "division by zero in POW");
    }
    return std::pow(a, arguments[1]);
  }
  return 0;
}

bool compare(Operator op, Value left, Value right) {
  // Only EQ and NE tell a vacant value from 0.
  if (op == Operator::Equal || op == Operator::NotEqual) {
    bool equal =
        left.vacant || right.vacant ? left.vacant == right.vacant : left.number == right.number;
    return op == Operator::Equal ? equal : !equal;
  }
  double a = left.vacant ? 0 : left.number;
  double b = right.vacant ? 0 : right.number;
  switch (op) {
  case Operator::Greater:
    return a > b;
  case Operator::Less:
    return a < b;
  case Operator::GreaterOrEqual:
    return a >= b;
  default:
    return a <= b;
  }
}

double applyBinary(Operator op, double a, double b, const Block& block) {
  switch (op) {
  case Operator::Add:
    return a + b;
  case Operator::Subtract:
    return a - b;
  case Operator::Multiply:
    return a * b;
  case Operator::Divide:
    if (b == 0) {
      failInBlock(block, "division by zero");
    }
    return a / b;
  case Operator::Modulo: {
    long long divisor = wholeOperand(b, "MOD", block);
    if (divisor == 0) {
      failInBlock(block, "division by zero in MOD");
    }
    return static_cast<double>(wholeOperand(a, "MOD", block) % divisor);
  }
  case Operator::And:
    return static_cast<double>(wholeOperand(a, "AND", block) & wholeOperand(b, "AND", block));
  case Operator::Or:
    return static_cast<double>(wholeOperand(a, "OR", block) | wholeOperand(b, "OR", block));
  case Operator::Xor:
    return static_cast<double>(wholeOperand(a, "XOR", block) ^ wholeOperand(b, "XOR", block));
  default:
    return 0; // comparisons are handled by compare()
  }
}

bool isComparison(Operator op) {
  return op != Operator::Add && op != Operator::Subtract && op != Operator::Multiply &&
         op != Operator::Divide && op != Operator::Modulo && op != Operator::And &&
         op != Operator::Or && op != Operator::Xor;
}

Value checked(double number, const Block& block) {
  if (!std::isfinite(number) || std::abs(number) > largestValue) {
    failInBlock(block, "a value out of the controller's range (about 1e47)");
  }
  return Value::of(number);
}

} // namespace

void failInBlock(const Block& block, const std::string& message) {
  throw SimulationError(block.line, block.text, message);
}

Value evaluate(const Expression& expression, const VariableReader& variables, const Block& block) {
  switch (expression.kind) {
  case Expression::Kind::Number:
    return Value::of(expression.number);
  case Expression::Kind::Variable:
    return variables.read(evaluateVariableNumber(expression.operands[0], variables, block), block);
  case Expression::Kind::Negate:
    return Value::of(-evaluate(expression.operands[0], variables, block).number);
  case Expression::Kind::Binary: {
    Value left = evaluate(expression.operands[0], variables, block);
    Value right = evaluate(expression.operands[1], variables, block);
    if (isComparison(expression.op)) {
      return Value::of(compare(expression.op, left, right) ? 1 : 0);
    }
    return checked(applyBinary(expression.op, left.number, right.number, block), block);
  }
  case Expression::Kind::Call: {
    std::vector<double> arguments;
    for (const Expression& operand : expression.operands) {
      arguments.push_back(evaluate(operand, variables, block).number);
    }
    return checked(applyFunction(expression.function, arguments, block), block);
  }
  }
  return Value::vacantValue();
}

int evaluateVariableNumber(const Expression& expression, const VariableReader& variables,
                           const Block& block) {
  Value value = evaluate(expression, variables, block);
  if (value.vacant || !isWhole(value.number) || value.number < 0 || value.number > 1e8) {
    failInBlock(block, value.vacant ? std::string("the variable number #[..] is vacant")
                                    : fmt::format("#{} is not a variable", value.number));
  }
  return static_cast<int>(std::lround(value.number));
}

int evaluateWholeNumber(const Expression& expression, const VariableReader& variables,
                        const Block& block, std::string_view what) {
  Value value = evaluate(expression, variables, block);
  if (value.vacant || !isWhole(value.number) || std::abs(value.number) > 1e9) {
    failInBlock(block, value.vacant
                           ? fmt::format("{} is vacant", what)
                           : fmt::format("{} must be a whole number, not {}", what, value.number));
  }
  return static_cast<int>(std::lround(value.number));
}

} // namespace cncc::backends::sim
