#pragma once

// Fourth-order finite differences that never leave the parameter range (internal).
// Central 5-point stencils where they fit, one-sided 5-point stencils near an end.
// Works for any f returning double or an Eigen vector.

#include "cncc/geom/curve.h"

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace cncc::geom::detail {

// Steps balancing truncation (h^4) against rounding (eps/h^k): eps^(1/5) for the first
// derivative and eps^(1/6) for the second, for functions that vary on a parameter scale
// of about 1. The step is not scaled by |t|: for t up to 1e4 the rounding of t + h stays
// below 1e-8 of h, while a step growing with t would make the truncation error of an
// oscillating curve (the polar contour at t = 6) a hundred times larger.
inline constexpr double kFirstDerivativeStep = 7.4e-4;  // (2.2e-16)^(1/5)
inline constexpr double kSecondDerivativeStep = 2.5e-3; // (2.2e-16)^(1/6)

inline double stepFor(double step, ParameterRange range) {
  return std::min(step, range.length() / 4.0);
}

// Eigen returns expression templates, so the result type is named, never deduced.
template <class F> using DifferenceValue = std::decay_t<std::invoke_result_t<const F&, double>>;

template <class F>
DifferenceValue<F> firstDerivativeByDifferences(const F& f, double t, ParameterRange range) {
  double h = stepFor(kFirstDerivativeStep, range);
  if (t - 2 * h >= range.t0 && t + 2 * h <= range.t1)
    return ((f(t - 2 * h) - f(t + 2 * h)) + 8.0 * (f(t + h) - f(t - h))) / (12.0 * h);
  // One-sided: h < 0 reaches backwards from the upper end.
  if (t + 4 * h > range.t1)
    h = -h;
  return (-25.0 * f(t) + 48.0 * f(t + h) - 36.0 * f(t + 2 * h) + 16.0 * f(t + 3 * h) -
          3.0 * f(t + 4 * h)) /
         (12.0 * h);
}

template <class F>
DifferenceValue<F> secondDerivativeByDifferences(const F& f, double t, ParameterRange range) {
  double h = stepFor(kSecondDerivativeStep, range);
  if (t - 2 * h >= range.t0 && t + 2 * h <= range.t1)
    return (16.0 * (f(t - h) + f(t + h)) - (f(t - 2 * h) + f(t + 2 * h)) - 30.0 * f(t)) /
           (12.0 * h * h);
  if (t + 4 * h > range.t1)
    h = -h;
  return (35.0 * f(t) - 104.0 * f(t + h) + 114.0 * f(t + 2 * h) - 56.0 * f(t + 3 * h) +
          11.0 * f(t + 4 * h)) /
         (12.0 * h * h);
}

} // namespace cncc::geom::detail
