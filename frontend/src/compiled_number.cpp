// Compiling a number expression of one variable: a walk of the tree that
// follows the number fast path (number_evaluation.cpp) node for node, and
// gives up wherever that path could give up whatever the variable is.
#include "cncc/frontend/compiled_number.h"

#include "evaluator.h"

#include <array>
#include <cmath>

namespace cncc::frontend {

namespace {

// The nodes a compiled expression may visit (the fast path's steps): the
// ordinary evaluation, the fallback where the compiled one gives up, then
// spends at most twice these a point, far within the step budget of the
// evaluator the lowering renews every thousand points.
constexpr std::size_t maximumNodes = 4 * CompiledNumber::maximumOperations;

} // namespace

class NumberCompiler {
public:
  using Code = CompiledNumber::Code;
  using Operand = CompiledNumber::Operand;
  using Operation = CompiledNumber::Operation;

  NumberCompiler(const Environment& environment, const Declaration* variable)
      : environment_(environment), variable_(variable) {}

  std::optional<CompiledNumber> compile(const Expr& expression) {
    if (!mayBeNumber(expression) || !number(expression, nullptr, 0, compiled_.result_)) {
      return std::nullopt;
    }
    return std::move(compiled_);
  }

  // The arithmetic of the fast path for one node: false where it gives up.
  static bool apply(const Operation& operation, double a, double b, double& result) {
    switch (operation.code) {
    case Code::Variable:
      return false;
    case Code::Negate:
      result = -a;
      return true;
    case Code::Add:
      result = a + 1 * b;
      break;
    case Code::Subtract:
      result = a + -1 * b;
      break;
    case Code::Multiply:
      result = a * b;
      break;
    case Code::Divide:
      if (b == 0) {
        return false;
      }
      result = a / b;
      break;
    case Code::Call:
      if (operation.checkDivisor && b == 0) {
        return false;
      }
      result = operation.function(a, b);
      break;
    }
    return std::isfinite(result);
  }

private:
  // A fn call's parameters, bound to the operands of its arguments (the
  // fast path's frame of numbers, with nothing outside it). The outermost
  // expression has none: its names are the variable and `environment_`.
  struct Frame {
    std::array<const Declaration*, Bindings::maximumNumbers> declarations{};
    std::array<Operand, Bindings::maximumNumbers> operands{};
    std::size_t count = 0;
  };

  bool number(const Expr& expression, const Frame* frame, int depth, Operand& result) {
    if (++nodes_ > maximumNodes || expression.type.kind == TypeKind::Error) {
      return false;
    }
    switch (expression.kind) {
    case ExprKind::Number:
      return constant(as<NumberExpr>(expression).value, result);
    case ExprKind::Name:
      return name(as<NameExpr>(expression), frame, result);
    case ExprKind::Unary: {
      const auto& unary = as<UnaryExpr>(expression);
      Operand operand;
      return unary.op == UnaryOperator::Negate && number(*unary.operand, frame, depth, operand) &&
             operation(of(Code::Negate, operand, operand), result);
    }
    case ExprKind::Binary:
      return binary(as<BinaryExpr>(expression), frame, depth, result);
    case ExprKind::Call:
      return call(as<CallExpr>(expression), frame, depth, result);
    default:
      return false;
    }
  }

  bool name(const NameExpr& name, const Frame* frame, Operand& result) {
    const Declaration* declaration = name.declaration;
    if (declaration == nullptr) {
      return false;
    }
    switch (declaration->kind) {
    case DeclarationKind::Constant:
    case DeclarationKind::Builtin:
      // A constant not yet computed is left to the ordinary evaluation
      // (checking computes every constant a part uses).
      return declaration->value && constantValue(*declaration->value, result);
    default:
      break;
    }
    if (frame != nullptr) {
      for (std::size_t i = 0; i < frame->count; ++i) {
        if (frame->declarations[i] == declaration) {
          result = frame->operands[i];
          return true;
        }
      }
      return false;
    }
    if (declaration == variable_) {
      return variable(result);
    }
    auto found = environment_.find(declaration);
    return found != environment_.end() && constantValue(found->second, result);
  }

  bool binary(const BinaryExpr& binary, const Frame* frame, int depth, Operand& result) {
    Operand left;
    Operand right;
    if (!isArithmetic(binary.op) || !number(*binary.left, frame, depth, left) ||
        !number(*binary.right, frame, depth, right)) {
      return false;
    }
    Operation operation = of(Code::Add, left, right);
    switch (binary.op) {
    case BinaryOperator::Add:
      break;
    case BinaryOperator::Subtract:
      operation.code = Code::Subtract;
      break;
    case BinaryOperator::Multiply:
      operation.code = Code::Multiply;
      break;
    case BinaryOperator::Divide:
      operation.code = Code::Divide;
      break;
    case BinaryOperator::Remainder:
      operation.code = Code::Call;
      operation.function = geom::mathFunctionInfo(arithmetic::MathFunction::Rem).compute;
      operation.checkDivisor = true;
      break;
    default:
      operation.code = Code::Call;
      operation.function = geom::mathFunctionInfo(arithmetic::MathFunction::Pow).compute;
      break;
    }
    return this->operation(operation, result);
  }

