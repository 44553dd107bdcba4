#include "gauss_legendre.h"

#include <cmath>
#include <numbers>

namespace cncc::geom::detail {

namespace {

// Nodes are the roots of the Legendre polynomial P_n, found by Newton's method from
// the Chebyshev-like guess cos(pi (i + 3/4) / (n + 1/2)); weights 2 / ((1 - x^2) P_n'(x)^2).
GaussLegendreRule computeRule() {
  const int n = kGaussLegendreNodes;
  GaussLegendreRule rule{};
  for (int i = 0; i < n; ++i) {
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double derivative = 0.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      // P_n(x) and P_{n-1}(x) by the three-term recurrence.
      double current = 1.0, previous = 0.0;
      for (int k = 1; k <= n; ++k) {
        double next = ((2.0 * k - 1.0) * x * current - (k - 1.0) * previous) / k;
        previous = current;
        current = next;
      }
      derivative = n * (x * current - previous) / (x * x - 1.0);
      double step = current / derivative;
      x -= step;
      if (std::fabs(step) < 1e-16)
        break;
    }
    rule.nodes[static_cast<std::size_t>(i)] = x;
    rule.weights[static_cast<std::size_t>(i)] = 2.0 / ((1.0 - x * x) * derivative * derivative);
  }
  return rule;
}

} // namespace

const GaussLegendreRule& gaussLegendreRule() {
  static const GaussLegendreRule rule = computeRule();
  return rule;
}

} // namespace cncc::geom::detail
