#include "cncc/geom/controller_bspline.h"

#include "cncc/geom/geometry_error.h"
#include "cncc/geom/knot_vector.h"

#include <string>

namespace cncc::geom {

NurbsCurve bsplineOfBlocks(const Eigen::Vector3d& start, int degree,
                           const std::vector<Eigen::Vector3d>& points,
                           const std::vector<double>& weights,
                           const std::vector<double>& intervals) {
  if (degree != 2 && degree != 3) {
    throw GeometryError("SD=" + std::to_string(degree) + " (2 or 3)");
  }
  if (points.size() < std::size_t(degree)) {
    throw GeometryError("a B spline of degree " + std::to_string(degree) + " needs at least " +
                        std::to_string(degree) + " points after its start, this one has " +
                        std::to_string(points.size()));
  }
  if (weights.size() != points.size() || intervals.size() != points.size()) {
    throw GeometryError("a B spline needs one PW and one PL per point");
  }
  // u_0 = u_1 = 0, u_{i+1} = u_i + PL_i (i = 1..n), then p more copies of
  // u_{n+1}: the first p - 1 intervals must keep u_2..u_p at 0.
  for (int i = 0; i + 1 < degree; ++i) {
    if (intervals[std::size_t(i)] != 0.0) {
      throw GeometryError("PL of point " + std::to_string(i + 1) +
                          " lies inside the clamped start of a degree " + std::to_string(degree) +
                          " spline and must be 0");
    }
  }
  std::vector<double> knots{0.0, 0.0};
  for (std::size_t i = 0; i < points.size(); ++i) {
    knots.push_back(knots.back() + intervals[i]);
  }
  for (int k = 0; k < degree; ++k) {
    knots.push_back(knots.back());
  }
  std::vector<Eigen::Vector3d> controlPoints{start};
  controlPoints.insert(controlPoints.end(), points.begin(), points.end());
  std::vector<double> allWeights{1.0};
  allWeights.insert(allWeights.end(), weights.begin(), weights.end());
  return NurbsCurve(KnotVector(std::move(knots), degree), std::move(controlPoints),
                    std::move(allWeights));
}

} // namespace cncc::geom
