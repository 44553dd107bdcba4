#include "cncc/ir/lowering.h"

#include "cncc/geom/arc_length.h"
#include "cncc/geom/discretisation.h"
#include "cncc/geom/function_curve.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/geom/line_arc_curves.h"
#include "cncc/geom/nurbs_curve.h"
#include "cncc/geom/polynomial_span.h"
#include "cncc/ir/builder.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace cncc::ir {

namespace {

using namespace frontend;

// A lowered CDL value: a num or bool (one IR value) or a point (three).
struct Lowered {
  TypeKind kind = TypeKind::Num;
  std::vector<ValueId> values;
};

// Thrown to abandon the lowering after its diagnostic has been reported.
struct LoweringFailed {};

const Expr* modifierValue(const CutStmt& cut, std::string_view name) {
  for (const Modifier& modifier : cut.modifiers) {
    if (modifier.name == name) {
      return modifier.value.get();
    }
  }
  return nullptr;
}

const Modifier* findModifier(const CutStmt& cut, std::string_view name) {
  for (const Modifier& modifier : cut.modifiers) {
    if (modifier.name == name) {
      return &modifier;
    }
  }
  return nullptr;
}

std::string wordOf(const Expr& expression) {
  if (expression.kind == ExprKind::Name) {
    return as<NameExpr>(expression).name;
  }
  if (expression.kind == ExprKind::String) {
    return as<StringExpr>(expression).value;
  }
  return {};
}

const std::map<std::string, Opcode, std::less<>>& unaryMath() {
  static const std::map<std::string, Opcode, std::less<>> table = {
      {"sin", Opcode::Sin},     {"cos", Opcode::Cos},     {"tan", Opcode::Tan},
      {"asin", Opcode::Asin},   {"acos", Opcode::Acos},   {"atan", Opcode::Atan},
      {"sqrt", Opcode::Sqrt},   {"abs", Opcode::Abs},     {"exp", Opcode::Exp},
      {"ln", Opcode::Ln},       {"floor", Opcode::Floor}, {"ceil", Opcode::Ceil},
      {"round", Opcode::Round},
  };
  return table;
}

const std::map<std::string, Opcode, std::less<>>& binaryMath() {
  static const std::map<std::string, Opcode, std::less<>> table = {
      {"atan2", Opcode::Atan2}, {"min", Opcode::Min}, {"max", Opcode::Max}, {"pow", Opcode::Pow}};
  return table;
}

class PartLowering {
public:
  PartLowering(const CheckedProgram& program, const PartItem& part, DiagnosticEngine& diagnostics,
               const LoweringOptions& options)
      : program_(program), part_(part), diagnostics_(diagnostics), options_(options),
        evaluator_(program, scratch_), builder_(part.name) {}

  Function run() {
    for (const frontend::Parameter& parameter : part_.parameters) {
      if (parameter.declaration == nullptr || !parameter.declaration->value ||
          parameter.declaration->value->type.kind != TypeKind::Num) {
        unsupported(parameter.nameSpan, "a parameter without a numeric value");
      }
      double value = parameter.declaration->value->number;
      std::uint32_t index = builder_.addParameter(parameter.name, value);
      bindings_[parameter.declaration] = {TypeKind::Num, {builder_.parameter(index)}};
      environment_[parameter.declaration] = Value::ofNumber(value);
    }
    builder_.comment(fmt::format("part {}", part_.name));
    lowerBlock(part_.body);
    return builder_.finish();
  }

private:
  [[noreturn]] void unsupported(SourceSpan span, std::string_view what) {
    diagnostics_.report(DiagnosticKind::UnsupportedConstruct, span,
                        fmt::format("{} is not supported by this version's lowering", what));
    throw LoweringFailed{};
  }

  [[noreturn]] void fail(SourceSpan span, std::string message) {
    diagnostics_.report(DiagnosticKind::UnsupportedConstruct, span, std::move(message));
    throw LoweringFailed{};
  }

  // --- Statements ----------------------------------------------------------

  void lowerBlock(const Block& block) {
    for (const StmtPtr& statement : block.statements) {
      lowerStatement(*statement);
    }
  }

