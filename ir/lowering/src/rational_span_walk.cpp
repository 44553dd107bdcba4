// A rational NURBS span whose weights the program computes, walked with a
// step computed at each point instead of one count for the whole span: its
// region of the lap gives the step (curve.walk), and expand-controller-loops
// writes the loop ending in loop.next.
//
// The bound is that of rational_span_steps.h taken over one step [u, u + h]
// instead of the whole span: with c = C(u), the chord's start, g = W (C -
// X) vanishes at both ends and g'' = (P - W c)'', a polynomial whose Taylor
// series at u is exact, so over the step
//   |g''| <= sum_(k=2..n) |D_k| h^(k-2) / (k-2)!,  D_k = P^(k)(u) - W^(k)(u) c,
// and likewise |W'| <= M(h) = sum_(k=1..n) |W^(k)(u)| h^(k-1) / (k-1)!, so
// W >= W(u) - h M(h) on the step. The chord keeps the budget when
//   f(h) = sum_(k=1..n) e_k h^k - W(u) <= 0,  e_k = a_k + |W^(k)(u)| / (k-1)!,
//   a_k = stretch |D_k| / (8 budget (k-2)!) (a_1 = 0),
// and X stays on the chord when 2 h M(h) <= W(u): then W(t) - W(b) (t - a)
// / h >= (b - t) (W(b) / h - M) >= 0 on the step. f is increasing and
// convex for h >= 0. With t_k = ((e_k + 2 n |W^(k)(u)| / (k-1)!) / W(u))^(1/k),
//   hi = 1 / max_k t_k
// keeps each term of f, and of 2 h M(h), at most W(u) / n: f(hi / n) <= 0,
// the chord condition holds up to hi, and the root of f, where hi is not
// below it, is at most hi. Two steps of regula falsi from hi / n towards hi
// (convexity keeps each below the root) close most of the gap; the step is
// the result, at most hi. It is at least the span's uniform step 1 / N
// (stepCount), which keeps the tolerance anywhere on the span: the loop
// ends within N passes whatever the weights.
//
// Where the weights make the speed along the curve uneven this takes the
// points where the curve needs them: bench/RESULTS.md, "Parameter-dependent
// rational spans".
#include "controller_segment.h"
#include "part_lowering.h"

#include <algorithm>
#include <cmath>

namespace cncc::ir::lowering {

namespace {

// The regula falsi steps from below; two leave the step within a few
// percent of the root on the spans measured.
constexpr int rootRefinements = 2;
// Keeps every quotient finite and every value in the controllers' range
// (with their 8 digits it stays itself): e_1 is at least this share of the
// smallest weight, a root's argument at least this much. Both only shorten
// the step.
constexpr double coefficientFloor = 1e-6;

// The coordinates the span moves in: z only when a control point has one.
int spanDimensions(const ControllerSegment& segment) {
  bool flat = std::all_of(segment.constantPart[2].begin(), segment.constantPart[2].end(),
                          [](double coefficient) { return coefficient == 0; });
  for (const std::array<Scalar, 4>& point : segment.dependentPoints) {
    flat = flat && point[2].isConstant() && point[2].constant == 0;
  }
  return flat ? 2 : 3;
}

double factorial(int k) {
  double product = 1;
  for (int i = 2; i <= k; ++i) {
    product *= i;
  }
  return product;
}

} // namespace

std::array<Scalar, 4> PartLowering::splitSpanDerivative(const ControllerSegment& segment, Scalar u,
                                                        int order) {
  auto differentiated = [&](Polynomial polynomial) {
    for (int k = 0; k < order; ++k) {
      polynomial = derivativeOf(polynomial);
    }
    return polynomial;
  };
  Arithmetic& math = arithmetic_;
  std::array<Scalar, 4> sums;
  for (int c = 0; c < 4; ++c) {
    sums[c] = hornerOf(differentiated(segment.constantPart[c]), u);
  }
  for (std::size_t d = 0; d < segment.dependentBasis.size(); ++d) {
    Scalar basis = hornerOf(differentiated(segment.dependentBasis[d]), u);
    for (int c = 0; c < 4; ++c) {
      const Scalar& factor = segment.dependentPoints[d][c];
      if (!(factor.isConstant() && factor.constant == 0)) {
        sums[c] = math.add(sums[c], times(factor, basis));
      }
    }
  }
  if (order == 0) {
    sums[3] = math.add(Scalar::of(segment.referenceWeight), sums[3]);
  }
  return sums;
}

Scalar PartLowering::rationalSpanStep(const ControllerSegment& segment, Scalar u,
                                      const std::array<Scalar, 4>& point) {
  Arithmetic& math = arithmetic_;
  auto sub = [&](Scalar a, Scalar b) { return math.binary(Opcode::Sub, a, b); };
  auto div = [&](Scalar a, Scalar b) { return math.binary(Opcode::Div, a, b); };
  Scalar weight = point[3];
  int dimensions = spanDimensions(segment);
  std::array<Scalar, 3> centre;
  for (int c = 0; c < dimensions; ++c) {
    centre[c] = div(point[c], weight);
  }
  int degree = static_cast<int>(segment.constantPart[0].size()) - 1;
  // coefficients[k - 1]: e_k of f, k = 1 .. degree.
  std::vector<Scalar> coefficients;
  std::optional<Scalar> largest;
  for (int k = 1; k <= degree; ++k) {
    std::array<Scalar, 4> derivative = splitSpanDerivative(segment, u, k);
    Scalar slope = times(magnitude(derivative[3]), Scalar::of(1 / factorial(k - 1)));
    Scalar coefficient = slope;
    if (k == 1) {
      coefficient = math.add(slope, times(segment.smallestWeight, Scalar::of(coefficientFloor)));
    } else {
      Scalar squares = Scalar::of(0);
      for (int c = 0; c < dimensions; ++c) {
        Scalar offset = sub(derivative[c], times(derivative[3], centre[c]));
        squares = math.add(squares, times(offset, offset));
      }
      Scalar scale = Scalar::of(1 / (8 * segment.budget * factorial(k - 2)));
      coefficient =
          math.add(times(math.unary(Opcode::Sqrt, squares), times(segment.stretch, scale)), slope);
    }
    coefficients.push_back(coefficient);
    Scalar ratio = div(math.add(coefficient, times(slope, Scalar::of(2.0 * degree))), weight);
    Scalar root = k == 1   ? ratio
                  : k == 2 ? math.unary(Opcode::Sqrt, ratio)
                           : math.binary(Opcode::Pow, math.add(ratio, Scalar::of(coefficientFloor)),
                                         Scalar::of(1.0 / k));
    largest = largest ? math.larger(*largest, root) : root;
  }
  auto f = [&](Scalar h) {
    Scalar sum = coefficients.back();
    for (std::size_t k = coefficients.size() - 1; k-- > 0;) {
      sum = math.add(math.multiply(sum, h), coefficients[k]);
    }
    return sub(math.multiply(sum, h), weight);
  };
  Scalar high = div(Scalar::of(1), *largest);
  Scalar low = div(high, Scalar::of(degree));
  Scalar highValue = f(high);
  for (int refinement = 0; refinement < rootRefinements; ++refinement) {
    Scalar lowValue = f(low);
    Scalar rise = sub(highValue, lowValue);
    low = sub(low, div(math.multiply(lowValue, sub(high, low)), rise));
  }
  // Inline extremes: a rounding here is harmless.
  Scalar fewestSteps = div(Scalar::of(1), stepsOf(segment));
  return math.larger(math.smaller(low, high), fewestSteps);
}

} // namespace cncc::ir::lowering
