#pragma once

// Brent's method for a one-dimensional extremum (golden-section search accelerated by
// parabolic interpolation, R. P. Brent, Algorithms for Minimization without
// Derivatives, 1973, ch. 5). Header-only so the callback is inlined.

#include <cmath>
#include <limits>

namespace cncc::geom::detail {

struct ScalarExtremum {
  double t;
  double value;
};

/// Minimum of f on [a, b], assuming f is unimodal there (otherwise a local minimum).
/// The search runs in the offset from a, so it stops when the bracket is below
/// 2 (sqrt(eps) |t - a| + 1e-12 (b - a)): relative to the bracket, not to |t|. The
/// functions searched here (distances of a few micrometres along parameters of order
/// 10) are far narrower than |t|, and a tolerance relative to |t| would leave an
/// error of 1e-12 mm in the extreme value.
template <class F>
ScalarExtremum minimiseBrent(const F& f, double a, double b, int maxIterations = 200) {
  const double goldenFraction = 0.5 * (3.0 - std::sqrt(5.0));
  const double relativeTolerance = std::sqrt(std::numeric_limits<double>::epsilon());
  const double origin = a;
  const double absoluteTolerance = 1e-12 * (b - a);
  auto g = [&](double offset) { return f(origin + offset); };
  b -= origin;
  a = 0.0;
  double x = goldenFraction * b;
  double w = x, v = x;
  double fx = g(x);
  double fw = fx, fv = fx;
  double step = 0.0;     // last step taken
  double stepBefore = 0; // the step before it (parabolic steps must shrink against it)
  for (int iteration = 0; iteration < maxIterations; ++iteration) {
    double middle = 0.5 * (a + b);
    double tol1 = relativeTolerance * std::fabs(x) + absoluteTolerance;
    double tol2 = 2.0 * tol1;
    if (std::fabs(x - middle) <= tol2 - 0.5 * (b - a))
      break;
    bool useGolden = true;
    if (std::fabs(stepBefore) > tol1) {
      // Parabola through (x, fx), (w, fw), (v, fv); its vertex is x + p / q.
      double r = (x - w) * (fx - fv);
      double q = (x - v) * (fx - fw);
      double p = (x - v) * q - (x - w) * r;
      q = 2.0 * (q - r);
      if (q > 0.0)
        p = -p;
      else
        q = -q;
      double previous = stepBefore;
      stepBefore = step;
      // Accept only a step inside the bracket and shorter than half the step two
      // iterations ago, so the search keeps shrinking at least like bisection.
      if (std::fabs(p) < std::fabs(0.5 * q * previous) && p > q * (a - x) && p < q * (b - x)) {
        step = p / q;
        double u = x + step;
        if (u - a < tol2 || b - u < tol2)
          step = x < middle ? tol1 : -tol1;
        useGolden = false;
      }
    }
    if (useGolden) {
      stepBefore = (x >= middle) ? a - x : b - x;
      step = goldenFraction * stepBefore;
    }
    double u = std::fabs(step) >= tol1 ? x + step : x + (step > 0 ? tol1 : -tol1);
    double fu = g(u);
    if (fu <= fx) {
      (u >= x ? a : b) = x;
      v = w, fv = fw;
      w = x, fw = fx;
      x = u, fx = fu;
    } else {
      (u < x ? a : b) = u;
      if (fu <= fw || w == x) {
        v = w, fv = fw;
        w = u, fw = fu;
      } else if (fu <= fv || v == x || v == w) {
        v = u, fv = fu;
      }
    }
  }
  return {origin + x, fx};
}

/// Maximum of f on [a, b], as minimiseBrent on -f.
template <class F>
ScalarExtremum maximiseBrent(const F& f, double a, double b, int maxIterations = 200) {
  ScalarExtremum m = minimiseBrent([&](double t) { return -f(t); }, a, b, maxIterations);
  return {m.t, -m.value};
}

} // namespace cncc::geom::detail
