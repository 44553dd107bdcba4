// A cut's curve: flattened into smooth pieces (a path's pieces in order,
// translate/rotate/scale composed into one transform per piece), the whole
// as one geom curve for choosing the points, and each piece's point in IR
// arithmetic at a parameter the IR loads from a table.
#include "part_lowering.h"

#include "cncc/frontend/compiled_number.h"
#include "cncc/geom/composite_curve.h"
#include "cncc/geom/function_curve.h"
#include "cncc/geom/line_arc_curves.h"
#include "cncc/geom/nurbs_curve.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace cncc::ir::lowering {

using namespace frontend;

namespace {

// What an analytic curve evaluates its expressions with; shared by the
// curve's callbacks, so that the curve outlives the lowering (it still
// needs the checked program).
struct AnalyticContext {
  AnalyticContext(const CheckedProgram& program, Environment values)
      : evaluator(program, diagnostics), environment(std::move(values)) {}
  DiagnosticEngine diagnostics{0};
  RenewingEvaluator evaluator;
  Environment environment;
};

Eigen::Vector3d vector(const std::array<double, 3>& point) {
  return {point[0], point[1], point[2]};
}

} // namespace

CutCurve PartLowering::cutCurve(const CutStmt& cut) {
  Value value = evaluate(*cut.curve, environment_);
  if (value.type.kind != TypeKind::Curve || !value.curve) {
    fail(cut.curve->span, "cannot evaluate this curve for lowering");
  }
  CutCurve curve;
  addPieces(value.curve, Affine{}, cut, curve);
  if (curve.pieces.empty()) {
    fail(cut.curve->span, "this path has no pieces to cut", DiagnosticKind::DegenerateCurve);
  }
  joinPieces(curve, cut);
  return curve;
}

void PartLowering::addPieces(const std::shared_ptr<const CurveValue>& value,
                             const Affine& transform, const CutStmt& cut, CutCurve& curve) {
  switch (value->kind) {
  case CurveKind::Path:
    for (const auto& piece : value->pieces) {
      addPieces(piece, transform, cut, curve);
    }
    return;
  case CurveKind::Translate:
  case CurveKind::Rotate:
  case CurveKind::Scale: {
    if (value->pieces.size() != 1) {
      fail(cut.curve->span, "cannot evaluate this transformed curve for lowering");
    }
    Affine own = value->kind == CurveKind::Translate ? Affine::translation(value->dx, value->dy)
                 : value->kind == CurveKind::Rotate  ? Affine::rotation(value->angle)
                                                     : Affine::scaling(value->factor);
    // The inner curve is moved first, then the enclosing transforms apply.
    addPieces(value->pieces.front(), transform.after(own), cut, curve);
    return;
  }
  default: {
    CurvePiece piece = leafPiece(value, cut);
    piece.transform = transform;
    curve.pieces.push_back(std::move(piece));
    return;
  }
  }
}

CurvePiece PartLowering::leafPiece(const std::shared_ptr<const CurveValue>& value,
                                   const CutStmt& cut) {
  CurvePiece piece;
  piece.value = value;
  const CurveValue& curve = *value;
  switch (curve.kind) {
  case CurveKind::Nurbs: {
    std::vector<Eigen::Vector3d> points;
    for (const auto& point : curve.points) {
      points.push_back(vector(point));
    }
    std::vector<double> weights = curve.weights;
    if (weights.empty()) {
      weights.assign(points.size(), 1.0);
    }
    auto nurbs = std::make_shared<geom::NurbsCurve>(geom::KnotVector(curve.knots, curve.degree),
                                                    points, weights);
    piece.spans = geom::toPowerBasis(*nurbs);
    piece.geometry = std::move(nurbs);
    break;
  }
  case CurveKind::Polar:
  case CurveKind::Param:
    piece.geometry = analyticCurve(value);
    break;
  case CurveKind::Line:
    piece.geometry = std::make_shared<geom::LineCurve>(vector(curve.from), vector(curve.to));
    break;
  case CurveKind::Arc:
    piece.geometry = std::make_shared<geom::ArcCurve>(
        Eigen::Vector2d(curve.center[0], curve.center[1]), curve.arcRadius, curve.startAngle,
        curve.endAngle - curve.startAngle, curve.startZ, curve.endZ - curve.startZ);
    break;
  default:
    unsupported(cut.curve->span, fmt::format("a '{}' curve", curve.constructor));
  }
  return piece;
}

