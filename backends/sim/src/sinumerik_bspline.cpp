// The B spline of a BSPLINE group (sinumerik_controller.h) and the dense
// sampling of the curves the virtual Sinumerik cuts.
#include "cncc/backends/sinumerik_controller.h"

#include "sinumerik_sampling.h"

#include "cncc/geom/geometry_error.h"
#include "cncc/geom/knot_vector.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace cncc::backends::sinumerik {

geom::NurbsCurve bsplineOfBlocks(const Eigen::Vector3d& start, int degree,
                                 const std::vector<Eigen::Vector3d>& points,
                                 const std::vector<double>& weights,
                                 const std::vector<double>& intervals) {
  if (degree != 2 && degree != 3) {
    throw geom::GeometryError(fmt::format("SD={} (2 or 3)", degree));
  }
  if (points.size() < std::size_t(degree)) {
    throw geom::GeometryError(fmt::format("a B spline of degree {} needs at least {} points "
                                          "after its start, this one has {}",
                                          degree, degree, points.size()));
  }
  // u_0 = u_1 = 0, u_{i+1} = u_i + PL_i (i = 1..n), then p more copies of
  // u_{n+1}: the first p - 1 intervals must keep u_2..u_p at 0.
  for (int i = 0; i + 1 < degree; ++i) {
    if (intervals[std::size_t(i)] != 0.0) {
      throw geom::GeometryError(fmt::format(
          "PL of point {} lies inside the clamped start of a degree {} spline and must be 0", i + 1,
          degree));
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
  return geom::NurbsCurve(geom::KnotVector(std::move(knots), degree), std::move(controlPoints),
                          std::move(allWeights));
}

geom::CurveSamples sampleDensely(const geom::Curve& curve, double tolerance) {
  constexpr int kProbes = 32;
  constexpr double kMargin = 2.0;
  geom::CurveSamples samples;
  std::vector<double> breakpoints = curve.breakpoints();
  samples.parameters.push_back(breakpoints.front());
  for (std::size_t piece = 0; piece + 1 < breakpoints.size(); ++piece) {
    double t0 = breakpoints[piece];
    double t1 = breakpoints[piece + 1];
    double bend = 0;
    for (int i = 0; i <= kProbes; ++i) {
      double t = t0 + (t1 - t0) * i / kProbes;
      bend = std::max(bend, curve.secondDerivative(std::min(t, t1)).norm());
    }
    double step = bend > 0 ? std::sqrt(8.0 * tolerance / (kMargin * bend)) : (t1 - t0);
    double count = std::clamp(std::ceil((t1 - t0) / step), 1.0, 1e7);
    auto steps = static_cast<std::size_t>(count);
    for (std::size_t i = 1; i <= steps; ++i) {
      samples.parameters.push_back(i == steps ? t1 : t0 + (t1 - t0) * double(i) / double(steps));
    }
  }
  for (double t : samples.parameters) {
    samples.points.push_back(curve.point(t));
  }
  return samples;
}

} // namespace cncc::backends::sinumerik
