// The controller's arithmetic for rationalSpanSteps
// (cncc/lowering/rational_span_steps.h): the span's homogeneous Bezier
// control points are sums of constant multiples of controller values
// (LinearForm), so each combination of them is one flat sum, and the
// square of one is a polynomial in the values, printed as one expression.
#pragma once

#include "controller_segment.h"

#include <array>
#include <vector>

namespace cncc::ir::lowering {

class ControllerSpanMath {
public:
  using Number = Scalar;
  using Point = std::array<LinearForm, 4>;

  ControllerSpanMath(Arithmetic& math, std::vector<Point> points)
      : math_(math), points_(std::move(points)) {}

  Scalar constant(double value) { return Scalar::of(value); }
  bool isZero(const Scalar& value) { return value.isConstant() && value.constant == 0; }
  Scalar add(Scalar a, Scalar b) { return math_.add(a, b); }
  // The bounds are finite: a product with a literal zero is zero.
  Scalar multiply(Scalar a, Scalar b) {
    return isZero(a) || isZero(b) ? Scalar::of(0) : math_.multiply(a, b);
  }
  Scalar divide(Scalar a, Scalar b) { return math_.binary(Opcode::Div, a, b); }
  Scalar magnitude(Scalar a);
  Scalar squareRoot(Scalar a);
  // As Arithmetic's: one inline expression.
  Scalar larger(Scalar a, Scalar b) { return math_.larger(a, b); }
  Scalar smaller(Scalar a, Scalar b) { return math_.smaller(a, b); }

  Point combination(const std::vector<double>& coefficients) const;
  Scalar length(const Point& point);
  Scalar weight(const Point& point) { return point[3].scalar(math_); }
  // |weight| factor; a literal factor goes into the weight's sum.
  Scalar weightTimes(const Point& point, Scalar factor);
  Scalar sumOfSquaredWeights(const std::vector<Point>& points);

private:
  // sum_k form_k^2, expanded in the forms' values.
  Scalar squareOf(const std::vector<LinearForm>& forms, bool cushioned);

  Arithmetic& math_;
  std::vector<Point> points_;
};

} // namespace cncc::ir::lowering
