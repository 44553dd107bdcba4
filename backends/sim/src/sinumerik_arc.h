// G2/G3 on the virtual Sinumerik in the XY plane: the centre from I J
// (incremental from the start) or from the radius CR= (positive: at most 180
// degrees, negative: more), Z along for a helix, TURN= full turns more
// before the end point. The arc comes back as chords.
#pragma once

#include <Eigen/Core>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace cncc::backends::sinumerik {

struct ProgrammedArc {
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
  std::array<std::optional<double>, 2> centre; // I J
  std::optional<double> radius;                // CR=
  int turns = 0;                               // TURN=
  bool clockwise = false;
};

// The chord end points (the last is the arc's end) within `tolerance` of the
// arc; `problem` set and empty points when the arc cannot be cut.
// At most `maximumPoints` points: an arc that needs more is a `problem`
// found before any is computed.
std::vector<Eigen::Vector3d> arcChordPoints(const ProgrammedArc& arc, double tolerance,
                                            std::size_t maximumPoints, std::string& problem);

} // namespace cncc::backends::sinumerik
