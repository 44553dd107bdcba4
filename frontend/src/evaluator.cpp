#include "evaluator.h"

#include <array>
#include <cmath>
#include <fmt/format.h>
#include <string_view>

namespace cncc::frontend {

void Evaluator::report(DiagnosticKind kind, SourceSpan span, std::string message) {
  ++reports_;
  if (!reported_.insert(reportKey(kind, span)).second) {
    return;
  }
  Diagnostic* diagnostic = diagnostics_->report(kind, span, std::move(message));
  for (auto call = callStack_.rbegin(); call != callStack_.rend(); ++call) {
    diagnostics_->addNote(diagnostic, *call, "in this call");
  }
}

void Evaluator::addReportsOf(const DiagnosticEngine& diagnostics, std::size_t first,
                             std::size_t last) {
  for (std::size_t i = first; i < last; ++i) {
    const Diagnostic& reported = diagnostics.diagnostics()[i];
    ++reports_;
    if (!reported_.insert(reportKey(reported.kind, reported.span)).second) {
      continue;
    }
    Diagnostic* diagnostic = diagnostics_->report(reported.kind, reported.span, reported.message);
    for (const DiagnosticNote& note : reported.notes) {
      diagnostics_->addNote(diagnostic, note.span, note.message);
    }
  }
}

Value Evaluator::typeError(SourceSpan span, std::string message) {
  report(DiagnosticKind::TypeMismatch, span, std::move(message));
  return {};
}

void Evaluator::reportNonFinite(SourceSpan span, const std::string& what) {
  report(DiagnosticKind::NonFiniteValue, span, fmt::format("{} is not a finite number", what));
}

Bindings::~Bindings() {
  for (std::size_t i = 0; i < inlineCount_; ++i) {
    inlineBinding(i)->~Binding();
  }
}

void Bindings::bind(const Declaration* declaration, Value value) {
  for (std::size_t i = 0; i < inlineCount_; ++i) {
    if (inlineBinding(i)->first == declaration) {
      inlineBinding(i)->second = std::move(value);
      return;
    }
  }
  for (auto& [bound, boundValue] : more_) {
    if (bound == declaration) {
      boundValue = std::move(value);
      return;
    }
  }
  if (inlineCount_ < inlineBindings) {
    new (inlineStorage_.data() + inlineCount_ * sizeof(Binding))
        Binding(declaration, std::move(value));
    ++inlineCount_;
    return;
  }
  more_.emplace_back(declaration, std::move(value));
}

const Value* Bindings::findLocal(const Declaration* declaration) const {
  for (std::size_t i = 0; i < inlineCount_; ++i) {
    if (inlineBinding(i)->first == declaration) {
      return &inlineBinding(i)->second;
    }
  }
  for (const auto& [bound, value] : more_) {
    if (bound == declaration) {
      return &value;
    }
  }
  return nullptr;
}

const Value* Bindings::find(const Declaration* declaration) const {
  for (const Bindings* frame = this; frame != nullptr; frame = frame->outer_) {
    if (const Value* value = frame->findLocal(declaration)) {
      return value;
    }
    if (frame->environment_ != nullptr) {
      auto found = frame->environment_->find(declaration);
      if (found != frame->environment_->end()) {
        return &found->second;
      }
    }
  }
  return nullptr;
}

bool Bindings::findNumber(const Declaration* declaration, double& number) const {
  for (const Bindings* frame = this; frame != nullptr; frame = frame->outer_) {
    for (std::size_t i = 0; i < frame->numberCount_; ++i) {
      if (frame->numberDeclarations_[i] == declaration) {
        number = frame->numbers_[i];
        return true;
      }
    }
    const Value* value = frame->findLocal(declaration);
    if (value == nullptr && frame->environment_ != nullptr) {
      auto found = frame->environment_->find(declaration);
      value = found == frame->environment_->end() ? nullptr : &found->second;
    }
    if (value != nullptr) {
      number = value->number;
      return value->type.kind == TypeKind::Num;
    }
  }
  return false;
}

Environment Bindings::flatten() const {
  Environment environment;
  flattenInto(environment);
  return environment;
}

// Innermost first: a binding already there shadows the ones outside it,
// which are not copied.
void Bindings::flattenInto(Environment& environment) const {
  for (const Bindings* frame = this; frame != nullptr; frame = frame->outer_) {
    for (std::size_t i = 0; i < frame->inlineCount_; ++i) {
      environment.emplace(frame->inlineBinding(i)->first, frame->inlineBinding(i)->second);
    }
    for (const auto& [declaration, value] : frame->more_) {
      environment.emplace(declaration, value);
    }
    if (frame->environment_ != nullptr) {
      for (const auto& [declaration, value] : *frame->environment_) {
        environment.emplace(declaration, value);
      }
    }
  }
}

std::vector<const Expr*> Evaluator::bindArguments(const CallExpr& call,
                                                  const std::vector<std::string>& names) {
  std::vector<const Expr*> bound(names.size(), nullptr);
  bindArguments(
      call, names.size(), [&](std::size_t i) -> const std::string& { return names[i]; },
      bound.data());
  return bound;
}

Value Evaluator::constantValue(const Declaration* declaration) {
  if (declaration->value) {
    return *declaration->value;
  }
  auto item = context_.fileItems.find(declaration);
  if (item == context_.fileItems.end() || constantsInProgress_.contains(declaration)) {
    return {};
  }
  constantsInProgress_.insert(declaration);
  ++constants_;
  std::vector<SourceSpan> savedStack;
  std::swap(savedStack, callStack_);
  // Evaluated the ordinary way (with its fast path) even when a fast path
  // asks, and the value is kept: its steps count whatever that path does.
  bool fastPathEnabled = fastPathEnabled_;
  int fastPathDepth = fastPathDepth_;
  fastPathEnabled_ = true;
  fastPathDepth_ = 0;
  std::size_t steps = steps_;
  Value value = evaluate(*as<ConstItem>(*item->second.item).value, Bindings());
  fastPathEnabled_ = fastPathEnabled;
  fastPathDepth_ = fastPathDepth;
  if (fastPathDepth_ > 0) {
    stepsKept_ += steps_ - steps;
  }
  std::swap(savedStack, callStack_);
  constantsInProgress_.erase(declaration);
  context_.mutableDeclaration(declaration).value = value;
  return value;
}

bool mayBeNumber(const Expr& expression) {
  if (expression.type.kind != TypeKind::Num && expression.type.kind != TypeKind::Any) {
    return false;
  }
  switch (expression.kind) {
  case ExprKind::Number:
  case ExprKind::Name:
  case ExprKind::Unary:
  case ExprKind::Binary:
  case ExprKind::Call:
    return true;
  default:
    return false;
  }
}

// A number written out, as the fast path takes it, without its bookkeeping.
bool Evaluator::numberWrittenOut(const Expr& expression, double& number) {
  if (expression.kind == ExprKind::Number && fastPathEnabled_ && steps_ < maximumSteps &&
      expression.type.kind == TypeKind::Num) {
    ++steps_;
    number = as<NumberExpr>(expression).value;
    return true;
  }
  return false;
}

bool Evaluator::fastPathNumber(const Expr& expression, const Bindings& bindings, double& number) {
  std::size_t steps = steps_;
  std::size_t outerKept = stepsKept_;
  stepsKept_ = 0;
  ++fastPathDepth_;
  bool evaluated = evaluateNumber(expression, bindings, number);
  --fastPathDepth_;
  std::size_t keptHere = stepsKept_;
  stepsKept_ = outerKept;
  if (!evaluated) {
    // As if the fast path had not run, but for the constants it evaluated.
    steps_ = steps + keptHere;
  }
  return evaluated;
}

Value Evaluator::evaluateWithoutFastPath(const Expr& expression, const Bindings& bindings) {
  fastPathEnabled_ = false;
  Value value = evaluateValue(expression, bindings);
  fastPathEnabled_ = true;
  return value;
}

Value Evaluator::evaluate(const Expr& expression, const Bindings& bindings) {
  double number = 0;
  if (numberWrittenOut(expression, number)) {
    return Value::ofNumber(number);
  }
  if (!fastPathEnabled_ || !mayBeNumber(expression)) {
    return evaluateValue(expression, bindings);
  }
  if (fastPathNumber(expression, bindings, number)) {
    return Value::ofNumber(number);
  }
  return evaluateWithoutFastPath(expression, bindings);
}

bool Evaluator::evaluateAsNumber(const Expr& expression, const Bindings& bindings, double& number,
                                 Value& value) {
  if (numberWrittenOut(expression, number)) {
    return true;
  }
  if (!fastPathEnabled_ || !mayBeNumber(expression)) {
    value = evaluateValue(expression, bindings);
  } else if (fastPathNumber(expression, bindings, number)) {
    return true;
  } else {
    value = evaluateWithoutFastPath(expression, bindings);
  }
  number = value.number;
  return value.type.kind == TypeKind::Num;
}

Value Evaluator::evaluateValue(const Expr& expression, const Bindings& bindings) {
  if (++steps_ > maximumSteps || expression.type.kind == TypeKind::Error) {
    return {};
  }
  switch (expression.kind) {
  case ExprKind::Number:
    return Value::ofNumber(as<NumberExpr>(expression).value);
  case ExprKind::Bool:
    return Value::ofBool(as<BoolExpr>(expression).value);
  case ExprKind::String:
    return Value::ofString(std::string(as<StringExpr>(expression).value));
  case ExprKind::Name:
    return evaluateName(as<NameExpr>(expression), bindings);
  case ExprKind::Unary:
    return evaluateUnary(as<UnaryExpr>(expression), bindings);
  case ExprKind::Binary:
    return evaluateBinary(as<BinaryExpr>(expression), bindings);
  case ExprKind::Call:
    return evaluateCall(as<CallExpr>(expression), bindings);
  case ExprKind::Point:
    return evaluatePoint(as<PointExpr>(expression), bindings);
  case ExprKind::List:
    return evaluateList(as<ListExpr>(expression), bindings);
  case ExprKind::Range: {
    const auto& range = as<RangeExpr>(expression);
    double low = 0;
    double high = 0;
    Value other;
    bool lowNumber = evaluateAsNumber(*range.low, bindings, low, other);
    if (!evaluateAsNumber(*range.high, bindings, high, other) || !lowNumber) {
      return {};
    }
    return Value::ofRange(low, high);
  }
  case ExprKind::Index:
    return evaluateIndex(as<IndexExpr>(expression), bindings);
  case ExprKind::Member:
    return evaluateMember(as<MemberExpr>(expression), bindings);
  case ExprKind::IfElse: {
    const auto& choice = as<IfElseExpr>(expression);
    Value condition = evaluate(*choice.condition, bindings);
    if (condition.type.kind != TypeKind::Bool) {
      return condition.isError()
                 ? Value{}
                 : typeError(choice.condition->span, "the condition of 'if' must be a bool");
    }
    return evaluate(condition.boolean ? *choice.thenValue : *choice.elseValue, bindings);
  }
  case ExprKind::Error:
    return {};
  }
  return {};
}

Value Evaluator::evaluateName(const NameExpr& name, const Bindings& bindings) {
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
  const Value* found = bindings.find(declaration);
  return found == nullptr ? Value{} : *found;
}

Value Evaluator::evaluateUnary(const UnaryExpr& unary, const Bindings& bindings) {
  Value operand = evaluate(*unary.operand, bindings);
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

Value Evaluator::evaluateBinary(const BinaryExpr& binary, const Bindings& bindings) {
  Value left = evaluate(*binary.left, bindings);
  if (left.isError()) {
    return {};
  }
  bool logical = binary.op == BinaryOperator::And || binary.op == BinaryOperator::Or;
  if (logical && left.type.kind == TypeKind::Bool) {
    // Short-circuit, so `i > 0 && L[i - 1] > 0` is safe.
    if (left.boolean == (binary.op == BinaryOperator::Or)) {
      return left;
    }
    Value right = evaluate(*binary.right, bindings);
    if (!right.isError() && right.type.kind != TypeKind::Bool) {
      return typeError(binary.right->span, "'&&' and '||' need bools");
    }
    return right;
  }
  Value right = evaluate(*binary.right, bindings);
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
    return checkedNumber(
        op == BinaryOperator::Divide ? a / b : geom::computeMath(geom::MathFunction::Rem, a, b),
        binary.span, [] { return std::string("the quotient"); });
  case BinaryOperator::Power:
    if (!numbers) {
      return mismatch();
    }
    return checkedNumber(geom::computeMath(geom::MathFunction::Pow, a, b), binary.span,
                         [&] { return fmt::format("{:g} ^ {:g}", a, b); });
  default:
    return mismatch();
  }
}

Value Evaluator::evaluateCall(const CallExpr& call, const Bindings& bindings) {
  const Declaration* declaration = call.declaration;
  if (declaration == nullptr) {
    return {};
  }
  if (declaration->kind == DeclarationKind::Function) {
    return evaluateFunctionCall(call, *declaration, bindings);
  }
  if (declaration->kind != DeclarationKind::Builtin) {
    return {};
  }
  if (call.type.kind == TypeKind::Curve) {
    return buildCurve(*this, call, bindings);
  }
  return evaluateMathCall(call, bindings);
}

Value Evaluator::evaluateFunctionCall(const CallExpr& call, const Declaration& function,
                                      const Bindings& bindings) {
  if (context_.invalidFunctions.contains(&function) || function.function == nullptr) {
    return {};
  }
  const FnItem& item = *function.function;
  const NodeList<Parameter>& parameters = item.parameters;
  std::size_t count = parameters.size();
  // Most functions have a few parameters: no allocation for them.
  constexpr std::size_t inlineCount = 8;
  std::array<const Expr*, inlineCount> inlineArguments{};
  std::vector<const Expr*> manyArguments(count > inlineCount ? count : 0, nullptr);
  const Expr** arguments = count > inlineCount ? manyArguments.data() : inlineArguments.data();
  bindArguments(
      call, count, [&](std::size_t i) -> std::string_view { return parameters[i].name; },
      arguments);
  Bindings inner;
  inner.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    if (arguments[i] == nullptr || parameters[i].declaration == nullptr) {
      return {};
    }
    Value argument = evaluate(*arguments[i], bindings);
    if (argument.isError()) {
      return {};
    }
    inner.bind(parameters[i].declaration, std::move(argument));
  }
  if (callStack_.size() > 64) {
    return {};
  }
  callStack_.push_back(call.span);
  Value result = evaluate(*item.body, inner);
  callStack_.pop_back();
  return result;
}

