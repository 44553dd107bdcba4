// A stand-in for an analytic curve, whose every evaluation runs the part's
// expressions: quintic Hermite spans through its points, first and second
// derivatives at equal parameter steps on each smooth piece, the steps
// halved until the spans' midpoints and quarter points are within `error`
// of the curve (the error falls like h^6). Searches that evaluate a curve
// many times run on it and add `error` to the deviations they find.
// Its joins are not the curve's breakpoints (it is C2 there, and within
// `error`), so it reports the curve's own: fits place knots by the curve,
// not by the stand-in's spans.
#pragma once

#include "cncc/geom/curve.h"
#include "cncc/geom/polynomial_span.h"

#include <memory>
#include <optional>

namespace cncc::geom {

struct CurveStandIn {
  std::unique_ptr<PiecewisePolynomialCurve> curve;
  double error = 0;
};

// Nothing when a piece needs more than 2^14 spans.
std::optional<CurveStandIn> standInFor(const Curve& curve, double error);

} // namespace cncc::geom
