// Weights of a NURBS that leave its curve as it is (The NURBS Book, 6.1 and
// the reparametrisation of NURBS): scaling every weight by one factor
// changes nothing, and the linear-rational (Moebius) map of its domain
// [a, b] onto itself
//
//   x = lambda y / ((1 - y) + lambda y),   x, y the parameters scaled to [0, 1]
//
// changes the weights' ratios: the knots become y(x_k) and each weight w_i
// is multiplied by the product of D(y) = (1 - y) + lambda y over its p
// knots y_{i+1} .. y_{i+p} (the homogeneous curve D(y)^p (w P, w)(x(y)) is a
// polynomial spline in y with those control points). The points are kept;
// lambda > 0.
#pragma once

#include "cncc/geom/nurbs_curve.h"

#include <optional>

namespace cncc::geom {

// The same curve over the same domain, its parameter mapped as above.
NurbsCurve reparametrised(const NurbsCurve& curve, double lambda);

// The new parameter y (in the domain) of the old parameter t.
double reparametrisedParameter(const NurbsCurve& curve, double lambda, double t);

struct WeightRange {
  double lowest = 0;  // the smallest weight allowed, > 0
  double highest = 0; // the largest
};

// The curve (clamped) with its first weight 1 and every weight within
// `range`: scaled as it is when that fits, else reparametrised with the
// lambda that keeps its smallest weight largest (printed in fixed steps, it
// keeps most of its digits), if one fits.
struct FittingWeights {
  NurbsCurve curve;
  double lambda = 1; // 1: only scaled
};
std::optional<FittingWeights> weightsWithin(const NurbsCurve& curve, WeightRange range);

} // namespace cncc::geom
