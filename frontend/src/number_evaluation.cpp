// The fast path of compile-time evaluation: expressions whose value is a
// number (most of what a part computes, and every sample of a polar or
// parametric curve) evaluated to doubles, without Values. It computes
// exactly what Evaluator::evaluateValue computes, with the same arithmetic,
// and counts the same steps; wherever that path would report a problem or
// produce something other than a number, this one gives up and the caller
// evaluates the expression the ordinary way.
#include "evaluator.h"

#include <cmath>

namespace cncc::frontend {

bool Evaluator::evaluateNumber(const Expr& expression, const Bindings& bindings, double& result) {
  if (++steps_ > maximumSteps || expression.type.kind == TypeKind::Error) {
    return false;
  }
  switch (expression.kind) {
  case ExprKind::Number:
    result = as<NumberExpr>(expression).value;
    return true;
  case ExprKind::Name:
    return numberOfName(as<NameExpr>(expression), bindings, result);
  case ExprKind::Unary: {
    const auto& unary = as<UnaryExpr>(expression);
    double operand = 0;
    if (unary.op != UnaryOperator::Negate || !evaluateNumber(*unary.operand, bindings, operand)) {
      return false;
    }
    result = -operand;
    return true;
  }
  case ExprKind::Binary:
    return numberOfBinary(as<BinaryExpr>(expression), bindings, result);
  case ExprKind::Call:
    return numberOfCall(as<CallExpr>(expression), bindings, result);
  default:
    return false;
  }
}

namespace {

bool numberOf(const Value& value, double& result) {
  result = value.number;
  return value.type.kind == TypeKind::Num;
}

// What evaluateNumber does for a number written out (the most common
// operand), for its callers to do in place of the call: the step, the
// checks, the value.
bool writtenNumber(const Expr& expression, std::size_t& steps, std::size_t maximumSteps,
                   double& result) {
  if (++steps > maximumSteps || expression.type.kind == TypeKind::Error) {
    return false;
  }
  result = as<NumberExpr>(expression).value;
  return true;
}

} // namespace

bool Evaluator::numberOfName(const NameExpr& name, const Bindings& bindings, double& result) {
  const Declaration* declaration = name.declaration;
  if (declaration == nullptr) {
    return false;
  }
  switch (declaration->kind) {
  case DeclarationKind::Constant:
    return declaration->value ? numberOf(*declaration->value, result)
                              : numberOf(constantValue(declaration), result);
  case DeclarationKind::Builtin:
    return declaration->value && numberOf(*declaration->value, result);
  default:
    return bindings.findNumber(declaration, result);
  }
}

bool Evaluator::numberOfBinary(const BinaryExpr& binary, const Bindings& bindings, double& result) {
  BinaryOperator op = binary.op;
  if (!isArithmetic(op)) {
    return false;
  }
  double a = 0;
  double b = 0;
  // Numbers written out and names, the most common operands, evaluated as
  // evaluateNumber would (a step, the checks), without the call.
  auto operand = [&](const Expr& expression, double& result) {
    switch (expression.kind) {
    case ExprKind::Number:
      return writtenNumber(expression, steps_, maximumSteps, result);
    case ExprKind::Name:
      return ++steps_ <= maximumSteps && expression.type.kind != TypeKind::Error &&
             numberOfName(as<NameExpr>(expression), bindings, result);
    default:
      return evaluateNumber(expression, bindings, result);
    }
  };
  if (!operand(*binary.left, a) || !operand(*binary.right, b)) {
    return false;
  }
  switch (op) {
  case BinaryOperator::Add:
    result = a + 1 * b;
    break;
  case BinaryOperator::Subtract:
    result = a + -1 * b;
    break;
  case BinaryOperator::Multiply:
    result = a * b;
    break;
  case BinaryOperator::Divide:
  case BinaryOperator::Remainder:
    if (b == 0) {
      return false;
    }
    result = op == BinaryOperator::Divide
                 ? a / b
                 : arithmetic::applyBinary(arithmetic::MathFunction::Rem, a, b);
    break;
  default:
    result = arithmetic::applyBinary(arithmetic::MathFunction::Pow, a, b);
    break;
  }
  return std::isfinite(result);
}

bool Evaluator::numberOfCall(const CallExpr& call, const Bindings& bindings, double& result) {
  using namespace arithmetic;
  const Declaration* declaration = call.declaration;
  if (declaration != nullptr && declaration->kind == DeclarationKind::Function) {
    return numberOfFunctionCall(call, *declaration, bindings, result);
  }
  std::optional<MathFunction> function = numericMathCall(call);
  if (!function) {
    return false;
  }
  std::size_t count = call.arguments.size();
  std::array<double, 2> values{};
  for (std::size_t i = 0; i < count; ++i) {
    if (!evaluateNumber(*call.arguments[i].value, bindings, values[i])) {
      return false;
    }
  }
  if (count == 2) {
    double a = values[0];
    double b = values[1];
    if (binaryArgumentsSwapped(call, *function)) {
      std::swap(a, b);
    }
    result = applyBinary(*function, a, b);
  } else {
    result = applyUnary(*function, values[0]);
  }
  return std::isfinite(result);
}

bool Evaluator::numberOfFunctionCall(const CallExpr& call, const Declaration& function,
                                     const Bindings& bindings, double& result) {
  if (function.function == nullptr || context_.invalidFunctions.contains(&function)) {
    return false;
  }
  const NodeList<Parameter>& parameters = function.function->parameters;
  std::size_t count = parameters.size();
  if (count > Bindings::maximumNumbers || callStack_.size() > 64) {
    return false;
  }
  std::array<const Expr*, Bindings::maximumNumbers> arguments{};
  bindArguments(
      call, count, [&](std::size_t i) -> std::string_view { return parameters[i].name; },
      arguments.data());
  Bindings inner;
  for (std::size_t i = 0; i < count; ++i) {
    double argument = 0;
    if (arguments[i] == nullptr || parameters[i].declaration == nullptr ||
        !evaluateNumber(*arguments[i], bindings, argument)) {
      return false;
    }
    inner.bindNumber(parameters[i].declaration, argument);
  }
  callStack_.push_back(call.span);
  bool evaluated = evaluateNumber(*function.function->body, inner, result);
  callStack_.pop_back();
  return evaluated;
}

} // namespace cncc::frontend
