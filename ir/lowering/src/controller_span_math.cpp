#include "controller_span_math.h"

#include <algorithm>
#include <cmath>

namespace cncc::ir::lowering {

namespace {

double sizeOf(const LinearForm& form) {
  double largest = std::abs(form.constant);
  for (const auto& term : form.terms) {
    largest = std::max(largest, std::abs(term.second));
  }
  return largest;
}

// Differences cancel: what is left of a coefficient at the rounding of the
// sum's inputs is nothing.
LinearForm withoutNoise(const LinearForm& form, double noise) {
  LinearForm cleaned{std::abs(form.constant) <= noise ? 0.0 : form.constant, {}};
  for (const auto& [value, factor] : form.terms) {
    if (std::abs(factor) > noise) {
      cleaned.terms.emplace_back(value, factor);
    }
  }
  return cleaned;
}

// The literals print to 8 significant digits. Where a square's expansion
// cancels (near a zero of the form) their rounding leaves an error of the
// order of 1e-8 of its constant term: this share of it is added.
constexpr double printedRoundingShare = 1e-7;

} // namespace

Scalar ControllerSpanMath::magnitude(Scalar a) {
  return a.isConstant() ? Scalar::of(std::abs(a.constant)) : math_.unary(Opcode::Abs, a);
}

Scalar ControllerSpanMath::squareRoot(Scalar a) {
  return a.isConstant() ? Scalar::of(std::sqrt(a.constant)) : math_.unary(Opcode::Sqrt, a);
}

ControllerSpanMath::Point
ControllerSpanMath::combination(const std::vector<double>& coefficients) const {
  Point result;
  for (std::size_t c = 0; c < 4; ++c) {
    LinearForm sum;
    double scale = 0;
    for (std::size_t j = 0; j < coefficients.size(); ++j) {
      if (coefficients[j] != 0) {
        sum.add(points_[j][c], coefficients[j]);
        scale += std::abs(coefficients[j]) * sizeOf(points_[j][c]);
      }
    }
    result[c] = withoutNoise(sum, 1e-12 * scale);
  }
  return result;
}

// sqrt(x^2 + y^2 + z^2) with the squares expanded (no operand is used
// twice, so the controller needs no variable for it); one coordinate is
// its magnitude.
Scalar ControllerSpanMath::length(const Point& point) {
  std::vector<LinearForm> coordinates;
  for (std::size_t c = 0; c < 3; ++c) {
    if (!(point[c].isConstant() && point[c].constant == 0)) {
      coordinates.push_back(point[c]);
    }
  }
  if (coordinates.size() == 1) {
    return magnitude(coordinates.front().scalar(math_));
  }
  return squareRoot(squareOf(coordinates, true));
}

Scalar ControllerSpanMath::sumOfSquaredWeights(const std::vector<Point>& points) {
  std::vector<LinearForm> weights;
  for (const Point& point : points) {
    weights.push_back(point[3]);
  }
  // A bound of another (see rationalSpanSteps) with room to spare.
  return squareOf(weights, false);
}

Scalar ControllerSpanMath::weightTimes(const Point& point, Scalar factor) {
  if (!factor.isConstant()) {
    return multiply(magnitude(point[3].scalar(math_)), factor);
  }
  LinearForm scaled;
  scaled.add(point[3], std::abs(factor.constant));
  return magnitude(scaled.scalar(math_));
}

// sum_k (c_k + sum_t a_kt v_t)^2 = sum c_k^2 + sum_t v_t (2 sum_k c_k a_kt +
// sum_(t' >= t) (2 - [t = t']) sum_k a_kt a_kt' v_t'), by value; its
// magnitude (rounding may take a zero below) and, `cushioned`, the printed
// literals' share added.
Scalar ControllerSpanMath::squareOf(const std::vector<LinearForm>& forms, bool cushioned) {
  std::vector<Scalar> values;
  auto indexOf = [&](const Scalar& value) {
    for (std::size_t t = 0; t < values.size(); ++t) {
      if (values[t].value == value.value) {
        return t;
      }
    }
    values.push_back(value);
    return values.size() - 1;
  };
  double constantPart = 0;
  std::vector<double> linear;
  std::vector<std::vector<double>> products;
  for (const LinearForm& form : forms) {
    constantPart += form.constant * form.constant;
    std::vector<std::pair<std::size_t, double>> terms;
    for (const auto& [value, factor] : form.terms) {
      terms.emplace_back(indexOf(value), factor);
    }
    linear.resize(values.size(), 0.0);
    products.resize(values.size());
    for (std::vector<double>& row : products) {
      row.resize(values.size(), 0.0);
    }
    for (std::size_t i = 0; i < terms.size(); ++i) {
      auto [t, a] = terms[i];
      linear[t] += 2 * form.constant * a;
      for (std::size_t k = i; k < terms.size(); ++k) {
        auto [u, b] = terms[k];
        products[std::min(t, u)][std::max(t, u)] += (k == i ? 1 : 2) * a * b;
      }
    }
  }
  Scalar sum = Scalar::of(constantPart);
  for (std::size_t t = 0; t < values.size(); ++t) {
    Scalar factor = Scalar::of(linear[t]);
    for (std::size_t u = t; u < values.size(); ++u) {
      factor = add(factor, multiply(Scalar::of(products[t][u]), values[u]));
    }
    sum = add(sum, multiply(values[t], factor));
  }
  if (sum.isConstant()) {
    return sum;
  }
  return add(magnitude(sum), Scalar::of(cushioned ? printedRoundingShare * constantPart : 0));
}

} // namespace cncc::ir::lowering