std::shared_ptr<const geom::Curve>
PartLowering::analyticCurve(const std::shared_ptr<const CurveValue>& curve) {
  auto context = std::make_shared<AnalyticContext>(program_, curve->environment);
  const Declaration* parameter = curve->parameter;
  std::vector<const Expr*> expressions =
      curve->kind == CurveKind::Polar ? std::vector<const Expr*>{curve->radius}
                                      : std::vector<const Expr*>{curve->x, curve->y, curve->z};
  // Compiled, the expressions give the evaluator's values to the bit, and
  // the evaluator's own where the compiled form gives up. All are compiled
  // or none: the evaluator is renewed after so many evaluations, and one
  // expression left to it alone would spend its steps faster than before.
  std::vector<std::shared_ptr<const CompiledNumber>> compiled;
  for (const Expr* expression : expressions) {
    if (expression == nullptr) {
      compiled.push_back(nullptr);
      continue;
    }
    std::optional<CompiledNumber> number =
        CompiledNumber::compile(*expression, context->environment, parameter);
    if (!number) {
      compiled.assign(expressions.size(), nullptr);
      break;
    }
    compiled.push_back(std::make_shared<const CompiledNumber>(std::move(*number)));
  }
  auto scalar = [&](std::size_t index) -> geom::ScalarFunction {
    const Expr* expression = expressions[index];
    if (expression == nullptr) {
      return {};
    }
    return [context, parameter, expression, compiled = compiled[index]](double t) {
      double number = 0;
      if (compiled && compiled->evaluate(t, number)) {
        return number;
      }
      context->diagnostics.clear();
      context->environment[parameter] = Value::ofNumber(t);
      Value value = context->evaluator.evaluate(*expression, context->environment);
      return value.type.kind == TypeKind::Num ? value.number
                                              : std::numeric_limits<double>::quiet_NaN();
    };
  };
  geom::ParameterRange range{curve->low, curve->high};
  if (curve->kind == CurveKind::Polar) {
    return std::make_shared<geom::PolarCurve>(range, scalar(0));
  }
  return std::make_shared<geom::FunctionCurve>(
      geom::FunctionCurve::fromCoordinates(range, scalar(0), scalar(1), scalar(2)));
}

void PartLowering::joinPieces(CutCurve& curve, const CutStmt& cut) {
  std::vector<std::shared_ptr<const geom::Curve>> moved;
  for (const CurvePiece& piece : curve.pieces) {
    moved.push_back(piece.transform.isIdentity()
                        ? piece.geometry
                        : std::make_shared<TransformedCurve>(piece.geometry, piece.transform));
  }
  if (moved.size() == 1) {
    geom::ParameterRange domain = moved.front()->domain();
    curve.geometry = moved.front();
    curve.pieceStarts = {domain.t0, domain.t1};
    return;
  }
  curve.pieceStarts = {0.0};
  for (std::size_t i = 0; i < moved.size(); ++i) {
    geom::ParameterRange domain = moved[i]->domain();
    if (i > 0) {
      Eigen::Vector3d end = moved[i - 1]->point(moved[i - 1]->domain().t1);
      double gap = (moved[i]->point(domain.t0) - end).norm();
      if (!(gap <= pathJoinTolerance)) {
        fail(cut.curve->span,
             fmt::format("the pieces of this path do not join: piece {} starts {:.6g} from "
                         "where piece {} ends at ({:.6g}, {:.6g}, {:.6g})",
                         i + 1, gap, i, end.x(), end.y(), end.z()),
             DiagnosticKind::DegenerateCurve);
      }
    }
    curve.pieceStarts.push_back(curve.pieceStarts.back() + domain.length());
  }
  curve.geometry = std::make_shared<geom::CompositeCurve>(std::move(moved), pathJoinTolerance);
}

SampleLocation PartLowering::locate(const CutCurve& curve, double t) const {
  SampleLocation location;
  // The later piece at a join, as geom::CompositeCurve evaluates it.
  std::size_t count = curve.pieces.size();
  while (location.piece + 1 < count && curve.pieceStarts[location.piece + 1] <= t) {
    ++location.piece;
  }
  const CurvePiece& piece = curve.pieces[location.piece];
  geom::ParameterRange domain = piece.geometry->domain();
  double own = count == 1 ? t : domain.t0 + (t - curve.pieceStarts[location.piece]);
  return locateInPiece(curve, location.piece, own);
}

SampleLocation PartLowering::locateInPiece(const CutCurve& curve, std::size_t piece, double own) {
  const CurvePiece& value = curve.pieces[piece];
  SampleLocation location{piece, 0, value.geometry->domain().clamp(own)};
  if (!value.spans.empty()) {
    while (location.span + 1 < value.spans.size() &&
           value.spans[location.span + 1].t0 <= location.local) {
      ++location.span;
    }
    const geom::PolynomialSpan& span = value.spans[location.span];
    location.local = std::clamp((location.local - span.t0) / (span.t1 - span.t0), 0.0, 1.0);
  }
  return location;
}