  void lowerStatement(const Stmt& statement) {
    switch (statement.kind) {
    case StmtKind::Units:
      return; // partUnits() reads it; the IR's numbers are in the part's units
    case StmtKind::Tool:
      return lowerTool(as<ToolStmt>(statement));
    case StmtKind::Feed:
      feed_ = number(*as<ValueStmt>(statement).value);
      return;
    case StmtKind::Spindle:
      builder_.spindle(number(*as<ValueStmt>(statement).value));
      return;
    case StmtKind::Safe:
      for (const Argument& setting : as<SafeStmt>(statement).settings) {
        if (setting.name == "z") {
          safe_ = number(*setting.value);
        }
      }
      return;
    case StmtKind::Let:
      return lowerLet(as<LetStmt>(statement));
    case StmtKind::Cut:
      return lowerCut(as<CutStmt>(statement));
    case StmtKind::For:
      unsupported(statement.span, "a 'for' loop");
    case StmtKind::If:
      unsupported(statement.span, "an 'if' statement");
    case StmtKind::Error:
      fail(statement.span, "cannot lower a statement that did not parse");
    }
  }

  void lowerTool(const ToolStmt& tool) {
    Value toolNumber = evaluate(*tool.number, environment_);
    if (toolNumber.type.kind != TypeKind::Num) {
      unsupported(tool.number->span, "a tool number that is not a constant");
    }
    ValueId diameter = builder_.constant(0);
    std::optional<ValueId> spindle;
    for (const Argument& setting : tool.settings) {
      if (setting.name == "diameter") {
        diameter = number(*setting.value);
      } else if (setting.name == "spindle") {
        spindle = number(*setting.value);
      } else if (setting.name == "feed") {
        feed_ = number(*setting.value);
      }
    }
    builder_.tool(toolNumber.number, diameter);
    if (spindle) {
      builder_.spindle(*spindle);
    }
  }

  void lowerLet(const LetStmt& let) {
    Value value = evaluate(*let.value, environment_);
    if (let.declaration == nullptr || value.isError()) {
      fail(let.value->span, "cannot evaluate this value for lowering");
    }
    environment_[let.declaration] = value;
    TypeKind kind = value.type.kind;
    if (kind == TypeKind::Num || kind == TypeKind::Bool || kind == TypeKind::Point) {
      std::optional<Lowered> lowered = tryLower(*let.value, bindings_, environment_);
      if (lowered) {
        bindings_[let.declaration] = *lowered;
      }
    }
  }

  // --- Expressions ---------------------------------------------------------

  Value evaluate(const Expr& expression, const Environment& environment) {
    scratch_.clear();
    return evaluator_.evaluate(expression, environment);
  }

  ValueId number(const Expr& expression) {
    std::optional<Lowered> lowered = tryLower(expression, bindings_, environment_);
    if (!lowered || lowered->kind != TypeKind::Num) {
      unsupported(expression.span, "this expression");
    }
    return lowered->values.front();
  }

  std::optional<Lowered> constantOf(const Value& value) {
    switch (value.type.kind) {
    case TypeKind::Num:
      return Lowered{TypeKind::Num, {builder_.constant(value.number)}};
    case TypeKind::Bool:
      return Lowered{TypeKind::Bool, {builder_.constantBool(value.boolean)}};
    case TypeKind::Point:
      return Lowered{TypeKind::Point,
                     {builder_.constant(value.point[0]), builder_.constant(value.point[1]),
                      builder_.constant(value.point[2])}};
    default:
      return std::nullopt;
    }
  }

  using Bindings = std::map<const Declaration*, Lowered>;

  // The expression as IR arithmetic; names resolve through `bindings` (IR
  // values), then `environment` (numbers). What has no IR form yet but does
  // not depend on a binding is evaluated to a constant.
  std::optional<Lowered> tryLower(const Expr& expression, const Bindings& bindings,
                                  const Environment& environment) {
    std::optional<Lowered> lowered = lowerDirect(expression, bindings, environment);
    if (lowered) {
      return lowered;
    }
    return constantOf(evaluate(expression, environment));
  }

