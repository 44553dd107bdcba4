// Curve constructors evaluated to CurveValues, with the geometric checks a
// user needs before anything is generated: order against the number of
// points, weights, knot vectors, empty ranges, degenerate shapes.
#include "evaluator.h"
#include "number_sampling.h"
#include "spelling_table.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <span>
#include <string_view>

namespace cncc::frontend {

namespace {

// The span of element `i` when the list is written out literally, else the
// span of the whole argument.
SourceSpan elementSpan(const Expr& list, std::size_t i) {
  if (list.kind == ExprKind::List) {
    const auto& elements = as<ListExpr>(list).elements;
    if (i < elements.size()) {
      return elements[i]->span;
    }
  }
  return list.span;
}

// The curve constructors, told apart once per call.
enum class Constructor {
  Nurbs,
  Bspline,
  Bezier,
  Polar,
  Param,
  Line,
  Arc,
  Path,
  Translate,
  Rotate,
  Scale,
  Other,
};
constexpr std::size_t constructorCount = static_cast<std::size_t>(Constructor::Other);

// By length, then by spelling: a comparison or two per call.
Constructor constructorOf(std::string_view name) {
  auto is = [&](std::string_view spelling, Constructor constructor) {
    return name == spelling ? constructor : Constructor::Other;
  };
  switch (name.size()) {
  case 3:
    return is("arc", Constructor::Arc);
  case 4:
    return name[1] == 'i' ? is("line", Constructor::Line) : is("path", Constructor::Path);
  case 5:
    switch (name[0]) {
    case 'n':
      return is("nurbs", Constructor::Nurbs);
    case 'p':
      return name[1] == 'o' ? is("polar", Constructor::Polar) : is("param", Constructor::Param);
    default:
      return is("scale", Constructor::Scale);
    }
  case 6:
    return name[0] == 'b' ? is("bezier", Constructor::Bezier) : is("rotate", Constructor::Rotate);
  case 7:
    return is("bspline", Constructor::Bspline);
  case 9:
    return is("translate", Constructor::Translate);
  default:
    return Constructor::Other;
  }
}

// A builtin's parameter names, in order: views of builtinFunctions()'s,
// which live as long as the program.
using ParameterNames = std::vector<std::string_view>;

ParameterNames parameterNamesOf(const BuiltinInfo& info) {
  ParameterNames names;
  for (const BuiltinParameter& parameter : info.parameters) {
    names.push_back(parameter.name);
  }
  return names;
}

// More parameters than any builtin has (nurbs has the most: five).
constexpr std::size_t maximumParameters = 8;
using BoundArguments = std::array<const Expr*, maximumParameters>;

// The parameters the curve constructors read, so the builder finds an
// argument by its position in the constructor's list rather than by
// comparing names.
enum class Parameter {
  Order,
  Degree,
  Points,
  Weights,
  Knots,
  R,
  T,
  X,
  Y,
  Z,
  From,
  To,
  Center,
  Radius,
  Curve,
  Dx,
  Dy,
  Angle,
  Factor,
};
constexpr std::array<std::string_view, 19> parameterSpellings = {
    "order", "degree", "points", "weights", "knots", "r",  "t",  "x",     "y",     "z",
    "from",  "to",     "center", "radius",  "curve", "dx", "dy", "angle", "factor"};

std::string_view spelling(Parameter parameter) {
  return parameterSpellings[static_cast<std::size_t>(parameter)];
}

// A curve constructor's parameters: their names, in order, and where in
// that order each Parameter is (-1: it has none of that name).
struct ConstructorParameters {
  std::string_view name; // the builtin's, which lives as long as the program
  ParameterNames names;
  std::array<int, parameterSpellings.size()> positions{};
};

ConstructorParameters constructorParametersOf(const BuiltinInfo& info) {
  ConstructorParameters result{info.name, parameterNamesOf(info), {}};
  for (std::size_t p = 0; p < parameterSpellings.size(); ++p) {
    result.positions[p] = -1;
    for (std::size_t i = 0; i < result.names.size() && i < maximumParameters; ++i) {
      if (result.names[i] == parameterSpellings[p]) {
        result.positions[p] = static_cast<int>(i);
        break;
      }
    }
  }
  return result;
}

// Built once: the curve constructors' by Constructor (Other: none), the
// other builtins' by name.
struct ParameterTable {
  std::array<ConstructorParameters, constructorCount + 1> constructors;
  std::vector<std::pair<std::string_view, ParameterNames>> others;
};

const ParameterTable& parameterTable() {
  static const ParameterTable table = [] {
    ParameterTable result;
    result.constructors[constructorCount].positions.fill(-1);
    for (const BuiltinInfo& info : builtinFunctions()) {
      Constructor of = constructorOf(info.name);
      if (of == Constructor::Other) {
        result.others.emplace_back(info.name, parameterNamesOf(info));
      } else {
        result.constructors[static_cast<std::size_t>(of)] = constructorParametersOf(info);
      }
    }
    return result;
  }();
  return table;
}

const ConstructorParameters& constructorParameters(Constructor constructor) {
  return parameterTable().constructors[static_cast<std::size_t>(constructor)];
}

const ParameterNames& parameterNames(std::string_view builtin, Constructor constructor) {
  if (constructor != Constructor::Other) {
    return constructorParameters(constructor).names;
  }
  for (const auto& [name, names] : parameterTable().others) {
    if (name == builtin) {
      return names;
    }
  }
  static const ParameterNames none;
  return none;
}

// The Parameters by length and first letter: an argument's name is
// compared with one or two spellings, not with every parameter name.
constexpr std::size_t longestParameter = 7;
constexpr SpellingTable<longestParameter> parameterTableBySpelling =
    makeSpellingTable<longestParameter>(parameterSpellings.size(),
                                        [](std::size_t i) { return parameterSpellings[i]; });

// The Parameter an argument names, if any.
std::optional<Parameter> parameterNamed(std::string_view name) {
  const SpellingCandidates* candidates = spellingCandidates(parameterTableBySpelling, name);
  if (candidates == nullptr) {
    return std::nullopt;
  }
  for (std::uint8_t candidate : {candidates->first, candidates->second}) {
    if (candidate != 0 && name == parameterSpellings[candidate - 1U]) {
      return static_cast<Parameter>(candidate - 1);
    }
  }
  return std::nullopt;
}

// The argument bound to each parameter, as the evaluator binds them (a
// constructor's parameter names are distinct, so a named argument binds at
// most one); parameters past `maximumParameters` (no builtin has them) stay
// unbound.
BoundArguments bindConstructorArguments(const CallExpr& call,
                                        const ConstructorParameters& parameters) {
  BoundArguments bound{};
  Evaluator::bindArgumentsWith(
      call, std::min(parameters.names.size(), maximumParameters), bound.data(),
      [&](const Argument& argument) {
        std::optional<Parameter> parameter = parameterNamed(argument.name);
        if (!parameter) {
          return;
        }
        int position = parameters.positions[static_cast<std::size_t>(*parameter)];
        if (position >= 0 && bound[static_cast<std::size_t>(position)] == nullptr) {
          bound[static_cast<std::size_t>(position)] = argument.value.get();
        }
      });
  return bound;
}

// The same for any builtin, by comparing names.
BoundArguments bindBuiltinArguments(const CallExpr& call, const ParameterNames& names) {
  BoundArguments bound{};
  Evaluator::bindArguments(
      call, std::min(names.size(), maximumParameters), [&](std::size_t i) { return names[i]; },
      bound.data());
  return bound;
}

bool sameNumber(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0; // -0 and 0 differ, as atan2 shows
}

// Whether evaluating with either gives the same: the same numbers to the
// bit, the same list contents, the very same curve.
bool sameValue(const Value& a, const Value& b) {
  if (a.type != b.type) {
    return false;
  }
  switch (a.type.kind) {
  case TypeKind::Num:
    return sameNumber(a.number, b.number);
  case TypeKind::Bool:
    return a.boolean == b.boolean;
  case TypeKind::String:
    return a.string == b.string || (a.string && b.string && *a.string == *b.string);
  case TypeKind::Point:
    return a.pointDimensions == b.pointDimensions && sameNumber(a.point[0], b.point[0]) &&
           sameNumber(a.point[1], b.point[1]) && sameNumber(a.point[2], b.point[2]);
  case TypeKind::Range:
    return sameNumber(a.low, b.low) && sameNumber(a.high, b.high);
  case TypeKind::List:
    if (a.list == b.list) {
      return true;
    }
    if (!a.list || !b.list || a.list->size() != b.list->size()) {
      return false;
    }
    for (std::size_t i = 0; i < a.list->size(); ++i) {
      if (!sameValue((*a.list)[i], (*b.list)[i])) {
        return false;
      }
    }
    return true;
  case TypeKind::Curve:
    return a.curve == b.curve;
  case TypeKind::Error:
  case TypeKind::Any:
    break;
  }
  return false;
}

bool sameEnvironment(const Environment& a, const Environment& b) {
  if (a.size() != b.size()) {
    return false;
  }
  for (auto left = a.begin(), right = b.begin(); left != a.end(); ++left, ++right) {
    if (left->first != right->first || !sameValue(left->second, right->second)) {
      return false;
    }
  }
  return true;
}

// Clamped uniform knots: `order` zeros, evenly spaced interior knots,
// `order` ones.
std::vector<double> clampedUniformKnots(std::size_t pointCount, int order) {
  std::vector<double> knots(static_cast<std::size_t>(order), 0.0);
  std::size_t interior = pointCount - static_cast<std::size_t>(order);
  for (std::size_t i = 1; i <= interior; ++i) {
    knots.push_back(static_cast<double>(i) / static_cast<double>(interior + 1));
  }
  knots.insert(knots.end(), static_cast<std::size_t>(order), 1.0);
  return knots;
}

class CurveBuilder {
public:
  CurveBuilder(Evaluator& evaluator, const CallExpr& call, const Bindings& bindings)
      : evaluator_(evaluator), call_(call), bindings_(bindings),
        constructor_(constructorOf(call.callee)), parameters_(constructorParameters(constructor_)),
        arguments_(bindConstructorArguments(call, parameters_)) {}

