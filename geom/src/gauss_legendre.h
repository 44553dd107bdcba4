#pragma once

// Gauss-Legendre quadrature on [-1, 1] (internal).

#include <array>

namespace cncc::geom::detail {

inline constexpr int kGaussLegendreNodes = 10;

struct GaussLegendreRule {
  std::array<double, kGaussLegendreNodes> nodes;
  std::array<double, kGaussLegendreNodes> weights;
};

/// The 10-node rule (exact for polynomials of degree 19), computed once.
const GaussLegendreRule& gaussLegendreRule();

/// Integral of f over [a, b] by the 10-node rule.
template <class F> double integrateGaussLegendre(const F& f, double a, double b) {
  const GaussLegendreRule& rule = gaussLegendreRule();
  double half = 0.5 * (b - a), middle = 0.5 * (a + b);
  double sum = 0.0;
  for (int i = 0; i < kGaussLegendreNodes; ++i)
    sum += rule.weights[static_cast<std::size_t>(i)] *
           f(middle + half * rule.nodes[static_cast<std::size_t>(i)]);
  return half * sum;
}

} // namespace cncc::geom::detail
