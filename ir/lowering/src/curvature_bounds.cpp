// Step counts the controller computes for a piece whose geometry depends
// on values it knows only when it runs (part parameters, its own loop
// variables). A chord over a parameter step h deviates from a C2 curve by
// at most h^2 M / 8, M >= |C''| over the chord, so N = |t1 - t0| sqrt(M /
// (8 budget)) uniform steps, rounded up, keep every chord within the
// budget. M is derived here as controller arithmetic:
// - a line needs one step; an arc of radius r turning by a (over s in
//   [0, 1]) has |C''| = |r| a^2;
// - a polar r(t) affine in t has the tight bound of polarStepCount;
// - any other polar or param curve gets bounds of |f|, |f'| and |f''| for
//   every IR value f of its coordinates, propagated through sums,
//   products, quotients, whole constant powers, sqrt, exp, sin and cos
//   (the rules of differentiation with each term bounded by its size). A
//   quotient by a value of t and a root need a number its size stays above
//   (1 + 0.5 cos t stays above 0.5: a polar conic r = p / (1 + e cos t)
//   with e a number); without one, and for other functions of t, a piece
//   is not bounded and keeps the compile-time tables.
// A transform multiplies M by its stretch.
#include "forward_derivative.h"
#include "part_lowering.h"

#include <cmath>
#include <functional>
#include <limits>
#include <map>