  Value build() {
    switch (constructor_) {
    case Constructor::Nurbs:
    case Constructor::Bspline:
    case Constructor::Bezier:
      return buildNurbs();
    case Constructor::Polar:
    case Constructor::Param:
      return buildAnalytic();
    case Constructor::Line:
      return buildLine();
    case Constructor::Arc:
      return buildArc();
    case Constructor::Path:
      return buildPath();
    default:
      return buildTransform();
    }
  }

private:
  const Expr* argument(Parameter parameter) const {
    int position = parameters_.positions[static_cast<std::size_t>(parameter)];
    return position < 0 ? nullptr : arguments_[static_cast<std::size_t>(position)];
  }

  // The whole `name=value` of an argument (just the value when positional),
  // for messages about the argument as a whole.
  SourceSpan argumentSpan(const Expr& expression) const {
    for (const Argument& given : call_.arguments) {
      if (given.value.get() == &expression) {
        return given.span();
      }
    }
    return expression.span;
  }

  // The argument's value when it was given, evaluated without an error and
  // is a `kind`; else an Error value (and `failed_`, but for a missing
  // argument, which the checker has reported).
  Value value(Parameter parameter, TypeKind kind) {
    const Expr* expression = argument(parameter);
    if (expression == nullptr) {
      return {};
    }
    Value result = argumentValue(*expression);
    if (!result.isError() && result.type.kind != kind) {
      evaluator_.report(DiagnosticKind::TypeMismatch, expression->span,
                        fmt::format("argument '{}' of '{}' must be a {}, not a {}",
                                    spelling(parameter), call_.callee, typeKindName(kind),
                                    typeName(result.type)));
      result = {};
    }
    failed_ = failed_ || result.isError();
    return result;
  }