CurvePoint PartLowering::pointAt(const CutCurve& curve, std::size_t piece, std::size_t span,
                                 Scalar local, const CutStmt& cut) {
  const CurvePiece& own = curve.pieces[piece];
  return transformed(own.transform, untransformedPointAt(own, span, local, cut));
}

CurvePoint PartLowering::transformed(const Affine& transform, const CurvePoint& point) {
  if (transform.isIdentity()) {
    return point;
  }
  // x' = l00 x + l01 y + ox; the terms of a zero coefficient are left out.
  auto row = [&](int r, double offset) {
    Scalar sum = Scalar::of(offset);
    const Scalar* inputs[2] = {&point.x, &point.y};
    for (int c = 0; c < 2; ++c) {
      double coefficient = transform.linear(r, c);
      if (coefficient != 0) {
        sum = arithmetic_.add(sum, arithmetic_.multiply(Scalar::of(coefficient), *inputs[c]));
      }
    }
    return sum;
  };
  Scalar z =
      transform.zScale == 1 ? point.z : arithmetic_.multiply(Scalar::of(transform.zScale), point.z);
  return {row(0, transform.offset.x()), row(1, transform.offset.y()), z};
}

CurvePoint PartLowering::untransformedPointAt(const CurvePiece& piece, std::size_t span,
                                              Scalar local, const CutStmt& cut) {
  const CurveValue& curve = *piece.value;
  Arithmetic& math = arithmetic_;
  switch (curve.kind) {
  case CurveKind::Polar:
  case CurveKind::Param: {
    Bindings bindings = bindings_;
    bindings[curve.parameter] = {TypeKind::Num, {local}};
    auto lower = [&](const Expr* expression) {
      std::optional<Lowered> value = tryLower(*expression, bindings, curve.environment);
      if (!value || value->kind != TypeKind::Num) {
        unsupported(expression->span, "this curve expression");
      }
      return value->values.front();
    };
    if (curve.kind == CurveKind::Polar) {
      Scalar r = lower(curve.radius);
      return {math.multiply(r, math.unary(Opcode::Cos, local)),
              math.multiply(r, math.unary(Opcode::Sin, local)), Scalar::of(0)};
    }
    return {lower(curve.x), lower(curve.y), curve.z ? lower(curve.z) : Scalar::of(0)};
  }
  case CurveKind::Line:
    return linePointAt({curve.from[0], curve.from[1], curve.from[2]},
                       {curve.to[0], curve.to[1], curve.to[2]}, piece.geometry->domain().t1, local);
  case CurveKind::Arc: {
    const auto& arc = static_cast<const geom::ArcCurve&>(*piece.geometry);
    return arcPointAt({{curve.center[0], curve.center[1]},
                       curve.arcRadius,
                       curve.startAngle,
                       arc.sweep() / arc.length(),
                       curve.startZ,
                       curve.endZ == curve.startZ ? 0 : (curve.endZ - curve.startZ) / arc.length()},
                      local);
  }
  case CurveKind::Nurbs:
    return spanPointAt(cleanedSpan(piece.spans[span]), local);
  default:
    unsupported(cut.curve->span, fmt::format("a '{}' curve", curve.constructor));
  }
}

// from + (to - from) s at s = local / length, a coordinate that does not
// change a number.
CurvePoint PartLowering::linePointAt(const Eigen::Vector3d& from, const Eigen::Vector3d& to,
                                     double length, Scalar local) {
  Scalar s = arithmetic_.binary(Opcode::Div, local, Scalar::of(length));
  Scalar coordinates[3];
  for (int i = 0; i < 3; ++i) {
    double change = to[i] - from[i];
    coordinates[i] = change == 0 ? Scalar::of(from[i])
                                 : arithmetic_.add(Scalar::of(from[i]),
                                                   arithmetic_.multiply(Scalar::of(change), s));
  }
  return {coordinates[0], coordinates[1], coordinates[2]};
}

// centre + r (cos a, sin a) at a = start + turn local; a helix climbs in
// proportion to the angle, so to the parameter too.
CurvePoint PartLowering::arcPointAt(const ArcNumbers& arc, Scalar local) {
  Arithmetic& math = arithmetic_;
  Scalar angle =
      math.add(Scalar::of(arc.startAngle), math.multiply(Scalar::of(arc.turnPerLength), local));
  Scalar r = Scalar::of(arc.radius);
  Scalar z =
      arc.climbPerLength == 0
          ? Scalar::of(arc.startZ)
          : math.add(Scalar::of(arc.startZ), math.multiply(Scalar::of(arc.climbPerLength), local));
  return {math.add(Scalar::of(arc.centre.x()), math.multiply(r, math.unary(Opcode::Cos, angle))),
          math.add(Scalar::of(arc.centre.y()), math.multiply(r, math.unary(Opcode::Sin, angle))),
          z};
}

