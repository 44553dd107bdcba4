// The B spline of a Sinumerik BSPLINE group, as the program's numbers give
// it: the control points are the position before its first block followed
// by one point per block; with degree p (SD, 2 or 3) and n programmed
// points the knots are clamped: p + 1 zeros, then u_{i+1} = u_i + PL_i for
// the blocks i = 1..n, then p more copies of the last. The first p - 1
// intervals lie inside the clamped start and must be 0. The weight of the
// start point is 1; PW is the weight of the block's point. The virtual
// controller and the IR's move.spline build it so.
#pragma once

#include "cncc/geom/nurbs_curve.h"

#include <Eigen/Core>

#include <vector>

namespace cncc::geom {

// Throws GeometryError when the numbers do not make one.
NurbsCurve bsplineOfBlocks(const Eigen::Vector3d& start, int degree,
                           const std::vector<Eigen::Vector3d>& points,
                           const std::vector<double>& weights,
                           const std::vector<double>& intervals);

} // namespace cncc::geom