  // As value(parameter, TypeKind::Num), without a Value for a number.
  std::optional<double> number(Parameter parameter) {
    const Expr* expression = argument(parameter);
    if (expression == nullptr) {
      return std::nullopt;
    }
    double result = 0;
    Value other;
    if (argumentNumber(*expression, result, other)) {
      return result;
    }
    if (!other.isError()) {
      evaluator_.report(DiagnosticKind::TypeMismatch, expression->span,
                        fmt::format("argument '{}' of '{}' must be a {}, not a {}",
                                    spelling(parameter), call_.callee, typeKindName(TypeKind::Num),
                                    typeName(other.type)));
    }
    failed_ = true;
    return std::nullopt;
  }

  std::optional<std::array<double, 3>> point(Parameter parameter) {
    Value result = value(parameter, TypeKind::Point);
    return result.isError() ? std::nullopt : std::optional(result.point);
  }

  // The elements of a list argument, each of which must be a `kind`
  // (`'name' must hold <what>` otherwise), appended to `into` by `take`;
  // false when the argument is missing or anything failed.
  template <typename Take>
  bool elements(Parameter parameter, TypeKind kind, std::string_view what, Take take) {
    const Expr* expression = argument(parameter);
    if (expression == nullptr) {
      return false;
    }
    if (expression->kind == ExprKind::List && expression->type.kind != TypeKind::Error &&
        evaluator_.spendSteps(1)) {
      return writtenElements(parameter, as<ListExpr>(*expression), kind, what, take);
    }
    Value list = value(parameter, TypeKind::List);
    if (list.isError()) {
      return false;
    }
    for (std::size_t i = 0; i < list.list->size(); ++i) {
      const Value& element = (*list.list)[i];
      if (element.type.kind != kind) {
        report(DiagnosticKind::TypeMismatch, elementSpan(*expression, i),
               fmt::format("'{}' must hold {}", spelling(parameter), what));
        return false;
      }
      take(element);
    }
    return true;
  }

