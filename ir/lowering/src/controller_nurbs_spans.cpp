// NURBS spans on the controller (controller_cuts.cpp plans them): a span
// moved by a transform of controller values, and a span whose control
// points depend on parameters, split into literals and the dependent
// points' share, with the bound of |C''| its step count comes from.
#include "controller_segment.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace cncc::ir::lowering {

using namespace frontend;

// The control points and weights of a NURBS piece as the controller
// computes them; nullopt when what depends on parameters is not written out
// as lists (or is the degree or the knots, which shape the spans).
std::optional<PartLowering::NurbsLists> PartLowering::nurbsLists(const SymbolicPiece& piece) {
  NurbsLists result;
  const Expr* points = builtinArgument(*piece.call, "points");
  const Expr* weights = builtinArgument(*piece.call, "weights");
  for (const Argument& argument : piece.call->arguments) {
    if (argument.value && dependsOn(*argument.value, piece.bindings) &&
        argument.value.get() != points && argument.value.get() != weights) {
      return std::nullopt;
    }
  }
  for (auto [expression, list] :
       {std::pair{points, &result.points}, std::pair{weights, &result.weights}}) {
    if (expression == nullptr) {
      continue;
    }
    *list = symbolicList(*expression, piece.bindings, piece.environment);
    if (!*list && dependsOn(*expression, piece.bindings)) {
      return std::nullopt;
    }
  }
  return result;
}

CurvePoint PartLowering::movedSplitSpanPoint(const ControllerSegment& segment, Scalar u) {
  CurvePoint point = splitSpanPoint(segment, u);
  return segment.moved != nullptr ? applied(*segment.moved, point) : point;
}

CurvePoint PartLowering::nurbsSegmentPoint(const CutCurve& curve, const ControllerSegment& segment,
                                           Scalar u, const CutStmt& cut) {
  if (segment.moved == nullptr) {
    return pointAt(curve, segment.piece, segment.span, u, cut);
  }
  return applied(*segment.moved,
                 untransformedPointAt(curve.pieces[segment.piece], segment.span, u, cut));
}

Scalar PartLowering::hornerOf(const std::vector<double>& polynomial, Scalar u) {
  Scalar sum = Scalar::of(0);
  for (std::size_t k = polynomial.size(); k-- > 0;) {
    bool zero = sum.isConstant() && sum.constant == 0;
    sum = zero ? Scalar::of(polynomial[k])
               : arithmetic_.add(arithmetic_.multiply(sum, u), Scalar::of(polynomial[k]));
  }
  return sum;
}