namespace {

// How far the controller's reading of a span's power-basis coefficients,
// each rounded to `digits` significant digits (half a unit in the last:
// relative 5 10^-digits), can move its points, sampled over the span: the
// rounding of the numerator's terms plus the weight's, divided by the
// weight. Coefficients far larger than the point (a weight of 1e9) cancel,
// and their rounding does not.
double literalRoundingError(const geom::PolynomialSpan& span, int digits) {
  double relative = 5 * std::pow(10.0, -digits);
  constexpr int samples = 64;
  double largest = 0;
  for (int k = 0; k <= samples; ++k) {
    double u = static_cast<double>(k) / samples;
    geom::HomogeneousPoint value = span.homogeneousAt(u);
    geom::HomogeneousPoint magnitude = geom::HomogeneousPoint::Zero();
    double power = 1;
    for (const geom::HomogeneousPoint& coefficient : span.coefficients) {
      magnitude += coefficient.cwiseAbs() * power;
      power *= u;
    }
    double weight = std::abs(value.w());
    double squared = 0;
    for (int c = 0; c < 3; ++c) {
      double coordinate = value[c] / value.w();
      double error = relative * (magnitude[c] + std::abs(coordinate) * magnitude.w()) / weight;
      squared += error * error;
    }
    largest = std::max(largest, std::sqrt(squared));
  }
  return largest;
}

} // namespace

bool PartLowering::spanLiteralsFit(const geom::PolynomialSpan& span, const CutStmt& cut,
                                   double stretch) {
  if (options_.literalSignificantDigits <= 0) {
    return true;
  }
  double tolerance = chordTolerance(cut).value_or(defaultTolerance);
  return stretch * literalRoundingError(span, options_.literalSignificantDigits) <= tolerance / 4;
}

CurvePoint PartLowering::spanPointAt(const geom::PolynomialSpan& span, Scalar u) {
  auto horner = [&](int coordinate) {
    auto degree = static_cast<std::size_t>(span.degree());
    while (degree > 0 && span.coefficients[degree][coordinate] == 0) {
      --degree;
    }
    // A negative leading coefficient: c0 - (((-c3) u - c2) u - c1) u, the
    // same operations without a negated literal to start the expression.
    double constantTerm = span.coefficients[0][coordinate];
    if (degree > 0 && span.coefficients[degree][coordinate] < 0 && constantTerm != 0) {
      Scalar inner = Scalar::of(-span.coefficients[degree][coordinate]);
      for (std::size_t k = degree; k-- > 1;) {
        inner = arithmetic_.add(arithmetic_.multiply(inner, u),
                                Scalar::of(-span.coefficients[k][coordinate]));
      }
      return arithmetic_.binary(Opcode::Sub, Scalar::of(constantTerm),
                                arithmetic_.multiply(inner, u));
    }
    Scalar sum = Scalar::of(span.coefficients[degree][coordinate]);
    for (std::size_t k = degree; k-- > 0;) {
      Scalar coefficient = Scalar::of(span.coefficients[k][coordinate]);
      // Leading zeros (a planar curve's z) need no multiplication: u is finite.
      bool zero = sum.isConstant() && sum.constant == 0;
      sum = zero ? coefficient : arithmetic_.add(arithmetic_.multiply(sum, u), coefficient);
    }
    return sum;
  };
  CurvePoint point{horner(0), horner(1), horner(2)};
  if (span.isRational()) {
    Scalar w = horner(3);
    for (Scalar* coordinate : {&point.x, &point.y, &point.z}) {
      if (!(coordinate->isConstant() && coordinate->constant == 0)) {
        *coordinate = arithmetic_.binary(Opcode::Div, *coordinate, w);
      }
    }
  }
  return point;
}

geom::PolynomialSpan cleanedSpan(geom::PolynomialSpan span) {
  bool constantWeight = true;
  for (std::size_t k = 1; k < span.coefficients.size(); ++k) {
    constantWeight = constantWeight && std::abs(span.coefficients[k].w()) <=
                                           1e-12 * std::abs(span.coefficients[0].w());
  }
  if (constantWeight && span.coefficients[0].w() != 0) {
    double weight = span.coefficients[0].w();
    for (geom::HomogeneousPoint& coefficient : span.coefficients) {
      coefficient /= weight;
      coefficient.w() = 0;
    }
    span.coefficients[0].w() = 1;
  }
  return span;
}

} // namespace cncc::ir::lowering