  // A list written out in the call, evaluated element by element as the
  // evaluator evaluates a list (its step spent by the caller), with the same
  // checks in the same order, but without building the list's Value.
  template <typename Take>
  bool writtenElements(Parameter parameter, const ListExpr& list, TypeKind kind,
                       std::string_view what, Take take) {
    TypeKind first = TypeKind::Any;
    for (const ExprPtr& item : list.elements) {
      Value element = argumentValue(*item);
      if (element.isError()) {
        failed_ = true;
        return false;
      }
      if (first == TypeKind::Any) {
        first = element.type.kind;
      } else if (element.type.kind != first) {
        report(DiagnosticKind::MixedList, item->span,
               fmt::format("a list holds one type: this element is a {}, the first is a {}",
                           typeName(element.type), typeKindName(first)));
        return false;
      }
      if (element.type.kind == kind) {
        take(element);
      }
    }
    if (!list.elements.empty() && first != kind) {
      report(DiagnosticKind::TypeMismatch, elementSpan(list, 0),
             fmt::format("'{}' must hold {}", spelling(parameter), what));
      return false;
    }
    return true;
  }

  // What evaluating an argument gives. A number or a point written out is
  // evaluated here as the evaluator would, with a step for each node (when
  // the budget has it), but without its detours: most arguments are these.
  Value argumentValue(const Expr& expression) {
    if (expression.type.kind != TypeKind::Error) {
      if (expression.kind == ExprKind::Number && evaluator_.spendSteps(1)) {
        return Value::ofNumber(as<NumberExpr>(expression).value);
      }
      if (expression.kind == ExprKind::Point && evaluator_.spendSteps(1)) {
        return pointValue(as<PointExpr>(expression));
      }
    }
    return evaluator_.evaluate(expression, bindings_);
  }

