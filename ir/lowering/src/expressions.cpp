// Expressions as IR arithmetic. What depends on a bound IR value (a part
// parameter, a let computed from one, a curve's `t`) becomes arithmetic;
// everything else is evaluated by the frontend's evaluator to a constant.
#include "part_lowering.h"

#include "cncc/ir/arithmetic.h"

#include <fmt/format.h>

#include <cmath>

namespace cncc::ir::lowering {

using namespace frontend;

bool dependsOn(const Expr& expression, const Bindings& bindings) {
  auto any = [&](const auto& children) {
    for (const auto& child : children) {
      if (child && dependsOn(*child, bindings)) {
        return true;
      }
    }
    return false;
  };
  switch (expression.kind) {
  case ExprKind::Name:
    return bindings.contains(as<NameExpr>(expression).declaration);
  case ExprKind::Unary:
    return dependsOn(*as<UnaryExpr>(expression).operand, bindings);
  case ExprKind::Binary: {
    const auto& binary = as<BinaryExpr>(expression);
    return dependsOn(*binary.left, bindings) || dependsOn(*binary.right, bindings);
  }
  case ExprKind::Call:
    for (const Argument& argument : as<CallExpr>(expression).arguments) {
      if (argument.value && dependsOn(*argument.value, bindings)) {
        return true;
      }
    }
    return false;
  case ExprKind::Point:
    return any(as<PointExpr>(expression).components);
  case ExprKind::List:
    return any(as<ListExpr>(expression).elements);
  case ExprKind::Range: {
    const auto& range = as<RangeExpr>(expression);
    return dependsOn(*range.low, bindings) || dependsOn(*range.high, bindings);
  }
  case ExprKind::Index: {
    const auto& index = as<IndexExpr>(expression);
    return dependsOn(*index.base, bindings) || dependsOn(*index.index, bindings);
  }
  case ExprKind::Member:
    return dependsOn(*as<MemberExpr>(expression).base, bindings);
  case ExprKind::IfElse: {
    const auto& choice = as<IfElseExpr>(expression);
    return dependsOn(*choice.condition, bindings) || dependsOn(*choice.thenValue, bindings) ||
           dependsOn(*choice.elseValue, bindings);
  }
  default:
    return false;
  }
}

Value RenewingEvaluator::evaluate(const Expr& expression, const Environment& environment) {
  if (!evaluator_ || ++evaluations_ > evaluationsPerEvaluator) {
    evaluator_ = std::make_unique<ExpressionEvaluator>(program_, diagnostics_);
    evaluations_ = 1;
  }
  return evaluator_->evaluate(expression, environment);
}

Value PartLowering::evaluate(const Expr& expression, const Environment& environment) {
  scratch_.clear();
  return evaluator_.evaluate(expression, environment);
}

double PartLowering::constantNumber(const Expr& expression, std::string_view what) {
  Value value = evaluate(expression, environment_);
  if (value.type.kind != TypeKind::Num) {
    fail(expression.span, fmt::format("cannot evaluate {} for lowering", what));
  }
  fixParameters(expression, expression.span, what);
  return value.number;
}

Scalar PartLowering::number(const Expr& expression) {
  std::optional<Lowered> lowered = tryLower(expression, bindings_, environment_);
  if (!lowered || lowered->kind != TypeKind::Num) {
    unsupported(expression.span, "this expression");
  }
  return lowered->values.front();
}

std::optional<Lowered> PartLowering::constantOf(const Value& value) {
  switch (value.type.kind) {
  case TypeKind::Num:
    return Lowered{TypeKind::Num, {Scalar::of(value.number)}};
  case TypeKind::Bool:
    return Lowered{TypeKind::Bool, {Scalar::ofBool(value.boolean)}};
  case TypeKind::Point:
    return Lowered{
        TypeKind::Point,
        {Scalar::of(value.point[0]), Scalar::of(value.point[1]), Scalar::of(value.point[2])}};
  default:
    return std::nullopt;
  }
}

std::optional<Lowered> PartLowering::tryLower(const Expr& expression, const Bindings& bindings,
                                              const Environment& environment) {
  // Bound to IR values, or reading parameters through a name the lowering
  // keeps no IR value for (a list of points computed from them).
  if (dependsOn(expression, bindings) || !parametersOf(expression).empty()) {
    if (std::optional<Lowered> lowered = lowerDirect(expression, bindings, environment)) {
      return lowered;
    }
    // Taken at its default.
    fixParameters(expression, expression.span, "this value");
  }
  return constantOf(evaluate(expression, environment));
}

std::optional<Lowered> PartLowering::lowerDirect(const Expr& expression, const Bindings& bindings,
                                                 const Environment& environment) {
  switch (expression.kind) {
  case ExprKind::Name: {
    auto found = bindings.find(as<NameExpr>(expression).declaration);
    return found == bindings.end() ? std::nullopt : std::optional(found->second);
  }
  case ExprKind::Unary:
    return lowerUnary(as<UnaryExpr>(expression), bindings, environment);
  case ExprKind::Binary:
    return lowerBinary(as<BinaryExpr>(expression), bindings, environment);
  case ExprKind::Point: {
    Lowered result{TypeKind::Point, {}};
    for (const ExprPtr& component : as<PointExpr>(expression).components) {
      std::optional<Lowered> value = tryLower(*component, bindings, environment);
      if (!value || value->kind != TypeKind::Num) {
        return std::nullopt;
      }
      result.values.push_back(value->values.front());
    }
    while (result.values.size() < 3) {
      result.values.push_back(Scalar::of(0));
    }
    return result;
  }
  case ExprKind::Member: {
    const auto& member = as<MemberExpr>(expression);
    std::optional<Lowered> base = tryLower(*member.base, bindings, environment);
    if (!base || base->kind != TypeKind::Point) {
      return std::nullopt;
    }
    std::size_t index = member.member == "x" ? 0 : member.member == "y" ? 1 : 2;
    return Lowered{TypeKind::Num, {base->values[index]}};
  }
  case ExprKind::IfElse:
    return lowerIfElse(as<IfElseExpr>(expression), bindings, environment);
  case ExprKind::Call:
    return lowerCall(as<CallExpr>(expression), bindings, environment);
  case ExprKind::Index:
    return lowerIndex(as<IndexExpr>(expression), bindings, environment);
  default:
    return std::nullopt;
  }
}

// An element of a list written out (or the let naming one) at an index
// known here: the element's own expression, lowered.
std::optional<Lowered> PartLowering::lowerIndex(const IndexExpr& index, const Bindings& bindings,
                                                const Environment& environment) {
  if (dependsOn(*index.index, bindings)) {
    return std::nullopt;
  }
  Value position = evaluate(*index.index, environment);
  std::optional<SymbolicList> elements = symbolicList(*index.base, bindings, environment);
  if (position.type.kind != TypeKind::Num || !elements || position.number < 0 ||
      position.number != std::floor(position.number) ||
      position.number >= static_cast<double>(elements->size())) {
    return std::nullopt;
  }
  return (*elements)[static_cast<std::size_t>(position.number)];
}

std::optional<Lowered> PartLowering::lowerUnary(const UnaryExpr& unary, const Bindings& bindings,
                                                const Environment& environment) {
  std::optional<Lowered> operand = tryLower(*unary.operand, bindings, environment);
  if (!operand) {
    return std::nullopt;
  }
  Opcode opcode = unary.op == UnaryOperator::Not ? Opcode::Not : Opcode::Neg;
  for (Scalar& value : operand->values) {
    value = arithmetic_.unary(opcode, value);
  }
  return operand;
}

std::optional<Lowered> PartLowering::lowerIfElse(const IfElseExpr& choice, const Bindings& bindings,
                                                 const Environment& environment) {
  std::optional<Lowered> condition = tryLower(*choice.condition, bindings, environment);
  std::optional<Lowered> yes = tryLower(*choice.thenValue, bindings, environment);
  std::optional<Lowered> no = tryLower(*choice.elseValue, bindings, environment);
  if (!condition || !yes || !no || condition->kind != TypeKind::Bool || yes->kind != no->kind ||
      yes->kind == TypeKind::Bool) {
    return std::nullopt;
  }
  for (std::size_t i = 0; i < yes->values.size(); ++i) {
    yes->values[i] = arithmetic_.select(condition->values.front(), yes->values[i], no->values[i]);
  }
  return yes;
}

std::optional<Lowered> PartLowering::lowerBinary(const BinaryExpr& binary, const Bindings& bindings,
                                                 const Environment& environment) {
  std::optional<Lowered> left = tryLower(*binary.left, bindings, environment);
  std::optional<Lowered> right = tryLower(*binary.right, bindings, environment);
  if (!left || !right) {
    return std::nullopt;
  }
  auto scalar = [&](Opcode opcode) -> std::optional<Lowered> {
    if (left->kind == TypeKind::Point || right->kind == TypeKind::Point) {
      return std::nullopt;
    }
    Scalar result = arithmetic_.binary(opcode, left->values.front(), right->values.front());
    TypeKind kind = opcodeInfo(opcode).result == ValueType::Bool ? TypeKind::Bool : TypeKind::Num;
    return Lowered{kind, {result}};
  };
  // Component-wise arithmetic on points, and num * point scaling.
  auto componentWise = [&](Opcode opcode) -> std::optional<Lowered> {
    if (left->kind != TypeKind::Point && right->kind != TypeKind::Point) {
      return scalar(opcode);
    }
    Lowered result{TypeKind::Point, {}};
    for (std::size_t i = 0; i < 3; ++i) {
      Scalar a = left->kind == TypeKind::Point ? left->values[i] : left->values.front();
      Scalar b = right->kind == TypeKind::Point ? right->values[i] : right->values.front();
      result.values.push_back(arithmetic_.binary(opcode, a, b));
    }
    return result;
  };
  switch (binary.op) {
  case BinaryOperator::Add:
    return componentWise(Opcode::Add);
  case BinaryOperator::Subtract:
    return componentWise(Opcode::Sub);
  case BinaryOperator::Multiply:
    return componentWise(Opcode::Mul);
  case BinaryOperator::Divide:
    return componentWise(Opcode::Div);
  case BinaryOperator::Remainder:
    return scalar(Opcode::Rem);
  case BinaryOperator::Power:
    return scalar(Opcode::Pow);
  case BinaryOperator::Equal:
    return scalar(Opcode::Eq);
  case BinaryOperator::NotEqual:
    return scalar(Opcode::Ne);
  case BinaryOperator::Less:
    return scalar(Opcode::Lt);
  case BinaryOperator::LessEqual:
    return scalar(Opcode::Le);
  case BinaryOperator::Greater:
    return scalar(Opcode::Gt);
  case BinaryOperator::GreaterEqual:
    return scalar(Opcode::Ge);
  case BinaryOperator::And:
    return scalar(Opcode::And);
  case BinaryOperator::Or:
    return scalar(Opcode::Or);
  }
  return std::nullopt;
}

std::optional<Lowered> PartLowering::lowerCall(const CallExpr& call, const Bindings& bindings,
                                               const Environment& environment) {
  const Declaration* declaration = call.declaration;
  if (declaration == nullptr) {
    return std::nullopt;
  }
  std::vector<Lowered> arguments;
  for (const Argument& argument : call.arguments) {
    if (!argument.name.empty()) {
      return std::nullopt;
    }
    std::optional<Lowered> value = tryLower(*argument.value, bindings, environment);
    if (!value) {
      return std::nullopt;
    }
    arguments.push_back(*value);
  }
  if (declaration->kind == DeclarationKind::Builtin) {
    for (const Lowered& argument : arguments) {
      if (argument.kind != TypeKind::Num) {
        return std::nullopt;
      }
    }
    // The math functions' table (cncc/geom/math_functions.h).
    std::optional<Opcode> opcode = mathOpcode(call.callee, static_cast<int>(arguments.size()));
    if (opcode && arguments.size() == 1) {
      return Lowered{TypeKind::Num, {arithmetic_.unary(*opcode, arguments[0].values.front())}};
    }
    if (opcode && arguments.size() == 2) {
      return Lowered{
          TypeKind::Num,
          {arithmetic_.binary(*opcode, arguments[0].values.front(), arguments[1].values.front())}};
    }
    return std::nullopt;
  }
  if (declaration->kind == DeclarationKind::Function && declaration->function != nullptr) {
    const FnItem& function = *declaration->function;
    if (function.parameters.size() != arguments.size() || !function.body) {
      return std::nullopt;
    }
    // Inlined: the body with the parameters bound to the arguments.
    Bindings inner = bindings;
    Environment innerEnvironment = environment;
    for (std::size_t i = 0; i < arguments.size(); ++i) {
      if (dependsOn(*call.arguments[i].value, bindings)) {
        inner[function.parameters[i].declaration] = arguments[i];
      }
      Value argument = evaluate(*call.arguments[i].value, environment);
      if (!argument.isError()) {
        innerEnvironment[function.parameters[i].declaration] = argument;
      }
    }
    return tryLower(*function.body, inner, innerEnvironment);
  }
  return std::nullopt;
}

} // namespace cncc::ir::lowering
