#pragma once

// Internal entry to the C spline model for searches that rebuild the spline from a
// point on: the tangent at the first point is given as a derivative, not a direction.

#include "cncc/geom/interpolating_splines.h"

#include <optional>

namespace cncc::geom::detail {

/// cSplineTangents, with the derivative at points[0] fixed to `startDerivative` when
/// given (the start transition is then ignored).
std::vector<Eigen::Vector3d>
cSplineTangentsFrom(const std::vector<Eigen::Vector3d>& points,
                    const SplineTransitions& transitions, const CSplineOptions& options,
                    const std::optional<Eigen::Vector3d>& startDerivative);

} // namespace cncc::geom::detail