  // As argumentValue, without a Value for a number: true with `number`
  // set then; else false with `value` set to what argumentValue gives.
  bool argumentNumber(const Expr& expression, double& number, Value& value) {
    if (expression.type.kind != TypeKind::Error && expression.kind == ExprKind::Number &&
        evaluator_.spendSteps(1)) {
      number = as<NumberExpr>(expression).value;
      return true;
    }
    if (expression.type.kind != TypeKind::Error && expression.kind == ExprKind::Point &&
        evaluator_.spendSteps(1)) {
      value = pointValue(as<PointExpr>(expression));
      return false;
    }
    return evaluator_.evaluateAsNumber(expression, bindings_, number, value);
  }

  // As Evaluator::evaluatePoint.
  Value pointValue(const PointExpr& point) {
    std::array<double, 3> coordinates{0, 0, 0};
    int dimensions = static_cast<int>(point.components.size());
    for (int i = 0; i < dimensions && i < 3; ++i) {
      const Expr& component = *point.components[static_cast<std::size_t>(i)];
      Value coordinate;
      if (argumentNumber(component, coordinates[static_cast<std::size_t>(i)], coordinate)) {
        continue;
      }
      if (!coordinate.isError()) {
        evaluator_.report(DiagnosticKind::TypeMismatch, component.span,
                          "a point's coordinates must be numbers");
      }
      return {};
    }
    return Value::ofPoint(coordinates, std::min(dimensions, 3));
  }

  bool numbers(Parameter parameter, std::vector<double>& into) {
    return elements(parameter, TypeKind::Num, "numbers",
                    [&](const Value& element) { into.push_back(element.number); });
  }

  bool points(Parameter parameter, std::vector<std::array<double, 3>>& into) {
    return elements(parameter, TypeKind::Point, "points",
                    [&](const Value& element) { into.push_back(element.point); });
  }

  void report(DiagnosticKind kind, SourceSpan span, std::string message) {
    evaluator_.report(kind, span, std::move(message));
    failed_ = true;
  }

  Value finish(std::shared_ptr<CurveValue> curve) {
    if (failed_) {
      return {};
    }
    curve->constructor = parameters_.name;
    return Value::ofCurve(std::move(curve));
  }

  // ------------------------------------------------------------ nurbs
  std::optional<int> order() {
    if (constructor_ == Constructor::Bezier) {
      return std::nullopt;
    }
    bool byDegree = argument(Parameter::Order) == nullptr;
    Parameter parameter = byDegree ? Parameter::Degree : Parameter::Order;
    std::string_view name = spelling(parameter);
    std::optional<double> given = number(parameter);
    if (!given) {
      return std::nullopt;
    }
    const Expr& expression = *argument(parameter);
    if (*given != std::floor(*given)) {
      report(DiagnosticKind::NotInteger, expression.span,
             fmt::format("'{}' must be a whole number, not {:g}", name, *given));
      return std::nullopt;
    }
    double result = byDegree ? *given + 1 : *given;
    if (result < 2 || result > 30) {
      report(DiagnosticKind::InvalidOrder, expression.span,
             fmt::format("'{}' {:g} is out of range: the order must be 2 .. 30 (degree 1 .. 29)",
                         name, *given));
      return std::nullopt;
    }
    return static_cast<int>(result);
  }

