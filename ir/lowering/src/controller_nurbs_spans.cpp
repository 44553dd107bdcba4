// NURBS spans on the controller (controller_cuts.cpp plans them): a span
// moved by a transform of controller values, and a span whose control
// points depend on parameters, split into literals and the dependent
// points' share, with the chord bound its step count comes from.
#include "controller_span_math.h"

#include "cncc/lowering/rational_span_steps.h"

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

namespace {

// What planSplitSpan knows of a span's control points: the B-spline's
// points q and weights w (literals or controller values), which are
// active on the span, which depend on parameters, the basis functions.
struct SpanControlPoints {
  const CurveValue& value;
  const std::vector<std::array<Scalar, 3>>& q;
  const std::vector<Scalar>& w;
  const std::vector<bool>& qConstant;
  const std::vector<bool>& wConstant;
  const std::vector<bool>& active;
  const std::vector<std::size_t>& dependent;
  const std::vector<Polynomial>& basis;
};

// The centre of the span's Bezier control points at the defaults (any
// point would do; a near one keeps R small).
Eigen::Vector3d bezierCentre(const SpanControlPoints& span, const std::vector<Polynomial>& bezier) {
  const CurveValue& value = span.value;
  std::size_t points = span.basis.front().size();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (std::size_t j = 0; j < points; ++j) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    double weightSum = 0;
    for (std::size_t i = 0; i < value.points.size(); ++i) {
      double weight = value.weights.empty() ? 1.0 : value.weights[i];
      sum += bezier[i][j] * weight *
             Eigen::Vector3d(value.points[i][0], value.points[i][1], value.points[i][2]);
      weightSum += bezier[i][j] * weight;
    }
    centre += sum / weightSum / static_cast<double>(points);
  }
  return centre;
}

// (w_j (b_j - centre), w_j) per Bezier control point j: bezier[i][j] is the
// share of the B-spline's control point i in it.
std::vector<ControllerSpanMath::Point>
homogeneousBezierPoints(const SpanControlPoints& span, const std::vector<Polynomial>& bezier,
                        const ControllerSegment& segment, const Eigen::Vector3d& centre) {
  std::vector<ControllerSpanMath::Point> homogeneous(span.basis.front().size());
  for (std::size_t j = 0; j < homogeneous.size(); ++j) {
    for (std::size_t i = 0; i < span.q.size(); ++i) {
      double share = bezier[i][j];
      if (share == 0) {
        continue;
      }
      ControllerSpanMath::Point& point = homogeneous[j];
      point[3].add(span.w[i], share);
      for (int c = 0; c < 3; ++c) {
        if (span.qConstant[i]) {
          // w_i (q_i - centre) with q_i a literal: a multiple of the weight.
          point[c].add(span.w[i], share * (span.q[i][c].constant - centre[c]));
          continue;
        }
        std::size_t d = static_cast<std::size_t>(
            std::find(span.dependent.begin(), span.dependent.end(), i) - span.dependent.begin());
        point[c].add(segment.dependentPoints[d][c], share);
        if (centre[c] != 0) {
          point[c].add(span.w[i], -share * centre[c]);
        }
      }
    }
  }
  return homogeneous;
}

struct SpanBounds {
  Scalar steps;          // what rationalSpanSteps asks for, before rounding up
  Scalar smallestWeight; // a positive lower bound of the weights
};

