// A cut's curve as the controller computes it. The compile-time curve
// value (curves.cpp) has every number evaluated at the part's defaults;
// here the curve expression is walked again, the way the value was built,
// so that what depends on a part parameter or a controller loop's variable
// stays an IR value: the arguments of the fns that make a piece, the
// piece's range, and the offsets, angles and factors of the transforms
// around it.
#include "part_lowering.h"

#include <cmath>

namespace cncc::ir::lowering {

using namespace frontend;

namespace {

// Deeper nesting of fns and transforms than this is left to the tables.
constexpr int maximumWalkDepth = 64;

bool isLeafCurve(std::string_view callee) {
  return callee == "polar" || callee == "param" || callee == "line" || callee == "arc" ||
         callee == "nurbs" || callee == "bspline" || callee == "bezier";
}

} // namespace

bool RuntimeTransform::isConstant() const {
  bool constant = zScale.isConstant() && norm.isConstant();
  for (const Scalar& entry : linear) {
    constant = constant && entry.isConstant();
  }
  for (const Scalar& entry : offset) {
    constant = constant && entry.isConstant();
  }
  return constant;
}

Scalar PartLowering::times(Scalar left, Scalar right) {
  bool zero =
      (left.isConstant() && left.constant == 0) || (right.isConstant() && right.constant == 0);
  return zero ? Scalar::of(0) : arithmetic_.multiply(left, right);
}

Scalar PartLowering::magnitude(Scalar value) {
  return value.isConstant() ? Scalar::of(std::abs(value.constant))
                            : arithmetic_.unary(Opcode::Abs, value);
}

std::optional<Scalar> PartLowering::symbolicNumber(const Expr* expression, const Bindings& bindings,
                                                   const Environment& environment) {
  if (expression == nullptr) {
    return std::nullopt;
  }
  std::optional<Lowered> lowered = tryLower(*expression, bindings, environment);
  if (!lowered || lowered->kind != TypeKind::Num) {
    return std::nullopt;
  }
  return lowered->values.front();
}

RuntimeTransform PartLowering::composed(const RuntimeTransform& outer,
                                        const RuntimeTransform& inner) {
  RuntimeTransform result;
  const auto& a = outer.linear;
  const auto& b = inner.linear;
  for (int row = 0; row < 2; ++row) {
    for (int column = 0; column < 2; ++column) {
      result.linear[2 * row + column] =
          arithmetic_.add(times(a[2 * row], b[column]), times(a[2 * row + 1], b[2 + column]));
    }
    result.offset[row] = arithmetic_.add(
        arithmetic_.add(times(a[2 * row], inner.offset[0]), times(a[2 * row + 1], inner.offset[1])),
        outer.offset[row]);
  }
  result.zScale = times(outer.zScale, inner.zScale);
  result.norm = times(outer.norm, inner.norm);
  return result;
}

CurvePoint PartLowering::applied(const RuntimeTransform& transform, const CurvePoint& point) {
  const auto& l = transform.linear;
  auto row = [&](int r) {
    return arithmetic_.add(arithmetic_.add(times(l[2 * r], point.x), times(l[2 * r + 1], point.y)),
                           transform.offset[r]);
  };
  return {row(0), row(1), times(transform.zScale, point.z)};
}

std::optional<RuntimeTransform> PartLowering::ownTransform(const CallExpr& call,
                                                           const Bindings& bindings,
                                                           const Environment& environment) {
  RuntimeTransform own;
  if (call.callee == "translate") {
    std::optional<Scalar> dx = symbolicNumber(builtinArgument(call, "dx"), bindings, environment);
    std::optional<Scalar> dy = symbolicNumber(builtinArgument(call, "dy"), bindings, environment);
    if (!dx || !dy) {
      return std::nullopt;
    }
    own.offset = {*dx, *dy};
  } else if (call.callee == "rotate") {
    std::optional<Scalar> angle =
        symbolicNumber(builtinArgument(call, "angle"), bindings, environment);
    if (!angle) {
      return std::nullopt;
    }
    Scalar cosine = angle->isConstant() ? Scalar::of(std::cos(angle->constant))
                                        : arithmetic_.unary(Opcode::Cos, *angle);
    Scalar sine = angle->isConstant() ? Scalar::of(std::sin(angle->constant))
                                      : arithmetic_.unary(Opcode::Sin, *angle);
    own.linear = {cosine, arithmetic_.unary(Opcode::Neg, sine), sine, cosine};
  } else {
    std::optional<Scalar> factor =
        symbolicNumber(builtinArgument(call, "factor"), bindings, environment);
    if (!factor) {
      return std::nullopt;
    }
    own.linear = {*factor, Scalar::of(0), Scalar::of(0), *factor};
    own.zScale = *factor;
    own.norm = magnitude(*factor);
  }
  return own;
}

std::optional<std::vector<SymbolicPiece>> PartLowering::symbolicPieces(const Expr& curve) {
  std::vector<SymbolicPiece> pieces;
  if (!collectSymbolicPieces(curve, bindings_, environment_, RuntimeTransform{}, pieces, 0)) {
    return std::nullopt;
  }
  return pieces;
}

bool PartLowering::collectSymbolicPieces(const Expr& curve, const Bindings& bindings,
                                         const Environment& environment,
                                         const RuntimeTransform& outer,
                                         std::vector<SymbolicPiece>& pieces, int depth) {
  if (depth > maximumWalkDepth) {
    return false;
  }
  if (curve.kind == ExprKind::Name) {
    auto found = letValues_.find(as<NameExpr>(curve).declaration);
    return found != letValues_.end() &&
           collectSymbolicPieces(*found->second, bindings, environment, outer, pieces, depth + 1);
  }
  if (curve.kind != ExprKind::Call) {
    return false;
  }
  const auto& call = as<CallExpr>(curve);
  const Declaration* declaration = call.declaration;
  if (declaration == nullptr) {
    return false;
  }
  if (declaration->kind == DeclarationKind::Function) {
    // A user fn: its body, with the parameters bound to the arguments.
    const FnItem* function = declaration->function;
    if (function == nullptr || !function->body ||
        function->parameters.size() != call.arguments.size()) {
      return false;
    }
    Bindings inner = bindings;
    Environment innerEnvironment = environment;
    for (std::size_t i = 0; i < call.arguments.size(); ++i) {
      const Argument& argument = call.arguments[i];
      const Declaration* parameter = function->parameters[i].declaration;
      if (!argument.name.empty() || parameter == nullptr) {
        return false;
      }
      Value value = evaluate(*argument.value, environment);
      if (value.isError() || value.type.kind == TypeKind::Curve) {
        return false; // a curve handed to a fn is left to the tables
      }
      innerEnvironment[parameter] = value;
      if (dependsOn(*argument.value, bindings)) {
        std::optional<Lowered> lowered = tryLower(*argument.value, bindings, environment);
        if (!lowered) {
          return false;
        }
        inner[parameter] = *lowered;
      } else {
        inner.erase(parameter);
      }
    }
    return collectSymbolicPieces(*function->body, inner, innerEnvironment, outer, pieces,
                                 depth + 1);
  }
  if (declaration->kind != DeclarationKind::Builtin) {
    return false;
  }
  if (call.callee == "path") {
    for (const Argument& argument : call.arguments) {
      if (!argument.value || !collectSymbolicPieces(*argument.value, bindings, environment, outer,
                                                    pieces, depth + 1)) {
        return false;
      }
    }
    return true;
  }
  if (call.callee == "translate" || call.callee == "rotate" || call.callee == "scale") {
    const Expr* inner = builtinArgument(call, "curve");
    std::optional<RuntimeTransform> own = ownTransform(call, bindings, environment);
    return inner != nullptr && own &&
           collectSymbolicPieces(*inner, bindings, environment, composed(outer, *own), pieces,
                                 depth + 1);
  }
  if (!isLeafCurve(call.callee)) {
    return false;
  }
  SymbolicPiece piece{&call, bindings, environment, outer, false, false};
  // Bound to IR values, or read through names the lowering keeps no IR
  // value for (a list of points computed from parameters).
  for (const Argument& argument : call.arguments) {
    piece.shapeDependent =
        piece.shapeDependent || (argument.value && (dependsOn(*argument.value, bindings) ||
                                                    !parametersOf(*argument.value).empty()));
  }
  piece.dependent = piece.shapeDependent || !outer.isConstant();
  pieces.push_back(std::move(piece));
  return true;
}

std::pair<Scalar, Scalar> PartLowering::symbolicRange(const SymbolicPiece& piece) {
  const Expr* range = builtinArgument(*piece.call, "t");
  if (range == nullptr || range->kind != ExprKind::Range) {
    return {Scalar::of(0), Scalar::of(1)};
  }
  return symbolicBounds(*range, piece, "this curve's range");
}

std::pair<Scalar, Scalar>
PartLowering::symbolicBounds(const Expr& range, const SymbolicPiece& piece, std::string_view what) {
  const auto& bounds = as<RangeExpr>(range);
  std::optional<Scalar> low = symbolicNumber(bounds.low.get(), piece.bindings, piece.environment);
  std::optional<Scalar> high = symbolicNumber(bounds.high.get(), piece.bindings, piece.environment);
  if (!low || !high) {
    unsupported(range.span, what);
  }
  return {*low, *high};
}

std::pair<Scalar, Scalar> PartLowering::symbolicHeights(const SymbolicPiece& piece,
                                                        const CurveValue& value) {
  const Expr* heights = builtinArgument(*piece.call, "z");
  if (heights == nullptr || !dependsOn(*heights, piece.bindings)) {
    return {Scalar::of(value.startZ), Scalar::of(value.endZ)};
  }
  if (heights->kind != ExprKind::Range) {
    unsupported(heights->span, "a helix's heights on the controller unless written 'z = a .. b'");
  }
  return symbolicBounds(*heights, piece, "this helix's heights");
}

// A point argument of the piece's call (x, y, z).
std::vector<Scalar> PartLowering::symbolicPoint(const SymbolicPiece& piece, std::string_view name) {
  const Expr* expression = builtinArgument(*piece.call, name);
  std::optional<Lowered> lowered =
      expression ? tryLower(*expression, piece.bindings, piece.environment) : std::nullopt;
  if (!lowered || lowered->kind != TypeKind::Point) {
    unsupported(piece.call->span, "this curve's points");
  }
  std::vector<Scalar> coordinates = lowered->values;
  coordinates.resize(3, Scalar::of(0));
  return coordinates;
}

// A symbolic line at t as from (1 - t) + to t: cut in one step (at t = 1)
// this is `to` once a controller's finite numbers fold x * 0 and 0 + x
// (fold-finite), as the line's own end is; from + (to - from) t would not
// fold.
CurvePoint PartLowering::symbolicLineRegionPoint(const SymbolicPiece& piece, Scalar local) {
  std::vector<Scalar> from = symbolicPoint(piece, "from");
  std::vector<Scalar> to = symbolicPoint(piece, "to");
  return applied(piece.transform,
                 pointBetween({from[0], from[1], from[2]}, {to[0], to[1], to[2]}, local));
}

// from (1 - fraction) + to fraction, a coordinate the two share as it is.
CurvePoint PartLowering::pointBetween(const CurvePoint& from, const CurvePoint& to,
                                      Scalar fraction) {
  Scalar rest = arithmetic_.binary(Opcode::Sub, Scalar::of(1), fraction);
  auto between = [&](const Scalar& a, const Scalar& b) {
    if (a.sameAs(b)) {
      return a;
    }
    Scalar towards = times(b, fraction);
    return arithmetic_.add(times(a, rest), towards);
  };
  return {between(from.x, to.x), between(from.y, to.y), between(from.z, to.z)};
}

CurvePoint PartLowering::symbolicPointAt(const SymbolicPiece& piece, const CurveValue& value,
                                         Scalar local) {
  Arithmetic& math = arithmetic_;
  auto number = [&](const Expr* expression, const Bindings& bindings) {
    std::optional<Scalar> result = symbolicNumber(expression, bindings, piece.environment);
    if (!result) {
      unsupported(expression != nullptr ? expression->span : piece.call->span,
                  "this curve expression");
    }
    return *result;
  };
  auto point = [&](std::string_view name) { return symbolicPoint(piece, name); };
  CurvePoint result;
  if (value.kind == CurveKind::Polar || value.kind == CurveKind::Param) {
    Bindings bindings = piece.bindings;
    bindings[value.parameter] = {TypeKind::Num, {local}};
    if (value.kind == CurveKind::Polar) {
      Scalar r = number(value.radius, bindings);
      result = {times(r, math.unary(Opcode::Cos, local)), times(r, math.unary(Opcode::Sin, local)),
                Scalar::of(0)};
    } else {
      result = {number(value.x, bindings), number(value.y, bindings),
                value.z ? number(value.z, bindings) : Scalar::of(0)};
    }
  } else if (value.kind == CurveKind::Line) {
    std::vector<Scalar> from = point("from");
    std::vector<Scalar> to = point("to");
    Scalar coordinates[3];
    for (int c = 0; c < 3; ++c) {
      bool same = from[c].sameAs(to[c]);
      bool atEnd = local.isConstant() && local.constant == 1;
      coordinates[c] =
          same || (local.isConstant() && local.constant == 0) ? from[c]
          : atEnd                                             ? to[c]
                  : math.add(from[c], times(math.binary(Opcode::Sub, to[c], from[c]), local));
    }
    result = {coordinates[0], coordinates[1], coordinates[2]};
  } else if (value.kind == CurveKind::Arc) {
    std::vector<Scalar> center = point("center");
    Scalar radius = number(builtinArgument(*piece.call, "radius"), piece.bindings);
    Scalar start = number(builtinArgument(*piece.call, "from"), piece.bindings);
    Scalar end = number(builtinArgument(*piece.call, "to"), piece.bindings);
    Scalar angle = math.add(start, times(math.binary(Opcode::Sub, end, start), local));
    auto [startZ, endZ] = symbolicHeights(piece, value);
    Scalar z = startZ;
    if (!endZ.sameAs(startZ)) {
      z = math.add(startZ, times(math.binary(Opcode::Sub, endZ, startZ), local));
    }
    result = {math.add(center[0], times(radius, math.unary(Opcode::Cos, angle))),
              math.add(center[1], times(radius, math.unary(Opcode::Sin, angle))), z};
  } else {
    unsupported(piece.call->span, "this curve on the controller");
  }
  return applied(piece.transform, result);
}

} // namespace cncc::ir::lowering