  Value buildNurbs() {
    auto curve = std::make_shared<CurveValue>();
    curve->kind = CurveKind::Nurbs;
    std::optional<int> k = order();
    std::vector<std::array<double, 3>>& controlPoints = curve->points;
    if (const Expr* given = argument(Parameter::Points);
        given != nullptr && given->kind == ExprKind::List) {
      controlPoints.reserve(as<ListExpr>(*given).elements.size());
    }
    if (!points(Parameter::Points, controlPoints)) {
      failed_ = true;
      return {};
    }
    std::size_t n = controlPoints.size();
    const Expr& pointsExpression = *argument(Parameter::Points);
    if (constructor_ == Constructor::Bezier) {
      if (n < 2) {
        report(DiagnosticKind::TooFewPoints, pointsExpression.span,
               fmt::format("a Bezier segment needs at least 2 points, 'points' has {}", n));
        return {};
      }
      k = static_cast<int>(n);
    }
    if (!k) {
      failed_ = true;
      return {};
    }
    if (n < static_cast<std::size_t>(*k)) {
      report(DiagnosticKind::OrderVsPoints, pointsExpression.span,
             fmt::format("order {} (degree {}) needs at least {} points, but 'points' has {}", *k,
                         *k - 1, *k, n));
      return {};
    }
    curve->degree = *k - 1;
    checkWeights(n, curve->weights);
    checkKnots(n, *k, curve->knots);
    return finish(std::move(curve));
  }

  // The weights (all 1 when not given) into `weights`; what is there when a
  // check fails does not matter, as the curve is not kept.
  void checkWeights(std::size_t n, std::vector<double>& weights) {
    const Expr* given = argument(Parameter::Weights);
    if (given == nullptr) {
      weights.assign(n, 1.0);
      return;
    }
    weights.reserve(n);
    if (!numbers(Parameter::Weights, weights)) {
      return;
    }
    if (weights.size() != n) {
      report(DiagnosticKind::WeightsCount, argumentSpan(*given),
             fmt::format("'weights' has {} entries but 'points' has {}", weights.size(), n));
      return;
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (!(weights[i] > 0)) {
        report(DiagnosticKind::WeightNotPositive, elementSpan(*given, i),
               fmt::format("weight {} is {:g}; every weight must be positive", i + 1, weights[i]));
      }
    }
  }

  // The knots (clamped uniform when not given) into `knots`.
  void checkKnots(std::size_t n, int k, std::vector<double>& knots) {
    std::size_t order = static_cast<std::size_t>(k);
    const Expr* given = argument(Parameter::Knots);
    if (given == nullptr) {
      knots = clampedUniformKnots(n, k);
      return;
    }
    knots.reserve(n + order);
    if (!numbers(Parameter::Knots, knots)) {
      return;
    }
    const Expr& expression = *given;
    if (knots.size() != n + order) {
      report(DiagnosticKind::KnotsCount, expression.span,
             fmt::format("'knots' has {} entries but needs {} ({} points + order {})", knots.size(),
                         n + order, n, k));
      return;
    }
    for (std::size_t i = 1; i < knots.size(); ++i) {
      if (knots[i] < knots[i - 1]) {
        report(DiagnosticKind::KnotsNotMonotonic, elementSpan(expression, i),
               fmt::format("knot {} ({:g}) is smaller than knot {} ({:g}); knots must not "
                           "decrease",
                           i + 1, knots[i], i, knots[i - 1]));
        return;
      }
    }
    if (!(knots[order - 1] < knots[n])) {
      report(DiagnosticKind::DegenerateCurve, expression.span,
             fmt::format("the knots leave the curve no parameter range (knot {} equals knot {})", k,
                         n + 1));
    }
  }