bool isArithmetic(BinaryOperator op) {
  switch (op) {
  case BinaryOperator::Add:
  case BinaryOperator::Subtract:
  case BinaryOperator::Multiply:
  case BinaryOperator::Divide:
  case BinaryOperator::Remainder:
  case BinaryOperator::Power:
    return true;
  default:
    return false;
  }
}

std::optional<arithmetic::MathFunction> numericMathCall(const CallExpr& call) {
  const Declaration* declaration = call.declaration;
  if (declaration == nullptr || declaration->kind != DeclarationKind::Builtin ||
      call.type.kind == TypeKind::Curve) {
    return std::nullopt;
  }
  std::optional<arithmetic::MathFunction> function = arithmetic::mathFunction(call.callee);
  if (!function ||
      static_cast<int>(call.arguments.size()) != geom::mathFunctionInfo(*function).arity) {
    return std::nullopt;
  }
  return function;
}

bool binaryArgumentsSwapped(const CallExpr& call, arithmetic::MathFunction function) {
  std::array<std::string_view, 2> names = arithmetic::binaryParameterNames(function);
  std::array<const Expr*, 2> arguments{};
  Evaluator::bindArguments(
      call, 2, [&](std::size_t i) { return names[i]; }, arguments.data());
  return arguments[0] != call.arguments[0].value.get();
}

