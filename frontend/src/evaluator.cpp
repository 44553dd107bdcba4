#include "evaluator.h"

#include <cmath>
#include <fmt/format.h>

namespace cncc::frontend {

void Evaluator::report(DiagnosticKind kind, SourceSpan span, std::string message) {
  auto key = std::make_pair(static_cast<int>(kind), std::make_pair(span.begin, span.end));
  if (!reported_.insert(key).second) {
    return;
  }
  Diagnostic* diagnostic = context_.report(kind, span, std::move(message));
  for (auto call = callStack_.rbegin(); call != callStack_.rend(); ++call) {
    context_.diagnostics.addNote(diagnostic, *call, "in this call");
  }
}

Value Evaluator::typeError(SourceSpan span, std::string message) {
  report(DiagnosticKind::TypeMismatch, span, std::move(message));
  return {};
}

void Evaluator::reportNonFinite(SourceSpan span, const std::string& what) {
  report(DiagnosticKind::NonFiniteValue, span, fmt::format("{} is not a finite number", what));
}

std::vector<const Expr*> Evaluator::bindArguments(const CallExpr& call,
                                                  const std::vector<std::string>& names) {
  std::vector<const Expr*> bound(names.size(), nullptr);
  std::size_t next = 0;
  for (const Argument& argument : call.arguments) {
    if (argument.name.empty()) {
      while (next < names.size() && bound[next] != nullptr) {
        ++next;
      }
      if (next < names.size()) {
        bound[next++] = argument.value.get();
      }
      continue;
    }
    for (std::size_t i = 0; i < names.size(); ++i) {
      if (names[i] == argument.name && bound[i] == nullptr) {
        bound[i] = argument.value.get();
      }
    }
  }
  return bound;
}

Value Evaluator::constantValue(const Declaration* declaration) {
  if (declaration->value) {
    return *declaration->value;
  }
  auto item = context_.itemOf.find(declaration);
  if (item == context_.itemOf.end() || constantsInProgress_.contains(declaration)) {
    return {};
  }
  constantsInProgress_.insert(declaration);
  std::vector<SourceSpan> savedStack;
  std::swap(savedStack, callStack_);
  Value value = evaluate(*as<ConstItem>(*item->second).value, {});
  std::swap(savedStack, callStack_);
  constantsInProgress_.erase(declaration);
  context_.mutableDeclaration(declaration).value = value;
  return value;
}

Value Evaluator::evaluate(const Expr& expression, const Environment& environment) {
  if (++steps_ > maximumSteps || expression.type.kind == TypeKind::Error) {
    return {};
  }
  switch (expression.kind) {
  case ExprKind::Number:
    return Value::ofNumber(as<NumberExpr>(expression).value);
  case ExprKind::Bool:
    return Value::ofBool(as<BoolExpr>(expression).value);
  case ExprKind::String:
    return Value::ofString(as<StringExpr>(expression).value);
  case ExprKind::Name:
    return evaluateName(as<NameExpr>(expression), environment);
  case ExprKind::Unary:
    return evaluateUnary(as<UnaryExpr>(expression), environment);
  case ExprKind::Binary:
    return evaluateBinary(as<BinaryExpr>(expression), environment);
  case ExprKind::Call:
    return evaluateCall(as<CallExpr>(expression), environment);
  case ExprKind::Point:
    return evaluatePoint(as<PointExpr>(expression), environment);
  case ExprKind::List:
    return evaluateList(as<ListExpr>(expression), environment);
  case ExprKind::Range: {
    const auto& range = as<RangeExpr>(expression);
    Value low = evaluate(*range.low, environment);
    Value high = evaluate(*range.high, environment);
    if (low.type.kind != TypeKind::Num || high.type.kind != TypeKind::Num) {
      return {};
    }
    return Value::ofRange(low.number, high.number);
  }
  case ExprKind::Index:
    return evaluateIndex(as<IndexExpr>(expression), environment);
  case ExprKind::Member:
    return evaluateMember(as<MemberExpr>(expression), environment);
  case ExprKind::IfElse: {
    const auto& choice = as<IfElseExpr>(expression);
    Value condition = evaluate(*choice.condition, environment);
    if (condition.type.kind != TypeKind::Bool) {
      return condition.isError()
                 ? Value{}
                 : typeError(choice.condition->span, "the condition of 'if' must be a bool");
    }
    return evaluate(condition.boolean ? *choice.thenValue : *choice.elseValue, environment);
  }
  case ExprKind::Error:
    return {};
  }
  return {};
}

Value Evaluator::evaluateName(const NameExpr& name, const Environment& environment) {
  const Declaration* declaration = name.declaration;
  if (declaration == nullptr) {
    return {};
  }
  if (declaration->kind == DeclarationKind::Constant) {
    return constantValue(declaration);
  }
  if (declaration->kind == DeclarationKind::Builtin) {
    return declaration->value.value_or(Value{});
  }
  auto found = environment.find(declaration);
  return found == environment.end() ? Value{} : found->second;
}

Value Evaluator::evaluateUnary(const UnaryExpr& unary, const Environment& environment) {
  Value operand = evaluate(*unary.operand, environment);
  if (operand.isError()) {
    return {};
  }
  if (unary.op == UnaryOperator::Not) {
    if (operand.type.kind != TypeKind::Bool) {
      return typeError(unary.span,
                       fmt::format("'!' needs a bool, not a {}", typeName(operand.type)));
    }
    return Value::ofBool(!operand.boolean);
  }
  if (operand.type.kind == TypeKind::Num) {
    return Value::ofNumber(-operand.number);
  }
  if (operand.type.kind == TypeKind::Point) {
    auto [x, y, z] = operand.point;
    return Value::ofPoint({-x, -y, -z}, operand.pointDimensions);
  }
  return typeError(unary.span, fmt::format("cannot negate a {}", typeName(operand.type)));
}

Value Evaluator::evaluateBinary(const BinaryExpr& binary, const Environment& environment) {
  Value left = evaluate(*binary.left, environment);
  if (left.isError()) {
    return {};
  }
  bool logical = binary.op == BinaryOperator::And || binary.op == BinaryOperator::Or;
  if (logical && left.type.kind == TypeKind::Bool) {
    // Short-circuit, so `i > 0 && L[i - 1] > 0` is safe.
    if (left.boolean == (binary.op == BinaryOperator::Or)) {
      return left;
    }
    Value right = evaluate(*binary.right, environment);
    if (!right.isError() && right.type.kind != TypeKind::Bool) {
      return typeError(binary.right->span, "'&&' and '||' need bools");
    }
    return right;
  }
  Value right = evaluate(*binary.right, environment);
  if (right.isError()) {
    return {};
  }
  return evaluateArithmetic(binary, left, right);
}

namespace {

Value combinePoints(const Value& left, const Value& right, double sign) {
  std::array<double, 3> result{};
  for (int i = 0; i < 3; ++i) {
    result[i] = left.point[i] + sign * right.point[i];
  }
  return Value::ofPoint(result, std::max(left.pointDimensions, right.pointDimensions));
}

Value scalePoint(const Value& point, double factor) {
  auto [x, y, z] = point.point;
  return Value::ofPoint({x * factor, y * factor, z * factor}, point.pointDimensions);
}

std::optional<bool> compare(BinaryOperator op, const Value& left, const Value& right) {
  if (left.type.kind == TypeKind::Bool && right.type.kind == TypeKind::Bool) {
    if (op == BinaryOperator::Equal) {
      return left.boolean == right.boolean;
    }
    if (op == BinaryOperator::NotEqual) {
      return left.boolean != right.boolean;
    }
    return std::nullopt;
  }
  if (left.type.kind != TypeKind::Num || right.type.kind != TypeKind::Num) {
    return std::nullopt;
  }
  double a = left.number;
  double b = right.number;
  switch (op) {
  case BinaryOperator::Equal:
    return a == b;
  case BinaryOperator::NotEqual:
    return a != b;
  case BinaryOperator::Less:
    return a < b;
  case BinaryOperator::LessEqual:
    return a <= b;
  case BinaryOperator::Greater:
    return a > b;
  case BinaryOperator::GreaterEqual:
    return a >= b;
  default:
    return std::nullopt;
  }
}

bool isComparison(BinaryOperator op) {
  return op == BinaryOperator::Equal || op == BinaryOperator::NotEqual ||
         op == BinaryOperator::Less || op == BinaryOperator::LessEqual ||
         op == BinaryOperator::Greater || op == BinaryOperator::GreaterEqual;
}

} // namespace

Value Evaluator::evaluateArithmetic(const BinaryExpr& binary, const Value& left,
                                    const Value& right) {
  TypeKind l = left.type.kind;
  TypeKind r = right.type.kind;
  BinaryOperator op = binary.op;
  auto mismatch = [&] {
    return typeError(binary.operatorSpan,
                     fmt::format("'{}' cannot combine a {} and a {}", operatorSpelling(op),
                                 typeName(left.type), typeName(right.type)));
  };
  if (isComparison(op)) {
    std::optional<bool> result = compare(op, left, right);
    return result ? Value::ofBool(*result) : mismatch();
  }
  bool numbers = l == TypeKind::Num && r == TypeKind::Num;
  double a = left.number;
  double b = right.number;
  switch (op) {
  case BinaryOperator::Add:
  case BinaryOperator::Subtract: {
    double sign = op == BinaryOperator::Add ? 1 : -1;
    if (numbers) {
      return checkedNumber(a + sign * b, binary.span, [] { return std::string("the result"); });
    }
    if (l == TypeKind::Point && r == TypeKind::Point) {
      return combinePoints(left, right, sign);
    }
    return mismatch();
  }
  case BinaryOperator::Multiply:
    if (numbers) {
      return checkedNumber(a * b, binary.span, [] { return std::string("the product"); });
    }
    if (l == TypeKind::Num && r == TypeKind::Point) {
      return scalePoint(right, a);
    }
    if (l == TypeKind::Point && r == TypeKind::Num) {
      return scalePoint(left, b);
    }
    return mismatch();
  case BinaryOperator::Divide:
  case BinaryOperator::Remainder:
    if (r != TypeKind::Num ||
        (l != TypeKind::Num && !(l == TypeKind::Point && op == BinaryOperator::Divide))) {
      return mismatch();
    }
    if (b == 0) {
      report(DiagnosticKind::DivisionByZero, binary.right->span,
             fmt::format("{} by zero", op == BinaryOperator::Divide ? "division" : "remainder"));
      return {};
    }
    if (l == TypeKind::Point) {
      return scalePoint(left, 1.0 / b);
    }
    return checkedNumber(op == BinaryOperator::Divide ? a / b : std::fmod(a, b), binary.span,
                         [] { return std::string("the quotient"); });
  case BinaryOperator::Power:
    if (!numbers) {
      return mismatch();
    }
    return checkedNumber(std::pow(a, b), binary.span,
                         [&] { return fmt::format("{:g} ^ {:g}", a, b); });
  default:
    return mismatch();
  }
}

Value Evaluator::evaluateCall(const CallExpr& call, const Environment& environment) {
  const Declaration* declaration = call.declaration;
  if (declaration == nullptr) {
    return {};
  }
  if (declaration->kind == DeclarationKind::Function) {
    return evaluateFunctionCall(call, *declaration, environment);
  }
  if (declaration->kind != DeclarationKind::Builtin) {
    return {};
  }
  if (call.type.kind == TypeKind::Curve) {
    return buildCurve(*this, call, environment);
  }
  return evaluateMathCall(call, environment);
}

Value Evaluator::evaluateFunctionCall(const CallExpr& call, const Declaration& function,
                                      const Environment& environment) {
  if (context_.invalidFunctions.contains(&function) || function.function == nullptr) {
    return {};
  }
  const FnItem& item = *function.function;
  std::vector<std::string> names;
  for (const Parameter& parameter : item.parameters) {
    names.push_back(parameter.name);
  }
  std::vector<const Expr*> arguments = bindArguments(call, names);
  Environment inner;
  for (std::size_t i = 0; i < arguments.size(); ++i) {
    if (arguments[i] == nullptr || item.parameters[i].declaration == nullptr) {
      return {};
    }
    Value argument = evaluate(*arguments[i], environment);
    if (argument.isError()) {
      return {};
    }
    inner[item.parameters[i].declaration] = argument;
  }
  if (callStack_.size() > 64) {
    return {};
  }
  callStack_.push_back(call.span);
  Value result = evaluate(*item.body, inner);
  callStack_.pop_back();
  return result;
}

Value Evaluator::evaluateMathCall(const CallExpr& call, const Environment& environment) {
  const std::string& name = call.callee;
  std::vector<Value> values;
  for (const Argument& argument : call.arguments) {
    values.push_back(evaluate(*argument.value, environment));
    if (values.back().isError()) {
      return {};
    }
  }
  if (name == "len") {
    if (values.size() != 1 || values[0].type.kind != TypeKind::List) {
      return typeError(call.span, "len(...) needs a list");
    }
    return Value::ofNumber(static_cast<double>(values[0].list->size()));
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (values[i].type.kind != TypeKind::Num) {
      return typeError(call.arguments[i].value->span,
                       fmt::format("'{}' needs numbers, not a {}", name, typeName(values[i].type)));
    }
  }
  if (values.size() == 2) {
    // Named arguments may come in any order: put them in parameter order.
    std::vector<std::string> names = name == "atan2" ? std::vector<std::string>{"y", "x"}
                                     : name == "pow" ? std::vector<std::string>{"base", "exponent"}
                                                     : std::vector<std::string>{"a", "b"};
    std::vector<const Expr*> arguments = bindArguments(call, names);
    double a = values[0].number;
    double b = values[1].number;
    if (arguments[0] != call.arguments[0].value.get()) {
      std::swap(a, b);
    }
    double result = name == "atan2" ? std::atan2(a, b)
                    : name == "pow" ? std::pow(a, b)
                    : name == "min" ? std::min(a, b)
                                    : std::max(a, b);
    return checkedNumber(result, call.span,
                         [&] { return fmt::format("{}({:g}, {:g})", name, a, b); });
  }
  if (values.size() != 1) {
    return {};
  }
  double x = values[0].number;
  double result = 0;
  if (name == "sin") {
    result = std::sin(x);
  } else if (name == "cos") {
    result = std::cos(x);
  } else if (name == "tan") {
    result = std::tan(x);
  } else if (name == "asin") {
    result = std::asin(x);
  } else if (name == "acos") {
    result = std::acos(x);
  } else if (name == "atan") {
    result = std::atan(x);
  } else if (name == "sqrt") {
    result = std::sqrt(x);
  } else if (name == "abs") {
    result = std::abs(x);
  } else if (name == "exp") {
    result = std::exp(x);
  } else if (name == "ln") {
    result = x > 0 ? std::log(x) : NAN;
  } else if (name == "floor") {
    result = std::floor(x);
  } else if (name == "ceil") {
    result = std::ceil(x);
  } else if (name == "round") {
    result = std::round(x);
  }
  return checkedNumber(result, call.span, [&] { return fmt::format("{}({:g})", name, x); });
}

Value Evaluator::evaluatePoint(const PointExpr& point, const Environment& environment) {
  std::array<double, 3> coordinates{0, 0, 0};
  int dimensions = static_cast<int>(point.components.size());
  for (int i = 0; i < dimensions && i < 3; ++i) {
    Value component = evaluate(*point.components[i], environment);
    if (component.isError()) {
      return {};
    }
    if (component.type.kind != TypeKind::Num) {
      return typeError(point.components[i]->span, "a point's coordinates must be numbers");
    }
    coordinates[i] = component.number;
  }
  return Value::ofPoint(coordinates, std::min(dimensions, 3));
}

Value Evaluator::evaluateList(const ListExpr& list, const Environment& environment) {
  ValueList elements;
  elements.reserve(list.elements.size());
  TypeKind element = TypeKind::Any;
  for (const ExprPtr& item : list.elements) {
    Value value = evaluate(*item, environment);
    if (value.isError()) {
      return {};
    }
    if (element == TypeKind::Any) {
      element = value.type.kind;
    } else if (value.type.kind != element) {
      report(DiagnosticKind::MixedList, item->span,
             fmt::format("a list holds one type: this element is a {}, the first is a {}",
                         typeName(value.type), typeKindName(element)));
      return {};
    }
    elements.push_back(std::move(value));
  }
  return Value::ofList(std::move(elements), element);
}

Value Evaluator::evaluateIndex(const IndexExpr& index, const Environment& environment) {
  Value base = evaluate(*index.base, environment);
  Value position = evaluate(*index.index, environment);
  if (base.isError() || position.isError()) {
    return {};
  }
  if (base.type.kind != TypeKind::List || position.type.kind != TypeKind::Num) {
    return typeError(index.span, "indexing needs a list and a number");
  }
  double number = position.number;
  if (number != std::floor(number)) {
    report(DiagnosticKind::NotInteger, index.index->span,
           fmt::format("a list index must be a whole number, not {:g}", number));
    return {};
  }
  std::size_t size = base.list->size();
  if (number < 0 || number >= static_cast<double>(size)) {
    report(DiagnosticKind::IndexOutOfRange, index.index->span,
           size == 0 ? fmt::format("index {:g} is out of range: the list is empty", number)
                     : fmt::format("index {:g} is out of range: the list has {} element{} "
                                   "(indexes 0 .. {})",
                                   number, size, size == 1 ? "" : "s", size - 1));
    return {};
  }
  return (*base.list)[static_cast<std::size_t>(number)];
}

Value Evaluator::evaluateMember(const MemberExpr& member, const Environment& environment) {
  Value base = evaluate(*member.base, environment);
  if (base.isError()) {
    return {};
  }
  if (base.type.kind != TypeKind::Point) {
    return typeError(member.base->span, fmt::format("only a point has .{}; this is a {}",
                                                    member.member, typeName(base.type)));
  }
  int axis = member.member == "x" ? 0 : member.member == "y" ? 1 : 2;
  return Value::ofNumber(base.point[axis]);
}

} // namespace cncc::frontend
