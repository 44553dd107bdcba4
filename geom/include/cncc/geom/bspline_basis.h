#pragma once

#include "cncc/geom/knot_vector.h"

#include <Eigen/Core>

namespace cncc::geom {

/// B-spline basis values N_{span-p+j, p}(t), j = 0..p (the only non-zero ones in the span).
using BasisValues = Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, kMaxDegree + 1, 1>;

/// Row k holds the k-th derivatives of the p + 1 non-zero basis functions.
using BasisDerivatives = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor,
                                       kMaxDegree + 1, kMaxDegree + 1>;

/// The non-zero basis functions at t in `span` (The NURBS Book A2.2, triangular scheme).
/// `span` must be knots.findSpan(t) or a span whose polynomial piece is wanted at t.
BasisValues basisFunctions(const KnotVector& knots, int span, double t);

/// The non-zero basis functions and their derivatives up to `order` (<= p; higher
/// derivatives of a degree-p piece are zero and are returned as such up to kMaxDegree)
/// at t in `span` (The NURBS Book A2.3). Result has order + 1 rows and p + 1 columns.
BasisDerivatives basisFunctionDerivatives(const KnotVector& knots, int span, double t, int order);

} // namespace cncc::geom