// A NURBS span with control points that depend on parameters (planned as
// `split`, see ControllerSegment), and its step count on the controller.
//
// The bound of |C''| in the span's u in [0, 1], for positive weights. Let
// c be a fixed point, P(u) = sum_i w_i (q_i - c) N_i(u) and W(u) = sum_i
// w_i N_i(u), so C - c = P / W. Differentiating W (C - c) = P twice:
//   C' = (P' - W' (C - c)) / W,  C'' = (P'' - W'' (C - c) - 2 W' C') / W.
// With W >= wmin (the smallest weight of the span: the N_i are a partition
// of unity), |C - c| <= R (the curve stays in the hull of its control
// points) and bounds P1 >= |P'|, P2 >= |P''|, W1 >= |W'|, W2 >= |W''|:
//   |C'| <= D1 = (P1 + W1 R) / wmin,  |C''| <= (P2 + W2 R + 2 W1 D1) / wmin.
// Each P_k, W_k is the bound of the constant control points' share (the
// largest Bernstein coefficient of the derivative's polynomial, exact at
// compile time) plus, per dependent control point, |w_i| |q_i - c| (for
// P) or |w_i - w0| (for W: the N_i^(k) sum to zero, so W^(k) = sum (w_i -
// w0) N_i^(k) for the reference weight w0 = 1) times the bound of N_i^(k),
// computed on the controller; R is the
// constant points' largest distance from c (c their centroid) plus the
// dependent points' distances. Without parameter-dependent or unequal
// weights W' = W'' = 0 and the bound is P2 / w.
void PartLowering::planSplitSpan(const CurvePiece& piece, const SymbolicList* weights,
                                 const SymbolicList* points, ControllerSegment& segment,
                                 double budget, Scalar norm) {
  const CurveValue& value = *piece.value;
  std::size_t count = value.points.size();
  if ((weights != nullptr && weights->size() != count) ||
      (points != nullptr && points->size() != count)) {
    return;
  }
  std::vector<std::array<Scalar, 3>> q(count);
  std::vector<Scalar> w(count);
  std::vector<bool> qConstant(count, true), wConstant(count, true);
  for (std::size_t i = 0; i < count; ++i) {
    for (int c = 0; c < 3; ++c) {
      q[i][c] = Scalar::of(value.points[i][c]);
    }
    w[i] = Scalar::of(value.weights.empty() ? 1.0 : value.weights[i]);
    if (points != nullptr && (*points)[i] && (*points)[i]->kind == TypeKind::Point) {
      const std::vector<Scalar>& lowered = (*points)[i]->values;
      for (std::size_t c = 0; c < lowered.size() && c < 3; ++c) {
        if (!lowered[c].isConstant()) {
          q[i][c] = lowered[c];
          qConstant[i] = false;
        }
      }
    }
    if (weights != nullptr && (*weights)[i] && (*weights)[i]->kind == TypeKind::Num &&
        !(*weights)[i]->values.front().isConstant()) {
      w[i] = (*weights)[i]->values.front();
      wConstant[i] = false;
    }
  }
  // The basis functions on this span, ascending powers of u.
  const auto& nurbs = static_cast<const geom::NurbsCurve&>(*piece.geometry);
  std::vector<Polynomial> basis(count);
  std::vector<bool> active(count, false);
  std::vector<std::size_t> dependent;
  for (std::size_t i = 0; i < count; ++i) {
    std::vector<Eigen::Vector3d> unit(count, Eigen::Vector3d::Zero());
    unit[i].x() = 1;
    geom::NurbsCurve function = geom::NurbsCurve::bspline(nurbs.knots(), unit);
    geom::PolynomialSpan span = geom::toPowerBasis(function)[segment.span];
    for (const geom::HomogeneousPoint& coefficient : span.coefficients) {
      basis[i].push_back(coefficient.x());
      active[i] = active[i] || std::abs(coefficient.x()) > 1e-14;
    }
    if (active[i] && !(qConstant[i] && wConstant[i])) {
      dependent.push_back(i);
    }
  }
  if (dependent.empty()) {
    return;
  }
  segment.split = true;
  std::size_t degree = basis.front().size();
  for (Polynomial& coordinate : segment.constantPart) {
    coordinate.assign(degree, 0.0);
  }
  double reference = segment.referenceWeight;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  int constantPoints = 0;
  for (std::size_t i = 0; i < count; ++i) {
    if (active[i] && qConstant[i]) {
      centre += Eigen::Vector3d(q[i][0].constant, q[i][1].constant, q[i][2].constant);
      ++constantPoints;
    }
  }
  if (constantPoints > 0) {
    centre /= constantPoints;
  }
  // Shares of the constant control points: evaluation (Xc, Wc) and bound.
  std::array<Polynomial, 3> translated;
  Polynomial constantWeights(degree, 0.0);
  for (Polynomial& coordinate : translated) {
    coordinate.assign(degree, 0.0);
  }
  double constantRadius = 0;
  std::optional<double> smallestConstantWeight;
  bool unequalWeights = false;
  for (std::size_t i = 0; i < count; ++i) {
    if (!active[i]) {
      continue;
    }
    if (wConstant[i]) {
      double weight = w[i].constant;
      unequalWeights = unequalWeights || weight != reference;
      smallestConstantWeight = std::min(smallestConstantWeight.value_or(weight), weight);
      for (std::size_t k = 0; k < degree; ++k) {
        // W' = sum (w_i - reference) N_i' (the N_i' sum to zero): the share
        // of weights equal to the reference is nothing.
        constantWeights[k] += (weight - reference) * basis[i][k];
      }
    } else {
      unequalWeights = true;
    }
    if (qConstant[i]) {
      Eigen::Vector3d point(q[i][0].constant, q[i][1].constant, q[i][2].constant);
      constantRadius = std::max(constantRadius, (point - centre).norm());
    }
    if (qConstant[i] && wConstant[i]) {
      double weight = w[i].constant;
      for (std::size_t k = 0; k < degree; ++k) {
        for (int c = 0; c < 3; ++c) {
          segment.constantPart[c][k] += weight * q[i][c].constant * basis[i][k];
          translated[c][k] += weight * (q[i][c].constant - centre[c]) * basis[i][k];
        }
        segment.constantPart[3][k] += (weight - reference) * basis[i][k];
      }
    }
  }
  for (double& coefficient : segment.constantPart[3]) {
    coefficient = std::abs(coefficient) <= 1e-12 ? 0.0 : coefficient;
  }
  segment.rational = unequalWeights;
  // Homogeneous points of the dependent control points, on the controller,
  // and the bounds as sums of constant multiples of controller values.
  Arithmetic& math = arithmetic_;
  LinearForm radius{constantRadius, {}};
  LinearForm weightSlope, weightCurve;
  std::array<Polynomial, 3> translatedSlope, translatedCurve;
  for (int c = 0; c < 3; ++c) {
    translatedSlope[c] = derivativeOf(translated[c]);
    translatedCurve[c] = derivativeOf(translatedSlope[c]);
  }
  LinearForm pointSlope{
      vectorSupremumBound({translatedSlope[0], translatedSlope[1], translatedSlope[2]}), {}};
  LinearForm pointCurve{
      vectorSupremumBound({translatedCurve[0], translatedCurve[1], translatedCurve[2]}), {}};
  if (unequalWeights) {
    weightSlope.constant = supremumBound(derivativeOf(constantWeights));
    weightCurve.constant = supremumBound(derivativeOf(derivativeOf(constantWeights)));
  }
  Scalar smallestWeight = Scalar::of(smallestConstantWeight.value_or(0));
  bool haveSmallest = smallestConstantWeight.has_value();
  for (std::size_t d : dependent) {
    segment.dependentBasis.push_back(basis[d]);
    // A zero coordinate stays a literal zero (x * 0 is not folded: x may be
    // infinite, here it is a finite weight).
    auto weighted = [&](const Scalar& coordinate) {
      return coordinate.isConstant() && coordinate.constant == 0 ? Scalar::of(0)
                                                                 : math.multiply(w[d], coordinate);
    };
    segment.dependentPoints.push_back({weighted(q[d][0]), weighted(q[d][1]), weighted(q[d][2]),
                                       math.binary(Opcode::Sub, w[d], Scalar::of(reference))});
    double slopeBound = supremumBound(derivativeOf(basis[d]));
    double curveBound = supremumBound(derivativeOf(derivativeOf(basis[d])));
    // |q_d - c|: a literal for a constant point.
    LinearForm distance;
    if (qConstant[d]) {
      Eigen::Vector3d point(q[d][0].constant, q[d][1].constant, q[d][2].constant);
      distance.constant = (point - centre).norm();
    } else {
      Scalar squares = Scalar::of(0);
      for (int c = 0; c < 3; ++c) {
        Scalar offset = math.binary(Opcode::Sub, q[d][c], Scalar::of(centre[c]));
        squares = math.add(squares, math.multiply(offset, offset));
      }
      distance.add(math.unary(Opcode::Sqrt, squares), 1);
      radius.add(distance, 1);
    }
    // The weights are positive (the bound divides by the smallest), so |w| = w.
    LinearForm size{wConstant[d] ? w[d].constant : 0, {}};
    if (!wConstant[d]) {
      size.add(w[d], 1);
    }
    LinearForm homogeneous = size.times(distance, math);
    pointSlope.add(homogeneous, slopeBound);
    pointCurve.add(homogeneous, curveBound);
    if (!wConstant[d]) {
      LinearForm offset;
      offset.add(math.unary(Opcode::Abs, math.binary(Opcode::Sub, w[d], Scalar::of(reference))), 1);
      weightSlope.add(offset, slopeBound);
      weightCurve.add(offset, curveBound);
      // min(a, b) = (a + b - |a - b|) / 2, one inline expression.
      smallestWeight =
          haveSmallest
              ? math.multiply(
                    Scalar::of(0.5),
                    math.binary(
                        Opcode::Sub, math.add(smallestWeight, w[d]),
                        math.unary(Opcode::Abs, math.binary(Opcode::Sub, smallestWeight, w[d]))))
              : w[d];
      haveSmallest = true;
    }
  }
  // M / (8 budget), the constant factor taken into the sums' coefficients:
  // M = (P2 + W2 R + 2 W1 (P1 + W1 R) / wmin) / wmin.
  double factor = 1 / (8 * budget);
  LinearForm curveNumerator;
  curveNumerator.add(pointCurve, factor);
  Scalar scaledBound;
  if (unequalWeights) {
    LinearForm slopeNumerator = pointSlope;
    slopeNumerator.add(weightSlope.times(radius, math), 1);
    curveNumerator.add(weightCurve.times(radius, math), factor);
    LinearForm doubledSlope;
    doubledSlope.add(weightSlope, 2 * factor);
    Scalar cross = math.binary(
        Opcode::Div, math.multiply(doubledSlope.scalar(math), slopeNumerator.scalar(math)),
        smallestWeight);
    scaledBound =
        math.binary(Opcode::Div, math.add(curveNumerator.scalar(math), cross), smallestWeight);
  } else {
    scaledBound = math.binary(Opcode::Div, curveNumerator.scalar(math), smallestWeight);
  }
  // N >= sqrt(M / (8 budget)) steps of u; a transform stretches M by its norm.
  Scalar steps = math.unary(Opcode::Sqrt, times(scaledBound, norm));
  segment.stepCount = roundedUpSteps(steps);
}