  // ------------------------------------------------------------ polar, param
  Value buildAnalytic() {
    auto curve = std::make_shared<CurveValue>();
    bool polar = constructor_ == Constructor::Polar;
    curve->kind = polar ? CurveKind::Polar : CurveKind::Param;
    Value range = value(Parameter::T, TypeKind::Range);
    if (range.isError() || call_.curveParameter == nullptr) {
      failed_ = true;
      return {};
    }
    const Expr& rangeExpression = *argument(Parameter::T);
    if (!(range.low < range.high)) {
      report(DiagnosticKind::EmptyRange, rangeExpression.span,
             fmt::format("the range {:g} .. {:g} is empty; a curve's parameter needs start < end",
                         range.low, range.high));
      return {};
    }
    curve->low = range.low;
    curve->high = range.high;
    curve->parameter = call_.curveParameter;
    curve->environment = bindings_.flatten();
    curve->radius = argument(Parameter::R);
    curve->x = argument(Parameter::X);
    curve->y = argument(Parameter::Y);
    curve->z = argument(Parameter::Z);
    sampleExpressions(curve);
    return finish(std::move(curve));
  }

  // Evaluates the curve's expressions along its range, so a curve that is
  // undefined somewhere (sqrt of a negative, a division by zero) is an error
  // now rather than a bad program later. The same call with the same values
  // (a curve made by a fn called in a loop) is evaluated once: a sampling
  // that reported nothing and computed no constant would do nothing else
  // again, and spends its steps again.
  void sampleExpressions(const std::shared_ptr<CurveValue>& curve) {
    Evaluator::Progress before = evaluator_.progress();
    auto& samplings = evaluator_.samplings();
    if (auto found = samplings.find(&call_);
        found != samplings.end() && found->second.callDepth == before.callDepth &&
        sameEnvironment(found->second.curve->environment, curve->environment) &&
        evaluator_.spendSteps(found->second.steps)) {
      return;
    }
    sampleAll(*curve);
    Evaluator::Progress after = evaluator_.progress();
    if (!failed_ && !evaluator_.exhausted() && after.reports == before.reports &&
        after.constants == before.constants) {
      samplings[&call_] = {curve, before.callDepth, after.steps - before.steps};
    }
  }

  void sampleAll(CurveValue& curve) {
    std::array<const Expr*, 4> expressions = {curve.radius, curve.x, curve.y, curve.z};
    if (sampledAtOnce(curve, expressions)) {
      return;
    }
    constexpr int samples = curveSampleIntervals;
    Bindings sample(&bindings_);
    for (int i = 0; i <= samples && !failed_ && !evaluator_.exhausted(); ++i) {
      double t = curve.low + (curve.high - curve.low) * i / samples;
      sample.bind(curve.parameter, Value::ofNumber(t));
      for (const Expr* expression : expressions) {
        if (expression == nullptr) {
          continue;
        }
        Value result = evaluator_.evaluate(*expression, sample);
        if (result.isError()) {
          failed_ = true;
        } else if (result.type.kind != TypeKind::Num) {
          report(DiagnosticKind::TypeMismatch, expression->span,
                 fmt::format("this must be a number in t, not a {}", typeName(result.type)));
        }
      }
    }
  }

  // Every sample a finite number by the fast path, as the loop above would
  // find one by one, with the steps it would spend: then the loop has
  // nothing to report and nothing else to do. Not when the budget would run
  // out on the way, so the loop stops where it did.
  bool sampledAtOnce(const CurveValue& curve, std::span<const Expr* const> expressions) {
    if (evaluator_.exhausted()) {
      return false;
    }
    std::optional<std::size_t> steps =
        fastPathSampleSteps(evaluator_.context(), evaluator_.progress().callDepth, bindings_,
                            {curve.parameter, curve.low, curve.high, expressions});
    return steps && evaluator_.spendSteps(*steps);
  }

  // ------------------------------------------------------------ others
  Value buildLine() {
    auto curve = std::make_shared<CurveValue>();
    curve->kind = CurveKind::Line;
    std::optional<std::array<double, 3>> from = point(Parameter::From);
    std::optional<std::array<double, 3>> to = point(Parameter::To);
    if (!from || !to) {
      return {};
    }
    if (*from == *to) {
      report(DiagnosticKind::DegenerateCurve, call_.span,
             "the line starts and ends at the same point");
    }
    curve->from = *from;
    curve->to = *to;
    return finish(std::move(curve));
  }

