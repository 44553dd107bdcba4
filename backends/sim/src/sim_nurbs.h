// The NURBS the virtual controller is collecting from G06.2 blocks
// (sim_nurbs.cpp): control points, weights and knots, until a block without
// K ends it and the curve is executed.
#pragma once

#include <Eigen/Core>

#include <vector>

namespace cncc::backends::sim {

struct NurbsInProgress {
  bool active = false;
  bool highSpeedMode = false; // G05 P10000 (Mitsubishi: required before G06.2)
  int order = 4;
  int firstLine = 0;
  std::vector<Eigen::Vector3d> points;
  std::vector<double> weights;
  std::vector<double> knots;
  bool knotsOnly = false; // a K-only block came: no more control points
};

} // namespace cncc::backends::sim