CurvePoint PartLowering::splitSpanPoint(const ControllerSegment& segment, Scalar u) {
  Arithmetic& math = arithmetic_;
  std::array<Scalar, 4> sums;
  for (int c = 0; c < 4; ++c) {
    sums[c] = hornerOf(segment.constantPart[c], u);
  }
  for (std::size_t d = 0; d < segment.dependentBasis.size(); ++d) {
    Scalar basis = hornerOf(segment.dependentBasis[d], u);
    for (int c = 0; c < 4; ++c) {
      const Scalar& factor = segment.dependentPoints[d][c];
      if (!(factor.isConstant() && factor.constant == 0)) {
        sums[c] = math.add(sums[c], math.multiply(factor, basis));
      }
    }
  }
  if (segment.rational) {
    Scalar weight = math.add(Scalar::of(segment.referenceWeight), sums[3]);
    for (int c = 0; c < 3; ++c) {
      if (!(sums[c].isConstant() && sums[c].constant == 0)) {
        sums[c] = math.binary(Opcode::Div, sums[c], weight);
      }
    }
  } else if (segment.referenceWeight != 1) {
    for (int c = 0; c < 3; ++c) {
      sums[c] = math.binary(Opcode::Div, sums[c], Scalar::of(segment.referenceWeight));
    }
  }
  return {sums[0], sums[1], sums[2]};
}

} // namespace cncc::ir::lowering