  Value buildArc() {
    auto curve = std::make_shared<CurveValue>();
    curve->kind = CurveKind::Arc;
    std::optional<std::array<double, 3>> center = point(Parameter::Center);
    std::optional<double> radius = number(Parameter::Radius);
    std::optional<double> from = number(Parameter::From);
    std::optional<double> to = number(Parameter::To);
    if (!center || !radius || !from || !to) {
      return {};
    }
    if (!(*radius > 0)) {
      report(DiagnosticKind::ValueNotPositive, argument(Parameter::Radius)->span,
             fmt::format("the arc's radius is {:g}; it must be positive", *radius));
    }
    if (*from == *to) {
      report(DiagnosticKind::DegenerateCurve, call_.span,
             fmt::format("the arc starts and ends at angle {:g}; it has no length", *from));
    }
    if (argument(Parameter::Z) != nullptr) {
      Value heights = value(Parameter::Z, TypeKind::Range);
      if (heights.isError()) {
        failed_ = true;
        return {};
      }
      curve->startZ = heights.low;
      curve->endZ = heights.high;
    }
    curve->center = *center;
    curve->arcRadius = *radius;
    curve->startAngle = *from;
    curve->endAngle = *to;
    return finish(std::move(curve));
  }

  Value buildPath() {
    auto curve = std::make_shared<CurveValue>();
    curve->kind = CurveKind::Path;
    curve->pieces.reserve(call_.arguments.size());
    for (const Argument& argument : call_.arguments) {
      Value piece = evaluator_.evaluate(*argument.value, bindings_);
      if (piece.type.kind != TypeKind::Curve) {
        if (!piece.isError()) {
          report(
              DiagnosticKind::TypeMismatch, argument.value->span,
              fmt::format("each piece of a path must be a curve, not a {}", typeName(piece.type)));
        }
        failed_ = true;
        continue;
      }
      curve->pieces.push_back(std::move(piece.curve));
    }
    return finish(std::move(curve));
  }

  Value buildTransform() {
    auto curve = std::make_shared<CurveValue>();
    Value piece = value(Parameter::Curve, TypeKind::Curve);
    if (constructor_ == Constructor::Translate) {
      curve->kind = CurveKind::Translate;
      curve->dx = number(Parameter::Dx).value_or(0);
      curve->dy = number(Parameter::Dy).value_or(0);
    } else if (constructor_ == Constructor::Rotate) {
      curve->kind = CurveKind::Rotate;
      curve->angle = number(Parameter::Angle).value_or(0);
    } else {
      curve->kind = CurveKind::Scale;
      std::optional<double> factor = number(Parameter::Factor);
      if (factor && *factor == 0) {
        report(DiagnosticKind::DegenerateCurve, argument(Parameter::Factor)->span,
               "scaling by 0 collapses the curve to a point");
      }
      curve->factor = factor.value_or(1);
    }
    if (piece.isError()) {
      return {};
    }
    curve->pieces.push_back(std::move(piece.curve));
    return finish(std::move(curve));
  }

  Evaluator& evaluator_;
  const CallExpr& call_;
  const Bindings& bindings_;
  Constructor constructor_;
  const ConstructorParameters& parameters_;
  BoundArguments arguments_;
  bool failed_ = false;
};

} // namespace

const Expr* builtinArgument(const CallExpr& call, std::string_view name) {
  const ParameterNames& names = parameterNames(call.callee, constructorOf(call.callee));
  BoundArguments bound = bindBuiltinArguments(call, names);
  for (std::size_t i = 0; i < names.size() && i < maximumParameters; ++i) {
    if (names[i] == name) {
      return bound[i];
    }
  }
  return nullptr;
}

Value buildCurve(Evaluator& evaluator, const CallExpr& call, const Bindings& bindings) {
  return CurveBuilder(evaluator, call, bindings).build();
}

} // namespace cncc::frontend
