// Curve constructors evaluated to CurveValues, with the geometric checks a
// user needs before anything is generated: order against the number of
// points, weights, knot vectors, empty ranges, degenerate shapes.
#include "evaluator.h"

#include <cmath>
#include <cstring>
#include <fmt/format.h>
#include <map>

namespace cncc::frontend {

using namespace std::string_view_literals;

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

// The parameter names of each builtin, built once.
const std::vector<std::string>& parameterNames(const std::string& builtin) {
  static const std::map<std::string, std::vector<std::string>> table = [] {
    std::map<std::string, std::vector<std::string>> names;
    for (const BuiltinInfo& info : builtinFunctions()) {
      for (const BuiltinParameter& parameter : info.parameters) {
        names[info.name].push_back(parameter.name);
      }
    }
    return names;
  }();
  static const std::vector<std::string> none;
  auto found = table.find(builtin);
  return found == table.end() ? none : found->second;
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
    return a.string == b.string;
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
        names_(parameterNames(call.callee)), arguments_(Evaluator::bindArguments(call, names_)) {}

  Value build() {
    const std::string& name = call_.callee;
    if (name == "nurbs"sv || name == "bspline"sv || name == "bezier"sv) {
      return buildNurbs();
    }
    if (name == "polar"sv || name == "param"sv) {
      return buildAnalytic();
    }
    if (name == "line"sv) {
      return buildLine();
    }
    if (name == "arc"sv) {
      return buildArc();
    }
    if (name == "path"sv) {
      return buildPath();
    }
    return buildTransform();
  }

private:
  const Expr* argument(std::string_view name) const {
    for (std::size_t i = 0; i < names_.size(); ++i) {
      if (std::string_view(names_[i]) == name) {
        return arguments_[i];
      }
    }
    return nullptr;
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

  std::optional<Value> value(std::string_view name, TypeKind kind) {
    const Expr* expression = argument(name);
    if (expression == nullptr) {
      return std::nullopt;
    }
    Value result = evaluator_.evaluate(*expression, bindings_);
    if (result.isError()) {
      failed_ = true;
      return std::nullopt;
    }
    if (result.type.kind != kind) {
      evaluator_.report(DiagnosticKind::TypeMismatch, expression->span,
                        fmt::format("argument '{}' of '{}' must be a {}, not a {}", name,
                                    call_.callee, typeKindName(kind), typeName(result.type)));
      failed_ = true;
      return std::nullopt;
    }
    return result;
  }

  std::optional<double> number(std::string_view name) {
    std::optional<Value> result = value(name, TypeKind::Num);
    return result ? std::optional<double>(result->number) : std::nullopt;
  }

  std::optional<std::array<double, 3>> point(std::string_view name) {
    std::optional<Value> result = value(name, TypeKind::Point);
    return result ? std::optional(result->point) : std::nullopt;
  }

  std::optional<std::vector<double>> numbers(std::string_view name) {
    std::optional<Value> list = value(name, TypeKind::List);
    if (!list) {
      return std::nullopt;
    }
    std::vector<double> result;
    for (std::size_t i = 0; i < list->list->size(); ++i) {
      const Value& element = (*list->list)[i];
      if (element.type.kind != TypeKind::Num) {
        evaluator_.report(DiagnosticKind::TypeMismatch, elementSpan(*argument(name), i),
                          fmt::format("'{}' must hold numbers", name));
        failed_ = true;
        return std::nullopt;
      }
      result.push_back(element.number);
    }
    return result;
  }

  std::optional<std::vector<std::array<double, 3>>> points(std::string_view name) {
    std::optional<Value> list = value(name, TypeKind::List);
    if (!list) {
      return std::nullopt;
    }
    std::vector<std::array<double, 3>> result;
    for (std::size_t i = 0; i < list->list->size(); ++i) {
      const Value& element = (*list->list)[i];
      if (element.type.kind != TypeKind::Point) {
        evaluator_.report(DiagnosticKind::TypeMismatch, elementSpan(*argument(name), i),
                          fmt::format("'{}' must hold points", name));
        failed_ = true;
        return std::nullopt;
      }
      result.push_back(element.point);
    }
    return result;
  }

  void report(DiagnosticKind kind, SourceSpan span, std::string message) {
    evaluator_.report(kind, span, std::move(message));
    failed_ = true;
  }

  Value finish(std::shared_ptr<CurveValue> curve) {
    if (failed_) {
      return {};
    }
    curve->constructor = call_.callee;
    return Value::ofCurve(std::move(curve));
  }

  // ------------------------------------------------------------ nurbs
  std::optional<int> order() {
    if (call_.callee == "bezier"sv) {
      return std::nullopt;
    }
    bool byDegree = argument("order") == nullptr;
    const char* name = byDegree ? "degree" : "order";
    std::optional<double> given = number(name);
    if (!given) {
      return std::nullopt;
    }
    const Expr& expression = *argument(name);
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
    std::optional<std::vector<std::array<double, 3>>> controlPoints = points("points");
    if (!controlPoints) {
      failed_ = true;
      return {};
    }
    std::size_t n = controlPoints->size();
    const Expr& pointsExpression = *argument("points");
    if (call_.callee == "bezier"sv) {
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
    curve->points = *controlPoints;
    curve->weights = checkWeights(n);
    curve->knots = checkKnots(n, *k);
    return finish(std::move(curve));
  }

  std::vector<double> checkWeights(std::size_t n) {
    if (argument("weights") == nullptr) {
      return std::vector<double>(n, 1.0);
    }
    std::optional<std::vector<double>> weights = numbers("weights");
    if (!weights) {
      return {};
    }
    const Expr& expression = *argument("weights");
    if (weights->size() != n) {
      report(DiagnosticKind::WeightsCount, argumentSpan(expression),
             fmt::format("'weights' has {} entries but 'points' has {}", weights->size(), n));
      return {};
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (!((*weights)[i] > 0)) {
        report(
            DiagnosticKind::WeightNotPositive, elementSpan(expression, i),
            fmt::format("weight {} is {:g}; every weight must be positive", i + 1, (*weights)[i]));
      }
    }
    return *weights;
  }

  std::vector<double> checkKnots(std::size_t n, int k) {
    std::size_t order = static_cast<std::size_t>(k);
    if (argument("knots") == nullptr) {
      return clampedUniformKnots(n, k);
    }
    std::optional<std::vector<double>> knots = numbers("knots");
    if (!knots) {
      return {};
    }
    const Expr& expression = *argument("knots");
    if (knots->size() != n + order) {
      report(DiagnosticKind::KnotsCount, expression.span,
             fmt::format("'knots' has {} entries but needs {} ({} points + order {})",
                         knots->size(), n + order, n, k));
      return {};
    }
    for (std::size_t i = 1; i < knots->size(); ++i) {
      if ((*knots)[i] < (*knots)[i - 1]) {
        report(DiagnosticKind::KnotsNotMonotonic, elementSpan(expression, i),
               fmt::format("knot {} ({:g}) is smaller than knot {} ({:g}); knots must not "
                           "decrease",
                           i + 1, (*knots)[i], i, (*knots)[i - 1]));
        return {};
      }
    }
    if (!((*knots)[order - 1] < (*knots)[n])) {
      report(DiagnosticKind::DegenerateCurve, expression.span,
             fmt::format("the knots leave the curve no parameter range (knot {} equals knot {})", k,
                         n + 1));
    }
    return *knots;
  }

  // ------------------------------------------------------------ polar, param
  Value buildAnalytic() {
    auto curve = std::make_shared<CurveValue>();
    bool polar = call_.callee == "polar"sv;
    curve->kind = polar ? CurveKind::Polar : CurveKind::Param;
    std::optional<Value> range = value("t", TypeKind::Range);
    auto found = evaluator_.context().program.curveParameters.find(&call_);
    if (!range || found == evaluator_.context().program.curveParameters.end()) {
      failed_ = true;
      return {};
    }
    const Expr& rangeExpression = *argument("t");
    if (!(range->low < range->high)) {
      report(DiagnosticKind::EmptyRange, rangeExpression.span,
             fmt::format("the range {:g} .. {:g} is empty; a curve's parameter needs start < end",
                         range->low, range->high));
      return {};
    }
    curve->low = range->low;
    curve->high = range->high;
    curve->parameter = found->second;
    curve->environment = bindings_.flatten();
    curve->radius = argument("r");
    curve->x = argument("x");
    curve->y = argument("y");
    curve->z = argument("z");
    sampleExpressions(*curve);
    return finish(std::move(curve));
  }

  // Evaluates the curve's expressions along its range, so a curve that is
  // undefined somewhere (sqrt of a negative, a division by zero) is an error
  // now rather than a bad program later. The same call with the same values
  // (a curve made by a fn called in a loop) is evaluated once: a sampling
  // that reported nothing and computed no constant would do nothing else
  // again, and spends its steps again.
  void sampleExpressions(CurveValue& curve) {
    Evaluator::Progress before = evaluator_.progress();
    auto& samplings = evaluator_.samplings();
    if (auto found = samplings.find(&call_);
        found != samplings.end() && found->second.callDepth == before.callDepth &&
        sameEnvironment(found->second.environment, curve.environment) &&
        evaluator_.spendSteps(found->second.steps)) {
      return;
    }
    sampleAll(curve);
    Evaluator::Progress after = evaluator_.progress();
    if (!failed_ && !evaluator_.exhausted() && after.reports == before.reports &&
        after.constants == before.constants) {
      samplings[&call_] = {curve.environment, before.callDepth, after.steps - before.steps};
    }
  }

  void sampleAll(CurveValue& curve) {
    constexpr int samples = 16;
    Bindings sample(&bindings_);
    for (int i = 0; i <= samples && !failed_ && !evaluator_.exhausted(); ++i) {
      double t = curve.low + (curve.high - curve.low) * i / samples;
      sample.bind(curve.parameter, Value::ofNumber(t));
      for (const Expr* expression : {curve.radius, curve.x, curve.y, curve.z}) {
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

  // ------------------------------------------------------------ others
  Value buildLine() {
    auto curve = std::make_shared<CurveValue>();
    curve->kind = CurveKind::Line;
    std::optional<std::array<double, 3>> from = point("from");
    std::optional<std::array<double, 3>> to = point("to");
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
    std::optional<std::array<double, 3>> center = point("center");
    std::optional<double> radius = number("radius");
    std::optional<double> from = number("from");
    std::optional<double> to = number("to");
    if (!center || !radius || !from || !to) {
      return {};
    }
    if (!(*radius > 0)) {
      report(DiagnosticKind::ValueNotPositive, argument("radius")->span,
             fmt::format("the arc's radius is {:g}; it must be positive", *radius));
    }
    if (*from == *to) {
      report(DiagnosticKind::DegenerateCurve, call_.span,
             fmt::format("the arc starts and ends at angle {:g}; it has no length", *from));
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
      curve->pieces.push_back(piece.curve);
    }
    return finish(std::move(curve));
  }

  Value buildTransform() {
    auto curve = std::make_shared<CurveValue>();
    std::optional<Value> piece = value("curve", TypeKind::Curve);
    const std::string& name = call_.callee;
    if (name == "translate"sv) {
      curve->kind = CurveKind::Translate;
      curve->dx = number("dx").value_or(0);
      curve->dy = number("dy").value_or(0);
    } else if (name == "rotate"sv) {
      curve->kind = CurveKind::Rotate;
      curve->angle = number("angle").value_or(0);
    } else {
      curve->kind = CurveKind::Scale;
      std::optional<double> factor = number("factor");
      if (factor && *factor == 0) {
        report(DiagnosticKind::DegenerateCurve, argument("factor")->span,
               "scaling by 0 collapses the curve to a point");
      }
      curve->factor = factor.value_or(1);
    }
    if (!piece) {
      return {};
    }
    curve->pieces.push_back(piece->curve);
    return finish(std::move(curve));
  }

  Evaluator& evaluator_;
  const CallExpr& call_;
  const Bindings& bindings_;
  const std::vector<std::string>& names_;
  std::vector<const Expr*> arguments_;
  bool failed_ = false;
};

} // namespace

const Expr* builtinArgument(const CallExpr& call, std::string_view name) {
  const std::vector<std::string>& names = parameterNames(call.callee);
  std::vector<const Expr*> bound = Evaluator::bindArguments(call, names);
  for (std::size_t i = 0; i < names.size(); ++i) {
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
