// The number of uniform steps of u in [0, 1] whose chords keep a rational
// Bezier span within a budget, from its homogeneous control points. Written
// once over a number type: the lowering computes it as controller
// arithmetic (the control points depend on part parameters, see
// controller_nurbs_spans.cpp), the tests on doubles.
//
// The bound. The span is C(u) = P(u) / W(u) with P = sum_j w_j b_j B_j,
// W = sum_j w_j B_j (Bernstein polynomials B_j of degree n, weights w_j > 0).
// Take a point c (any; the caller's centre of the span) and a step [a, b],
// h = b - a. Let m(u) = W(b) (u - a) / h, s(u) = m(u) / W(u) and X(u) =
// C(a) + s(u) (C(b) - C(a)), a point of the chord's line. Then
//   g(u) = W(u) (C(u) - X(u)) = P(u) - W(u) c - W(u) (C(a) - c) - m(u) (C(b) - C(a))
// is a polynomial with g(a) = g(b) = 0 and, m being linear,
//   g''(u) = (P - W c)''(u) - W''(u) (C(a) - c).
// A vector polynomial that vanishes at a and b has |g(u)| <= (u - a)(b - u)
// / 2 max |g''| <= h^2 / 8 max |g''| (apply the scalar bound to e . g for
// e = g(u) / |g(u)|). The Bernstein coefficients bound the derivatives:
// (P - W c)'' = n (n - 1) sum_j D_j B^{n-2}_j with D_j the second
// differences of w_j (b_j - c), |W''| <= n (n - 1) max |second differences
// of w_j| = W2, |W'| <= n max |differences of w_j| = W1; and |C(a) - c| <= R
// for R >= max_j |b_j - c| (positive weights: the curve lies in the hull of
// the b_j). With wmin <= W (the smallest w_j, or any smaller bound):
//   |C(u) - X(u)| <= h^2 G / (8 wmin),  G = n (n - 1) max_j (|D_j| + |second
//   difference of w_j| R).
// X(u) lies on the chord itself when 0 <= s <= 1, that is 0 <= m <= W on
// [a, b]. On the step as a Bezier curve of its own (parameter t = (u - a) /
// h), with weights v_k (the blossom of W at a^(n-k) b^k): m = v_n t = sum_k
// (k / n) v_n B_k(t), so W - m = sum_k (v_k - k v_n / n) B_k(t). Moving one
// argument of the blossom from a to b changes it by at most h W1 / n, so
// v_k >= v_n - (n - k) h W1 / n and v_k - k v_n / n >= (n - k) / n (v_n - h
// W1) >= 0 once wmin >= h W1. And X runs from C(a) to C(b), so every point
// of the chord is that close to the curve too. Hence
//   N >= sqrt(G / (8 budget wmin))  and  N >= W1 / wmin
// uniform steps keep every chord within the budget; an affine map that
// stretches lengths by at most `stretch` multiplies G by it. The count
// taken is N = sqrt(G / (8 budget wmin) + n^2 sum_j (w_(j+1) - w_j)^2 /
// wmin^2), at least both (W1^2 <= n^2 times the sum of the squared
// differences): the two conditions in one expression for the controller,
// without a maximum, whose operands would each take a block of their own.
//
// This is sharper than a bound of |C''|: C'' = (P'' - W'' C - 2 W' C') / W,
// and the chord takes up the tangential term 2 W' C' / W, the largest one
// where the weights change fast. It still bounds the whole of g'', not only
// its part normal to the chord: where the weights drive the speed along the
// curve far from uniform it asks for more steps than the curve needs.
//
// Math provides the number type and its operations:
//   using Number; Number constant(double); add, multiply, divide, larger
//   (Number, Number); squareRoot(Number); bool isZero(const Number&);
//   using Point; Point combination(const std::vector<double>& k): sum_j k_j
//   (w_j (b_j - c), w_j) over the span's n + 1 control points;
//   Number length(const Point&) (|x, y, z|), weight(const Point&),
//   weightTimes(const Point&, Number factor) (|weight| factor),
//   sumOfSquaredWeights(const std::vector<Point>&).
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <vector>

namespace cncc::ir::lowering {

namespace rational_span {

// The coefficients of the difference of order `order` (0, 1 or 2) of the
// control points, starting at j.
inline std::vector<double> differenceOf(std::size_t points, std::size_t j, int order) {
  std::vector<double> coefficients(points, 0.0);
  static constexpr std::array<std::array<double, 3>, 3> rows = {
      {{1, 0, 0}, {-1, 1, 0}, {1, -2, 1}}};
  for (int k = 0; k <= order; ++k) {
    coefficients[j + static_cast<std::size_t>(k)] =
        rows[static_cast<std::size_t>(order)][static_cast<std::size_t>(k)];
  }
  return coefficients;
}

} // namespace rational_span

// The steps the bound above asks for, before rounding up. `smallestWeight`
// is a positive lower bound of the weights, `radius` an upper bound of the
// control points' distances from the centre, chordFactor = 1 / (8 budget).
template <class Math, class Number = typename Math::Number>
Number rationalSpanSteps(Math& math, std::size_t degree, double chordFactor, Number stretch,
                         Number smallestWeight, Number radius) {
  using rational_span::differenceOf;
  std::size_t points = degree + 1;
  double n = static_cast<double>(degree);
  std::optional<Number> largestTerm;
  for (std::size_t j = 0; j + 2 < points; ++j) {
    auto second = math.combination(differenceOf(points, j, 2));
    Number term = math.length(second);
    if (!math.isZero(math.weight(second))) {
      term = math.add(term, math.weightTimes(second, radius));
    }
    largestTerm = largestTerm ? math.larger(*largestTerm, term) : term;
  }
  Number chord = math.constant(0); // G stretch / (8 budget)
  if (largestTerm) {
    chord = math.multiply(math.multiply(*largestTerm, stretch),
                          math.constant(n * (n - 1) * chordFactor));
  }
  std::vector<typename Math::Point> slopes;
  for (std::size_t j = 0; j + 1 < points; ++j) {
    slopes.push_back(math.combination(differenceOf(points, j, 1)));
  }
  Number slopeSquares = math.sumOfSquaredWeights(slopes);
  if (!math.isZero(slopeSquares)) {
    // (chord + n^2 sum / wmin) / wmin: wmin is one value, its square would
    // be another.
    chord = math.add(
        chord, math.divide(math.multiply(slopeSquares, math.constant(n * n)), smallestWeight));
  }
  return math.squareRoot(math.divide(chord, smallestWeight));
}

} // namespace cncc::ir::lowering