  std::optional<Lowered> lowerDirect(const Expr& expression, const Bindings& bindings,
                                     const Environment& environment) {
    switch (expression.kind) {
    case ExprKind::Number:
      return Lowered{TypeKind::Num, {builder_.constant(as<NumberExpr>(expression).value)}};
    case ExprKind::Bool:
      return Lowered{TypeKind::Bool, {builder_.constantBool(as<BoolExpr>(expression).value)}};
    case ExprKind::Name: {
      const Declaration* declaration = as<NameExpr>(expression).declaration;
      if (auto found = bindings.find(declaration); found != bindings.end()) {
        return found->second;
      }
      return std::nullopt; // constants, builtins and numbers: evaluated
    }
    case ExprKind::Unary: {
      const auto& unary = as<UnaryExpr>(expression);
      std::optional<Lowered> operand = tryLower(*unary.operand, bindings, environment);
      if (!operand) {
        return std::nullopt;
      }
      Opcode opcode = unary.op == UnaryOperator::Not ? Opcode::Not : Opcode::Neg;
      for (ValueId& value : operand->values) {
        value = builder_.unary(opcode, value);
      }
      return operand;
    }
    case ExprKind::Binary:
      return lowerBinary(as<BinaryExpr>(expression), bindings, environment);
    case ExprKind::Point: {
      const auto& point = as<PointExpr>(expression);
      Lowered result{TypeKind::Point, {}};
      for (const ExprPtr& component : point.components) {
        std::optional<Lowered> value = tryLower(*component, bindings, environment);
        if (!value || value->kind != TypeKind::Num) {
          return std::nullopt;
        }
        result.values.push_back(value->values.front());
      }
      while (result.values.size() < 3) {
        result.values.push_back(builder_.constant(0));
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
    case ExprKind::IfElse: {
      const auto& choice = as<IfElseExpr>(expression);
      std::optional<Lowered> condition = tryLower(*choice.condition, bindings, environment);
      std::optional<Lowered> yes = tryLower(*choice.thenValue, bindings, environment);
      std::optional<Lowered> no = tryLower(*choice.elseValue, bindings, environment);
      if (!condition || !yes || !no || condition->kind != TypeKind::Bool || yes->kind != no->kind ||
          yes->kind == TypeKind::Bool) {
        return std::nullopt;
      }
      for (std::size_t i = 0; i < yes->values.size(); ++i) {
        yes->values[i] = builder_.operation(
            Opcode::Select, {condition->values.front(), yes->values[i], no->values[i]});
      }
      return yes;
    }
    case ExprKind::Call:
      return lowerCall(as<CallExpr>(expression), bindings, environment);
    default:
      return std::nullopt;
    }
  }

  std::optional<Lowered> lowerBinary(const BinaryExpr& binary, const Bindings& bindings,
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
      ValueId result = builder_.binary(opcode, left->values.front(), right->values.front());
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
        ValueId a = left->kind == TypeKind::Point ? left->values[i] : left->values.front();
        ValueId b = right->kind == TypeKind::Point ? right->values[i] : right->values.front();
        result.values.push_back(builder_.binary(opcode, a, b));
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

  std::optional<Lowered> lowerCall(const CallExpr& call, const Bindings& bindings,
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
      if (auto found = unaryMath().find(call.callee);
          found != unaryMath().end() && arguments.size() == 1) {
        return Lowered{TypeKind::Num,
                       {builder_.unary(found->second, arguments[0].values.front())}};
      }
      if (auto found = binaryMath().find(call.callee);
          found != binaryMath().end() && arguments.size() == 2) {
        return Lowered{TypeKind::Num,
                       {builder_.binary(found->second, arguments[0].values.front(),
                                        arguments[1].values.front())}};
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
        inner[function.parameters[i].declaration] = arguments[i];
        Value argument = evaluate(*call.arguments[i].value, environment);
        if (!argument.isError()) {
          innerEnvironment[function.parameters[i].declaration] = argument;
        }
      }
      return tryLower(*function.body, inner, innerEnvironment);
    }
    return std::nullopt;
  }

  // --- Cuts ----------------------------------------------------------------

  struct CurvePoint {
    ValueId x, y, z; // z relative to the pass depth
  };

  // How one curve's points are computed in IR.
  struct CurveLowering {
    std::unique_ptr<geom::Curve> geometry;
    std::shared_ptr<const CurveValue> value;
    std::vector<geom::PolynomialSpan> spans; // NURBS only
  };

  std::unique_ptr<geom::Curve> analyticCurve(const std::shared_ptr<const CurveValue>& curve) {
    auto environment = std::make_shared<Environment>(curve->environment);
    auto evaluator = std::make_shared<ExpressionEvaluator>(program_, scratch_);
    const Declaration* parameter = curve->parameter;
    auto scalar = [environment, evaluator, parameter](const Expr* expression) {
      return [environment, evaluator, parameter, expression](double t) {
        (*environment)[parameter] = Value::ofNumber(t);
        Value value = evaluator->evaluate(*expression, *environment);
        return value.type.kind == TypeKind::Num ? value.number
                                                : std::numeric_limits<double>::quiet_NaN();
      };
    };
    geom::ParameterRange range{curve->low, curve->high};
    if (curve->kind == CurveKind::Polar) {
      return std::make_unique<geom::PolarCurve>(range, scalar(curve->radius));
    }
    geom::ScalarFunction z;
    if (curve->z != nullptr) {
      z = scalar(curve->z);
    }
    return std::make_unique<geom::FunctionCurve>(
        geom::FunctionCurve::fromCoordinates(range, scalar(curve->x), scalar(curve->y), z));
  }

  CurveLowering curveFor(const CutStmt& cut) {
    Value value = evaluate(*cut.curve, environment_);
    if (value.type.kind != TypeKind::Curve || !value.curve) {
      fail(cut.curve->span, "cannot evaluate this curve for lowering");
    }
    CurveLowering lowering;
    lowering.value = value.curve;
    const CurveValue& curve = *value.curve;
    switch (curve.kind) {
    case CurveKind::Nurbs: {
      std::vector<Eigen::Vector3d> points;
      for (const auto& point : curve.points) {
        points.emplace_back(point[0], point[1], point[2]);
      }
      std::vector<double> weights = curve.weights;
      if (weights.empty()) {
        weights.assign(points.size(), 1.0);
      }
      auto nurbs = std::make_unique<geom::NurbsCurve>(geom::KnotVector(curve.knots, curve.degree),
                                                      points, weights);
      lowering.spans = geom::toPowerBasis(*nurbs);
      lowering.geometry = std::move(nurbs);
      break;
    }
    case CurveKind::Polar:
    case CurveKind::Param:
      lowering.geometry = analyticCurve(value.curve);
      break;
    case CurveKind::Line:
      lowering.geometry = std::make_unique<geom::LineCurve>(
          Eigen::Vector3d(curve.from[0], curve.from[1], curve.from[2]),
          Eigen::Vector3d(curve.to[0], curve.to[1], curve.to[2]));
      break;
    case CurveKind::Arc:
      lowering.geometry = std::make_unique<geom::ArcCurve>(
          Eigen::Vector2d(curve.center[0], curve.center[1]), curve.arcRadius, curve.startAngle,
          curve.endAngle - curve.startAngle);
      break;
    default:
      unsupported(cut.curve->span, fmt::format("a '{}' curve", curve.constructor));
    }
    return lowering;
  }

  // The point at parameter t (analytic curves, lines, arcs).
  CurvePoint pointAt(const CurveLowering& lowering, ValueId t, const CutStmt& cut) {
    const CurveValue& curve = *lowering.value;
    auto constant = [&](double v) { return builder_.constant(v); };
    switch (curve.kind) {
    case CurveKind::Polar:
    case CurveKind::Param: {
      Bindings bindings = bindings_;
      bindings[curve.parameter] = {TypeKind::Num, {t}};
      auto lower = [&](const Expr* expression) {
        std::optional<Lowered> value = tryLower(*expression, bindings, curve.environment);
        if (!value || value->kind != TypeKind::Num) {
          unsupported(expression->span, "this curve expression");
        }
        return value->values.front();
      };
      if (curve.kind == CurveKind::Polar) {
        ValueId r = lower(curve.radius);
        return {builder_.binary(Opcode::Mul, r, builder_.unary(Opcode::Cos, t)),
                builder_.binary(Opcode::Mul, r, builder_.unary(Opcode::Sin, t)), constant(0)};
      }
      return {lower(curve.x), lower(curve.y), curve.z ? lower(curve.z) : constant(0)};
    }
    case CurveKind::Line: {
      const auto& line = static_cast<const geom::LineCurve&>(*lowering.geometry);
      double length = line.domain().t1;
      ValueId s = builder_.binary(Opcode::Div, t, constant(length));
      CurvePoint point{};
      ValueId* out[3] = {&point.x, &point.y, &point.z};
      for (int i = 0; i < 3; ++i) {
        *out[i] = builder_.binary(
            Opcode::Add, constant(curve.from[i]),
            builder_.binary(Opcode::Mul, constant(curve.to[i] - curve.from[i]), s));
      }
      return point;
    }
    case CurveKind::Arc: {
      const auto& arc = static_cast<const geom::ArcCurve&>(*lowering.geometry);
      ValueId angle = builder_.binary(
          Opcode::Add, constant(curve.startAngle),
          builder_.binary(Opcode::Mul, constant(arc.sweep() / arc.length()), t));
      ValueId r = constant(curve.arcRadius);
      return {builder_.binary(Opcode::Add, constant(curve.center[0]),
                              builder_.binary(Opcode::Mul, r, builder_.unary(Opcode::Cos, angle))),
              builder_.binary(Opcode::Add, constant(curve.center[1]),
                              builder_.binary(Opcode::Mul, r, builder_.unary(Opcode::Sin, angle))),
              constant(0)};
    }
    default:
      unsupported(cut.curve->span, fmt::format("a '{}' curve", curve.constructor));
    }
  }

  // A NURBS point: span `index` at local u in [0, 1], by Horner's rule.
  CurvePoint spanPointAt(const geom::PolynomialSpan& span, ValueId u) {
    auto horner = [&](int coordinate) {
      int degree = span.degree();
      ValueId sum = builder_.constant(span.coefficients[static_cast<std::size_t>(degree)][coordinate]);
      for (int k = degree - 1; k >= 0; --k) {
        sum = builder_.binary(
            Opcode::Add, builder_.binary(Opcode::Mul, sum, u),
            builder_.constant(span.coefficients[static_cast<std::size_t>(k)][coordinate]));
      }
      return sum;
    };
    CurvePoint point{horner(0), horner(1), horner(2)};
    if (span.isRational()) {
      ValueId w = horner(3);
      point.x = builder_.binary(Opcode::Div, point.x, w);
      point.y = builder_.binary(Opcode::Div, point.y, w);
      point.z = builder_.binary(Opcode::Div, point.z, w);
    }
    return point;
  }

  static constexpr double maximumPointsPerCut = 1'000'000;

  geom::CurveSamples samplesFor(const CutStmt& cut, const geom::Curve& curve) {
    auto numberOf = [&](std::string_view name) -> std::optional<double> {
      const Expr* expression = modifierValue(cut, name);
      if (expression == nullptr) {
        return std::nullopt;
      }
      Value value = evaluate(*expression, environment_);
      if (value.type.kind != TypeKind::Num) {
        fail(expression->span, "cannot evaluate this modifier for lowering");
      }
      return value.number;
    };
    try {
      if (std::optional<double> samples = numberOf("samples")) {
        return geom::sampleUniformParameter(curve, static_cast<std::size_t>(*samples));
      }
      if (std::optional<double> spacing = numberOf("spacing")) {
        double count = geom::arcLength(curve) / *spacing;
        if (!(count <= maximumPointsPerCut)) {
          diagnostics_.report(DiagnosticKind::ProgramTooLarge, cut.span,
                              fmt::format("spacing={:g} would put {:.0f} points on this curve; "
                                          "the limit is {:.0f}",
                                          *spacing, count, maximumPointsPerCut));
          throw LoweringFailed{};
        }
        return geom::sampleEqualArcLength(curve, *spacing);
      }
      double tolerance = numberOf("tolerance").value_or(options_.defaultTolerance);
      return geom::discretiseByChordTolerance(curve, tolerance);
    } catch (const geom::GeometryError& error) {
      fail(cut.curve->span, fmt::format("cannot discretise this curve: {}", error.what()));
    }
  }

  void lowerCut(const CutStmt& cut) {
    if (const Modifier* method = findModifier(cut, "method")) {
      std::string word = method->value ? wordOf(*method->value) : "";
      if (word != "linear") {
        unsupported(method->span(), fmt::format("method={}", word));
      }
    }
    if (const Modifier* entry = findModifier(cut, "entry")) {
      std::string word = entry->value ? wordOf(*entry->value) : "";
      if (word != "plunge" && word != "ramp") {
        unsupported(entry->span(), fmt::format("entry={}", word));
      }
    }
    if (!safe_) {
      fail(cut.span, "this cut has no safe height; write 'safe z=Z' before it");
    }
    ValueId feed = feed_.value_or(ValueId{});
    if (const Expr* expression = modifierValue(cut, "feed")) {
      feed = number(*expression);
    }
    if (!feed.valid()) {
      fail(cut.span, "this cut has no feed rate");
    }

    CurveLowering curve = curveFor(cut);
    geom::CurveSamples samples = samplesFor(cut, *curve.geometry);
    for (const Eigen::Vector3d& point : samples.points) {
      if (!point.allFinite()) {
        fail(cut.curve->span, "this curve has a point that is not a finite number");
      }
    }
    if (samples.parameters.size() < 2) {
      fail(cut.curve->span, "this curve gave fewer than two points");
    }

    // The pass depths: -S, -2S, ... ending exactly at -D; or one pass at 0.
    std::vector<double> depths;
    const Expr* depthExpression = modifierValue(cut, "depth");
    const Expr* stepExpression = modifierValue(cut, "step");
    if (depthExpression != nullptr && stepExpression != nullptr) {
      Value depth = evaluate(*depthExpression, environment_);
      Value step = evaluate(*stepExpression, environment_);
      if (depth.type.kind != TypeKind::Num || step.type.kind != TypeKind::Num ||
          !(step.number > 0) || !(depth.number >= step.number)) {
        fail(cut.span, "cannot evaluate this sweep for lowering");
      }
      for (int k = 1;; ++k) {
        double z = k * step.number;
        if (z >= depth.number - 1e-9 * depth.number) {
          depths.push_back(depth.number);
          break;
        }
        depths.push_back(z);
      }
    } else if (depthExpression != nullptr || stepExpression != nullptr) {
      fail(cut.span, "a sweep needs both depth= and step=");
    } else {
      depths.push_back(0);
    }

    // The curve's parameter tables: one per NURBS span (local u), or one for
    // the whole curve (t). The first sample is the start, reached by the plunge.
    std::vector<std::pair<std::uint32_t, std::size_t>> tables; // (table, span)
    if (!curve.spans.empty()) {
      std::size_t span = 0;
      std::vector<std::vector<double>> perSpan(curve.spans.size());
      for (std::size_t i = 1; i < samples.parameters.size(); ++i) {
        double t = samples.parameters[i];
        while (span + 1 < curve.spans.size() && t > curve.spans[span].t1) {
          ++span;
        }
        const geom::PolynomialSpan& s = curve.spans[span];
        perSpan[span].push_back(std::clamp((t - s.t0) / (s.t1 - s.t0), 0.0, 1.0));
      }
      for (std::size_t k = 0; k < perSpan.size(); ++k) {
        if (!perSpan[k].empty()) {
          tables.emplace_back(builder_.addTable(std::move(perSpan[k])), k);
        }
      }
    } else {
      tables.emplace_back(builder_.addTable(std::vector<double>(samples.parameters.begin() + 1,
                                                                samples.parameters.end())),
                          0);
    }

    // entry=ramp: each pass descends from the previous depth over one lap of
    // the (closed) curve, its z linear in the curve parameter, then cuts a
    // full lap at its depth.
    bool ramp = false;
    if (const Modifier* entry = findModifier(cut, "entry")) {
      ramp = entry->value && wordOf(*entry->value) == "ramp";
      double gap = (samples.points.front() - samples.points.back()).norm();
      if (ramp && !(gap <= 1e-6)) {
        unsupported(entry->span(), "entry=ramp on a curve that does not close");
      }
    }
    double t0 = samples.parameters.front();
    double t1 = samples.parameters.back();

    // One lap: z = zFrom + (zTo - zFrom) * (t - t0) / (t1 - t0) over the
    // lap, plus the curve's own z.
    auto lap = [&](double zFrom, double zTo, ValueId feedRate) {
      for (auto [table, span] : tables) {
        std::size_t count = function().tables[table].size();
        ValueId index = builder_.beginLoop(builder_.constant(0),
                                           builder_.constant(static_cast<double>(count) - 1));
        ValueId parameter = builder_.tableLoad(table, index);
        CurvePoint point;
        ValueId t = parameter;
        if (curve.spans.empty()) {
          point = pointAt(curve, parameter, cut);
        } else {
          const geom::PolynomialSpan& s = curve.spans[span];
          point = spanPointAt(s, parameter);
          t = builder_.binary(Opcode::Add, builder_.constant(s.t0),
                              builder_.binary(Opcode::Mul, builder_.constant(s.t1 - s.t0),
                                              parameter));
        }
        ValueId z = builder_.constant(zTo);
        if (zFrom != zTo) {
          ValueId fraction = builder_.binary(
              Opcode::Div, builder_.binary(Opcode::Sub, t, builder_.constant(t0)),
              builder_.constant(t1 - t0));
          z = builder_.binary(Opcode::Add, builder_.constant(zFrom),
                              builder_.binary(Opcode::Mul, builder_.constant(zTo - zFrom),
                                              fraction));
        }
        builder_.feed(point.x, point.y, builder_.binary(Opcode::Add, z, point.z), feedRate);
        builder_.endLoop();
      }
    };

    double previous = 0;
    for (double depth : depths) {
      builder_.comment(depths.size() > 1 ? fmt::format("pass at depth {}", depth) : "cut");
      double passZ = depth == 0 ? 0.0 : -depth;
      double entryZ = ramp ? previous : passZ;
      CurvePoint start = curve.spans.empty()
                             ? pointAt(curve, builder_.constant(t0), cut)
                             : spanPointAt(curve.spans.front(), builder_.constant(0));
      builder_.rapid(start.x, start.y, *safe_);
      builder_.feed(start.x, start.y,
                    builder_.binary(Opcode::Add, builder_.constant(entryZ), start.z), feed);
      if (ramp) {
        builder_.comment("ramp");
        lap(entryZ, passZ, feed);
      }
      lap(passZ, passZ, feed);
      // The retract: straight up from the end of the curve.
      CurvePoint end = curve.spans.empty()
                           ? pointAt(curve, builder_.constant(t1), cut)
                           : spanPointAt(curve.spans.back(), builder_.constant(1));
      builder_.rapid(end.x, end.y, *safe_);
      previous = passZ;
    }
  }

  const Function& function() const { return builder_.function(); }

  const CheckedProgram& program_;
  const PartItem& part_;
  DiagnosticEngine& diagnostics_;
  const LoweringOptions& options_;
  // Diagnostics of speculative evaluations (their failures are handled here).
  DiagnosticEngine scratch_{0};
  ExpressionEvaluator evaluator_;
  FunctionBuilder builder_;
  Bindings bindings_;
  Environment environment_;
  std::optional<ValueId> feed_;
  std::optional<ValueId> safe_;
};

} // namespace

std::optional<Function> lowerPart(const CheckedProgram& program, const PartItem& part,
                                  DiagnosticEngine& diagnostics, const LoweringOptions& options) {
  try {
    PartLowering lowering(program, part, diagnostics, options);
    return lowering.run();
  } catch (const LoweringFailed&) {
    return std::nullopt;
  } catch (const geom::GeometryError& error) {
    diagnostics.report(DiagnosticKind::DegenerateCurve, part.nameSpan,
                       fmt::format("cannot lower this part: {}", error.what()));
    return std::nullopt;
  }
}

PartUnits partUnits(const PartItem& part) {
  for (const StmtPtr& statement : part.body.statements) {
    if (statement->kind == StmtKind::Units) {
      return as<UnitsStmt>(*statement).unit == "inch" ? PartUnits::Inches : PartUnits::Millimetres;
    }
  }
  return PartUnits::Millimetres;
}

} // namespace cncc::ir