  bool call(const CallExpr& call, const Frame* frame, int depth, Operand& result) {
    const Declaration* declaration = call.declaration;
    if (declaration != nullptr && declaration->kind == DeclarationKind::Function) {
      return functionCall(call, *declaration, frame, depth, result);
    }
    std::optional<arithmetic::MathFunction> function = numericMathCall(call);
    if (!function) {
      return false;
    }
    std::size_t count = call.arguments.size();
    std::array<Operand, 2> arguments{};
    for (std::size_t i = 0; i < count; ++i) {
      if (!number(*call.arguments[i].value, frame, depth, arguments[i])) {
        return false;
      }
    }
    Operation operation = of(Code::Call, arguments[0], arguments[1]);
    operation.function = geom::mathFunctionInfo(*function).compute;
    if (count == 2 && binaryArgumentsSwapped(call, *function)) {
      std::swap(operation.left, operation.right);
    } else if (count == 1 && !constant(0.0, operation.right)) {
      return false;
    }
    return this->operation(operation, result);
  }

  bool functionCall(const CallExpr& call, const Declaration& function, const Frame* frame,
                    int depth, Operand& result) {
    if (function.function == nullptr || depth >= CompiledNumber::maximumCallDepth) {
      return false;
    }
    const NodeList<Parameter>& parameters = function.function->parameters;
    std::size_t count = parameters.size();
    if (count > Bindings::maximumNumbers) {
      return false;
    }
    std::array<const Expr*, Bindings::maximumNumbers> arguments{};
    Evaluator::bindArguments(
        call, count, [&](std::size_t i) -> std::string_view { return parameters[i].name; },
        arguments.data());
    Frame inner;
    for (std::size_t i = 0; i < count; ++i) {
      if (arguments[i] == nullptr || parameters[i].declaration == nullptr ||
          !number(*arguments[i], frame, depth, inner.operands[i])) {
        return false;
      }
      inner.declarations[i] = parameters[i].declaration;
      inner.count = i + 1;
    }
    return number(*function.function->body, &inner, depth + 1, result);
  }

  static Operation of(Code code, Operand left, Operand right) {
    Operation operation;
    operation.code = code;
    operation.left = left;
    operation.right = right;
    return operation;
  }

  bool constantValue(const Value& value, Operand& result) {
    return value.type.kind == TypeKind::Num && std::isfinite(value.number) &&
           constant(value.number, result);
  }

  bool constant(double value, Operand& result) {
    if (compiled_.constants_.size() >= CompiledNumber::maximumOperations) {
      return false;
    }
    result.constant = true;
    result.index = static_cast<std::uint16_t>(compiled_.constants_.size());
    compiled_.constants_.push_back(value);
    return true;
  }

  bool variable(Operand& result) {
    if (!variableOperand_) {
      Operand operand;
      if (!append(Operation{}, operand)) {
        return false;
      }
      variableOperand_ = operand;
    }
    result = *variableOperand_;
    return true;
  }

  // An operation whose operands are all computed once is computed now;
  // where it gives up, the fast path gives up at every value of the
  // variable, and the expression is not compiled.
  bool operation(const Operation& operation, Operand& result) {
    bool once =
        operation.left.constant && (operation.code == Code::Negate || operation.right.constant);
    if (!once) {
      return append(operation, result);
    }
    double value = 0;
    return apply(operation, compiled_.constants_[operation.left.index],
                 compiled_.constants_[operation.right.index], value) &&
           constant(value, result);
  }

  bool append(const Operation& operation, Operand& result) {
    if (compiled_.operations_.size() >= CompiledNumber::maximumOperations) {
      return false;
    }
    result.constant = false;
    result.index = static_cast<std::uint16_t>(compiled_.operations_.size());
    compiled_.operations_.push_back(operation);
    return true;
  }

  const Environment& environment_;
  const Declaration* variable_;
  CompiledNumber compiled_;
  std::optional<Operand> variableOperand_;
  std::size_t nodes_ = 0;
};

std::optional<CompiledNumber> CompiledNumber::compile(const Expr& expression,
                                                      const Environment& environment,
                                                      const Declaration* variable) {
  return NumberCompiler(environment, variable).compile(expression);
}

bool CompiledNumber::evaluate(double x, double& result) const {
  std::array<double, maximumOperations> values;
  auto read = [&](Operand operand) {
    return operand.constant ? constants_[operand.index] : values[operand.index];
  };
  for (std::size_t i = 0; i < operations_.size(); ++i) {
    const Operation& operation = operations_[i];
    if (operation.code == Code::Variable) {
      values[i] = x;
    } else if (!NumberCompiler::apply(operation, read(operation.left), read(operation.right),
                                      values[i])) {
      return false;
    }
  }
  result = read(result_);
  return true;
}

} // namespace cncc::frontend