Value Evaluator::evaluateMathCall(const CallExpr& call, const Bindings& bindings) {
  std::size_t count = call.arguments.size();
  // Math functions take one or two arguments: no allocation for them.
  std::array<Value, 2> fewValues;
  std::vector<Value> manyValues(count > fewValues.size() ? count : 0);
  Value* values = count > fewValues.size() ? manyValues.data() : fewValues.data();
  for (std::size_t i = 0; i < count; ++i) {
    values[i] = evaluate(*call.arguments[i].value, bindings);
    if (values[i].isError()) {
      return {};
    }
  }
  return applyMathFunction(call, values, count);
}

Value Evaluator::applyMathFunction(const CallExpr& call, const Value* values, std::size_t count) {
  using namespace arithmetic;
  std::string_view name = call.callee;
  if (name == "len") {
    if (count != 1 || values[0].type.kind != TypeKind::List) {
      return typeError(call.span, "len(...) needs a list");
    }
    return Value::ofNumber(static_cast<double>(values[0].list->size()));
  }
  std::optional<MathFunction> found = mathFunction(name);
  if (!found || static_cast<int>(count) != geom::mathFunctionInfo(*found).arity) {
    return typeError(call.span,
                     fmt::format("'{}' is no math function of {} arguments", name, count));
  }
  MathFunction function = *found;
  for (std::size_t i = 0; i < count; ++i) {
    if (values[i].type.kind != TypeKind::Num) {
      return typeError(call.arguments[i].value->span,
                       fmt::format("'{}' needs numbers, not a {}", name, typeName(values[i].type)));
    }
  }
  if (count == 2) {
    // Named arguments may come in any order: put them in parameter order.
    double a = values[0].number;
    double b = values[1].number;
    if (binaryArgumentsSwapped(call, function)) {
      std::swap(a, b);
    }
    double result = applyBinary(function, a, b);
    return checkedNumber(result, call.span,
                         [&] { return fmt::format("{}({:g}, {:g})", name, a, b); });
  }
  double x = values[0].number;
  double result = applyUnary(function, x);
  return checkedNumber(result, call.span, [&] { return fmt::format("{}({:g})", name, x); });
}

Value Evaluator::evaluatePoint(const PointExpr& point, const Bindings& bindings) {
  std::array<double, 3> coordinates{0, 0, 0};
  int dimensions = static_cast<int>(point.components.size());
  for (int i = 0; i < dimensions && i < 3; ++i) {
    Value component;
    if (evaluateAsNumber(*point.components[i], bindings, coordinates[i], component)) {
      continue;
    }
    if (component.isError()) {
      return {};
    }
    return typeError(point.components[i]->span, "a point's coordinates must be numbers");
  }
  return Value::ofPoint(coordinates, std::min(dimensions, 3));
}

Value Evaluator::evaluateList(const ListExpr& list, const Bindings& bindings) {
  ValueList elements;
  elements.reserve(list.elements.size());
  TypeKind element = TypeKind::Any;
  for (const ExprPtr& item : list.elements) {
    Value value = evaluate(*item, bindings);
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

Value Evaluator::evaluateIndex(const IndexExpr& index, const Bindings& bindings) {
  Value base = evaluate(*index.base, bindings);
  Value position = evaluate(*index.index, bindings);
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

Value Evaluator::evaluateMember(const MemberExpr& member, const Bindings& bindings) {
  Value base = evaluate(*member.base, bindings);
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