namespace cncc::ir::lowering {

using namespace frontend;

namespace {

// Added before rounding: round(x + 0.5) >= ceil(x), and >= 1 for x >= 0.
constexpr double roundUpOffset = 0.5;

// Bounds over the piece's range of |f|, |f'| and |f''| for one value f,
// and a number |f| stays above (0: none known).
struct DerivativeBounds {
  Scalar value, slope, curvature;
  double floor = 0;
};

// |a + b| and |a - b| stay above |a| - |b|, where |b|'s bound is a number.
double floorOfSum(const DerivativeBounds& a, const DerivativeBounds& b) {
  double above = 0;
  if (b.value.isConstant()) {
    above = std::max(above, a.floor - b.value.constant);
  }
  if (a.value.isConstant()) {
    above = std::max(above, b.floor - a.value.constant);
  }
  return above;
}

bool isZero(const Scalar& scalar) {
  return scalar.isConstant() && scalar.constant == 0;
}

} // namespace

Scalar PartLowering::roundedUpSteps(Scalar steps) {
  return arithmetic_.unary(Opcode::Round, arithmetic_.add(steps, Scalar::of(roundUpOffset)));
}

std::optional<Scalar> PartLowering::symbolicStepCount(const SymbolicPiece& piece,
                                                      const CurveValue& value, double budget) {
  Arithmetic& math = arithmetic_;
  Scalar length;
  Scalar bound;
  if (value.kind == CurveKind::Line) {
    return Scalar::of(1);
  }
  if (value.kind == CurveKind::Arc) {
    auto argument = [&](std::string_view name) {
      return symbolicNumber(builtinArgument(*piece.call, name), piece.bindings, piece.environment);
    };
    std::optional<Scalar> radius = argument("radius");
    std::optional<Scalar> start = argument("from");
    std::optional<Scalar> end = argument("to");
    if (!radius || !start || !end) {
      return std::nullopt;
    }
    length = magnitude(math.binary(Opcode::Sub, *end, *start));
    bound = times(magnitude(*radius), piece.transform.norm);
  } else if (value.kind == CurveKind::Polar || value.kind == CurveKind::Param) {
    if (std::optional<Scalar> polar =
            value.kind == CurveKind::Polar ? polarStepCount(piece, value, budget) : std::nullopt) {
      return polar;
    }
    std::optional<Scalar> curvature = analyticCurvatureBound(piece, value);
    if (!curvature) {
      return std::nullopt;
    }
    auto [low, high] = symbolicRange(piece);
    length = magnitude(math.binary(Opcode::Sub, high, low));
    bound = times(*curvature, piece.transform.norm);
  } else {
    return std::nullopt;
  }
  // The arc's sweep appears squared in M: N = sweep sqrt(|r| / (8 budget)).
  Scalar steps =
      times(length, math.unary(Opcode::Sqrt, math.multiply(bound, Scalar::of(1 / (8 * budget)))));
  return roundedUpSteps(steps);
}

std::optional<Scalar> PartLowering::analyticCurvatureBound(const SymbolicPiece& piece,
                                                           const CurveValue& value) {
  Arithmetic& math = arithmetic_;
  ValueId probe = builder_.constant(std::numeric_limits<double>::quiet_NaN());
  SymbolicPiece untransformed = piece;
  untransformed.transform = RuntimeTransform{};
  CurvePoint point = symbolicPointAt(untransformed, value, Scalar::of(probe, ValueType::F64));
  auto [low, high] = symbolicRange(piece);
  // |t| over the range: the larger of |t0| and |t1| (|t| is convex).
  Scalar reach = isZero(low)    ? magnitude(high)
                 : isZero(high) ? magnitude(low)
                                : math.larger(magnitude(low), magnitude(high));

  ValueDependence varies(builder_.function(), probe);

  // g^n for a whole constant n >= 0 that expand-whole-powers writes out
  // (the controller's EXP[LN[g]*n] stops for g <= 0): (g^n)' = n g^(n-1) g',
  // (g^n)'' = n (n-1) g^(n-2) g'^2 + n g^(n-1) g''.
  auto wholePowerBounds = [&](const DerivativeBounds& g,
                              ValueId exponent) -> std::optional<DerivativeBounds> {
    const Instruction& definition = builder_.function().definition(exponent);
    double n = definition.opcode == Opcode::Const ? definition.number : -1;
    if (!(n >= 0 && n <= largestExpandedExponent && std::trunc(n) == n)) {
      return std::nullopt;
    }
    auto power = [&](double k) {
      return k == 0   ? Scalar::of(1)
             : k == 1 ? g.value
                      : math.binary(Opcode::Pow, g.value, Scalar::of(k));
    };
    if (n == 0) {
      return DerivativeBounds{Scalar::of(1), Scalar::of(0), Scalar::of(0)};
    }
    Scalar below = power(n - 1);
    Scalar slope = times(Scalar::of(n), times(below, g.slope));
    Scalar bent = times(Scalar::of(n), times(below, g.curvature));
    if (n >= 2) {
      Scalar turned = times(Scalar::of(n * (n - 1)), times(power(n - 2), times(g.slope, g.slope)));
      bent = math.add(turned, bent);
    }
    return DerivativeBounds{power(n), slope, bent, std::pow(g.floor, n)};
  };

  // (ab)' = a'b + ab', (ab)'' = a''b + 2a'b' + ab''.
  auto productBounds = [&](const DerivativeBounds& a, const DerivativeBounds& b) {
    return DerivativeBounds{times(a.value, b.value),
                            math.add(times(a.slope, b.value), times(a.value, b.slope)),
                            math.add(math.add(times(a.curvature, b.value),
                                              times(Scalar::of(2), times(a.slope, b.slope))),
                                     times(a.value, b.curvature)),
                            a.floor * b.floor};
  };
  // 1/g where |g| >= L > 0: (1/g)' = -g'/g^2, (1/g)'' = 2g'^2/g^3 - g''/g^2.
  auto reciprocalBounds = [&](const DerivativeBounds& g) -> std::optional<DerivativeBounds> {
    double low = g.floor;
    if (!(low > 0)) {
      return std::nullopt; // g may vanish: no bound
    }
    Scalar slope = times(g.slope, Scalar::of(1 / (low * low)));
    Scalar bent = math.add(times(g.curvature, Scalar::of(1 / (low * low))),
                           times(times(g.slope, g.slope), Scalar::of(2 / (low * low * low))));
    double above = g.value.isConstant() && g.value.constant > 0 ? 1 / g.value.constant : 0;
    return DerivativeBounds{Scalar::of(1 / low), slope, bent, above};
  };
  // sqrt(g) where g >= L > 0: (sqrt g)' = g'/(2 sqrt g),
  // (sqrt g)'' = g''/(2 sqrt g) - g'^2/(4 g sqrt g).
  auto rootBounds = [&](const DerivativeBounds& g) -> std::optional<DerivativeBounds> {
    double low = g.floor;
    if (!(low > 0)) {
      return std::nullopt; // the root's slope has no bound near 0
    }
    double root = std::sqrt(low);
    Scalar slope = times(g.slope, Scalar::of(1 / (2 * root)));
    Scalar bent = math.add(times(g.curvature, Scalar::of(1 / (2 * root))),
                           times(times(g.slope, g.slope), Scalar::of(1 / (4 * low * root))));
    return DerivativeBounds{math.unary(Opcode::Sqrt, g.value), slope, bent, root};
  };

  std::map<std::uint32_t, std::optional<DerivativeBounds>> memo;
  std::function<std::optional<DerivativeBounds>(Scalar)> bounds =
      [&](Scalar scalar) -> std::optional<DerivativeBounds> {
    // A const instruction as its number (the probe t is one too: not it).
    if (!scalar.isConstant() && scalar.value != probe &&
        builder_.function().definition(scalar.value).opcode == Opcode::Const) {
      scalar = Scalar::of(builder_.function().definition(scalar.value).number);
    }
    if (scalar.isConstant() || !varies(scalar.value)) {
      return DerivativeBounds{magnitude(scalar), Scalar::of(0), Scalar::of(0),
                              scalar.isConstant() ? std::abs(scalar.constant) : 0};
    }
    if (scalar.value == probe) {
      return DerivativeBounds{reach, Scalar::of(1), Scalar::of(0)};
    }
    if (auto found = memo.find(scalar.value.index); found != memo.end()) {
      return found->second;
    }
    // A copy, without regions: the arithmetic below appends instructions.
    Instruction instruction = withoutRegions(builder_.function().definition(scalar.value));
    std::vector<DerivativeBounds> operands;
    for (ValueId operand : instruction.operands) {
      std::optional<DerivativeBounds> own = bounds(Scalar::of(operand, ValueType::F64));
      if (!own) {
        return memo[scalar.value.index] = std::nullopt;
      }
      operands.push_back(*own);
    }
    std::optional<DerivativeBounds> result;
    switch (instruction.opcode) {
    case Opcode::Add:
    case Opcode::Sub:
      result = {math.add(operands[0].value, operands[1].value),
                math.add(operands[0].slope, operands[1].slope),
                math.add(operands[0].curvature, operands[1].curvature),
                floorOfSum(operands[0], operands[1])};
      break;
    case Opcode::Neg:
      result = operands[0];
      break;
    case Opcode::Mul:
      result = productBounds(operands[0], operands[1]);
      break;
    case Opcode::Div:
      if (!varies(instruction.operands[1])) {
        Scalar divisor = magnitude(Scalar::of(instruction.operands[1], ValueType::F64));
        auto divided = [&](Scalar bound) {
          return isZero(bound) ? bound : math.binary(Opcode::Div, bound, divisor);
        };
        result = {
            divided(operands[0].value), divided(operands[0].slope), divided(operands[0].curvature),
            divisor.isConstant() && divisor.constant > 0 ? operands[0].floor / divisor.constant
                                                         : 0};
      } else if (std::optional<DerivativeBounds> inverse = reciprocalBounds(operands[1])) {
        result = productBounds(operands[0], *inverse);
      }
      break;
    case Opcode::Sqrt:
      result = rootBounds(operands[0]);
      break;
    case Opcode::Pow:
      result = wholePowerBounds(operands[0], instruction.operands[1]);
      break;
    case Opcode::Exp: {
      // (e^g)' = e^g g', (e^g)'' = e^g (g'' + g'^2), and e^g <= e^|g|.
      const DerivativeBounds& g = operands[0];
      Scalar size = math.unary(Opcode::Exp, g.value);
      result = {size, times(size, g.slope),
                times(size, math.add(g.curvature, times(g.slope, g.slope)))};
      break;
    }
    case Opcode::Sin:
    case Opcode::Cos: {
      // (sin g)'' = cos(g) g'' - sin(g) g'^2.
      const DerivativeBounds& g = operands[0];
      result = {Scalar::of(1), g.slope, math.add(g.curvature, times(g.slope, g.slope))};
      break;
    }
    default:
      break;
    }
    return memo[scalar.value.index] = result;
  };
  Scalar sum = Scalar::of(0);
  for (const Scalar& coordinate : {point.x, point.y, point.z}) {
    std::optional<DerivativeBounds> own = bounds(coordinate);
    if (!own) {
      return std::nullopt;
    }
    sum = math.add(sum, times(own->curvature, own->curvature));
  }
  return sum.isConstant() ? Scalar::of(std::sqrt(sum.constant)) : math.unary(Opcode::Sqrt, sum);
}

// A polar curve r(t) whose r is affine in t with parameter-dependent
// coefficients (the Archimedean spiral r = a + b t). For C = r (cos t,
// sin t): C'' = (r'' - r)(cos t, sin t) + 2 r' (-sin t, cos t), so
// |C''|^2 = (r'' - r)^2 + 4 r'^2 = r^2 + 4 r'^2 when r'' = 0. |r| is convex
// and r' constant, so over [t0, t1]
//   |C''|^2 <= max(r(t0)^2, r(t1)^2) + 4 r'^2 <= r(t0)^2 + r(t1)^2 + 4 r'^2,
// the bound the controller computes (the sum instead of the larger term
// saves a comparison and costs at most a factor sqrt(2) in |C''|). An r
// that is not affine in t gives nullopt.
std::optional<Scalar> PartLowering::polarStepCount(const SymbolicPiece& piece,
                                                   const CurveValue& curve, double budget) {
  ValueId probe = builder_.constant(std::numeric_limits<double>::quiet_NaN());
  auto lowerAt = [&](Scalar t) {
    Bindings bindings = piece.bindings;
    bindings[curve.parameter] = {TypeKind::Num, {t}};
    std::optional<Scalar> value = symbolicNumber(curve.radius, bindings, piece.environment);
    if (!value) {
      unsupported(curve.radius->span, "this curve expression");
    }
    return *value;
  };
  Scalar radius = lowerAt(Scalar::of(probe, ValueType::F64));
  // d r / d t over the IR; nullopt when r is not affine in t (its slope
  // varies with t).
  std::optional<Scalar> slope = ForwardDerivative(builder_, arithmetic_, probe).of(radius);
  if (!slope ||
      (!slope->isConstant() && ValueDependence(builder_.function(), probe)(slope->value))) {
    return std::nullopt;
  }
  auto [low, high] = symbolicRange(piece);
  Scalar r0 = lowerAt(low);
  Scalar r1 = lowerAt(high);
  auto square = [&](Scalar value) { return arithmetic_.multiply(value, value); };
  Scalar slopeTerm = arithmetic_.multiply(Scalar::of(4), square(*slope));
  Scalar r1Squared = square(r1);
  Scalar sum = arithmetic_.add(arithmetic_.add(square(r0), r1Squared), slopeTerm);
  Scalar bound = times(piece.transform.norm, arithmetic_.unary(Opcode::Sqrt, sum));
  // N >= (t1 - t0) sqrt(M / (8 budget)).
  Scalar length = magnitude(arithmetic_.binary(Opcode::Sub, high, low));
  Scalar steps =
      times(length, arithmetic_.unary(Opcode::Sqrt,
                                      arithmetic_.multiply(bound, Scalar::of(1 / (8 * budget)))));
  return roundedUpSteps(steps);
}

} // namespace cncc::ir::lowering