// The bounds over the span's homogeneous Bezier control points.
SpanBounds chordSteps(Arithmetic& math, const SpanControlPoints& span,
                      const ControllerSegment& segment, double budget, Scalar norm) {
  std::size_t count = span.q.size();
  std::size_t points = span.basis.front().size();
  // The Bezier control points: Bernstein coefficients of the basis functions.
  std::vector<Polynomial> bezier(count);
  for (std::size_t i = 0; i < count; ++i) {
    bezier[i] = span.active[i] ? bernsteinCoefficients(span.basis[i]) : Polynomial(points, 0.0);
  }
  Eigen::Vector3d centre = bezierCentre(span, bezier);
  // The Bezier weights are convex combinations of the active ones (knot
  // insertion), the Bezier points lie in the hull of the active points: the
  // smallest active weight and the largest distance bound them (a sum of the
  // dependent points' distances, as the controller has no max).
  std::optional<double> smallestConstantWeight;
  double constantRadius = 0;
  LinearForm radius;
  std::vector<Scalar> runtimeWeights;
  for (std::size_t i = 0; i < count; ++i) {
    if (!span.active[i]) {
      continue;
    }
    if (span.wConstant[i]) {
      smallestConstantWeight =
          std::min(smallestConstantWeight.value_or(span.w[i].constant), span.w[i].constant);
    } else {
      runtimeWeights.push_back(span.w[i]);
    }
    if (span.qConstant[i]) {
      Eigen::Vector3d point(span.q[i][0].constant, span.q[i][1].constant, span.q[i][2].constant);
      constantRadius = std::max(constantRadius, (point - centre).norm());
      continue;
    }
    Scalar squares = Scalar::of(0);
    for (int c = 0; c < 3; ++c) {
      Scalar offset = math.binary(Opcode::Sub, span.q[i][c], Scalar::of(centre[c]));
      squares = math.add(squares, math.multiply(offset, offset));
    }
    radius.add(math.unary(Opcode::Sqrt, squares), 1);
  }
  radius.constant = constantRadius;
  ControllerSpanMath spanMath(math, homogeneousBezierPoints(span, bezier, segment, centre));
  Scalar smallestWeight = Scalar::of(smallestConstantWeight.value_or(0));
  for (std::size_t k = 0; k < runtimeWeights.size(); ++k) {
    smallestWeight = k == 0 && !smallestConstantWeight
                         ? runtimeWeights[k]
                         : spanMath.smaller(smallestWeight, runtimeWeights[k]);
  }
  return {rationalSpanSteps(spanMath, points - 1, 1 / (8 * budget), norm, smallestWeight,
                            radius.scalar(math)),
          smallestWeight};
}

} // namespace

// A weight the program computes stops it with an alarm before anything is
// divided by it, unless positive (the controller's own error would name
// neither the curve nor the weight).
void PartLowering::guardWeights(const SymbolicList& weights) {
  for (const std::optional<Lowered>& weight : weights) {
    if (weight && weight->kind == TypeKind::Num && !weight->values.front().isConstant()) {
      alarmWhen(arithmetic_.binary(Opcode::Le, weight->values.front(), Scalar::of(0)),
                "a weight of a NURBS is not positive");
    }
  }
}

// A NURBS span with control points that depend on parameters (planned as
// `split`, see ControllerSegment), and its step count on the controller:
// rationalSpanSteps (cncc/lowering/rational_span_steps.h, where the bound is
// derived) over the span's homogeneous Bezier control points. Each is a
// combination of the B-spline's homogeneous control points (w_i q_i, w_i)
// with the Bernstein coefficients of the span's basis functions, so a
// combination of the constant points' share (a literal) and the dependent
// points' homogeneous points (controller values).
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
  bool unequalWeights = false;
  for (std::size_t i = 0; i < count; ++i) {
    if (!active[i]) {
      continue;
    }
    unequalWeights = unequalWeights || !wConstant[i] || w[i].constant != reference;
    if (qConstant[i] && wConstant[i]) {
      double weight = w[i].constant;
      for (std::size_t k = 0; k < degree; ++k) {
        for (int c = 0; c < 3; ++c) {
          segment.constantPart[c][k] += weight * q[i][c].constant * basis[i][k];
        }
        // W = reference + sum (w_i - reference) N_i (the N_i sum to one).
        segment.constantPart[3][k] += (weight - reference) * basis[i][k];
      }
    }
  }
  for (double& coefficient : segment.constantPart[3]) {
    coefficient = std::abs(coefficient) <= 1e-12 ? 0.0 : coefficient;
  }
  segment.rational = unequalWeights;
  // Homogeneous points of the dependent control points, computed once.
  Arithmetic& math = arithmetic_;
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
  }
  SpanControlPoints span{value, q, w, qConstant, wConstant, active, dependent, basis};
  SpanBounds bounds = chordSteps(math, span, segment, budget, norm);
  segment.stepCount = roundedUpSteps(bounds.steps);
  if (segment.rational && degree >= 3) {
    segment.stepPerPoint = true;
    segment.smallestWeight = bounds.smallestWeight;
    segment.budget = budget;
    segment.stretch = norm;
  }
}

CurvePoint PartLowering::splitSpanPoint(const ControllerSegment& segment, Scalar u) {
  Arithmetic& math = arithmetic_;
  std::array<Scalar, 4> sums = splitSpanDerivative(segment, u, 0);
  if (segment.rational) {
    for (int c = 0; c < 3; ++c) {
      if (!(sums[c].isConstant() && sums[c].constant == 0)) {
        sums[c] = math.binary(Opcode::Div, sums[c], sums[3]);
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
