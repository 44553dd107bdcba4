// The virtual controller against an independent interpreter: plain G-code
// that Fanuc and LinuxCNC read alike (G91 arcs and helices, the drilling
// cycles with G98/G99, pecks with LinuxCNC's fixed 0.254 mm clearance) runs
// through both, and the paths must be the same: every vertex of one on the
// other, and the same feed and rapid lengths (a missing peck retraces a
// line, so only the lengths see it).
#include "linuxcnc_rs274.h"

#include "cncc/backends/controller_profile.h"
#include "cncc/backends/linuxcnc_canon.h"
#include "cncc/backends/virtual_controller.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <limits>
#include <string>
#include <vector>

namespace cncc::backends::sim {
namespace {

struct Polyline {
  std::vector<Eigen::Vector3d> points; // points[0] is the start
  std::vector<bool> rapid;             // per segment
  double feedLength = 0;
  double rapidLength = 0;
};

void addSegment(Polyline& line, const Eigen::Vector3d& end, bool rapid) {
  double length = (end - line.points.back()).norm();
  (rapid ? line.rapidLength : line.feedLength) += length;
  line.points.push_back(end);
  line.rapid.push_back(rapid);
}

Polyline simulatorPolyline(const std::string& program) {
  SimulationOptions options;
  options.peckRetract = 0.254; // LinuxCNC's: 0.010 inch
  options.peckClearance = 0.254;
  SimulationResult result = simulateProgram(program, *findControllerProfile("fanuc"), options);
  EXPECT_FALSE(result.error) << (result.error ? result.error->what() : "");
  Polyline line;
  line.points.push_back(Eigen::Vector3d::Zero());
  for (const ir::MachineEvent& event : flattenPath(result.path, 1e-5).events) {
    if (event.kind == ir::MachineEvent::Kind::Rapid || event.kind == ir::MachineEvent::Kind::Feed) {
      addSegment(line, {event.x, event.y, event.z}, event.kind == ir::MachineEvent::Kind::Rapid);
    }
  }
  return line;
}

Polyline rs274Polyline(const std::string& rs274, const std::string& program) {
  testing::Rs274Run run = testing::runRs274(rs274, program, "T1 P1 D6 ;\n");
  EXPECT_EQ(run.exitCode, 0) << run.errors << run.canon;
  backends::ExecutedPath path = readLinuxcncCanon(run.canon, 1e-5);
  Polyline line;
  line.points.push_back(path.start);
  for (const backends::ExecutedMove& move : path.moves) {
    addSegment(line, move.end, move.rapid);
  }
  return line;
}

double distanceToSegment(const Eigen::Vector3d& point, const Eigen::Vector3d& a,
                         const Eigen::Vector3d& b) {
  Eigen::Vector3d along = b - a;
  double squared = along.squaredNorm();
  double t = squared > 0 ? std::clamp((point - a).dot(along) / squared, 0.0, 1.0) : 0;
  return (a + t * along - point).norm();
}

// The largest distance from a vertex of `from` to the polyline `to`.
double farthestVertex(const Polyline& from, const Polyline& to) {
  double worst = 0;
  for (const Eigen::Vector3d& point : from.points) {
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 1; i < to.points.size(); ++i) {
      nearest = std::min(nearest, distanceToSegment(point, to.points[i - 1], to.points[i]));
    }
    worst = std::max(worst, nearest);
  }
  return worst;
}

void expectSamePath(const std::string& program) {
  CNCC_FIND_RS274(rs274);
  Polyline simulated = simulatorPolyline(program);
  Polyline reference = rs274Polyline(*rs274, program);
  // rs274 prints 4 decimals; the arcs are chords within 1e-5 on both sides.
  constexpr double tolerance = 2e-4;
  EXPECT_LT(farthestVertex(simulated, reference), tolerance) << program;
  EXPECT_LT(farthestVertex(reference, simulated), tolerance) << program;
  EXPECT_NEAR(simulated.feedLength, reference.feedLength, 1e-3) << program;
  EXPECT_NEAR(simulated.rapidLength, reference.rapidLength, 1e-3) << program;
}

TEST(SimAgainstRs274, IncrementalArcsAndHelices) {
  expectSamePath("G21 G17 G90 G94\nG0 X10. Y0. Z2.\nG1 Z0. F300.\n"
                 "G91 G3 X0. Y0. I-10. J0. Z-1.5\n"
                 "G3 X0. Y0. I-10. J0. Z-1.5\n"
                 "G2 X-10. Y10. I-10. J0.\n"
                 "G3 X5. Y5. R5.\n"
                 "G2 X10. Y0. R-5.\n"
                 "G90 G0 Z10.\nM30\n");
}

// Fanuc positions a hole at the current Z and returns by G98/G99 after it;
// LinuxCNC first climbs to the G98 level and feeds G85/G89 out to it. The
// programs keep to what both do alike: a series in G99, a series in G98
// from the initial level, G85/G89 only in G99, R in every block that
// changes the cycle (LinuxCNC does not keep it across cycles, Fanuc does).
TEST(SimAgainstRs274, DrillingCyclesInG99) {
  expectSamePath("G21 G17 G90 G94\nG0 X0. Y0. Z10.\nM3 S1000\n"
                 "G99 G81 X10. Y5. Z-3. R1. F120.\n"
                 "X20.\n"
                 "G82 X30. Z-2. R1. P0.5\n"
                 "G83 X40. Z-9. R1. Q2.5\n"
                 "G73 X50. Z-6.5 R1. Q2.\n"
                 "G85 X60. Z-4. R1.\n"
                 "G89 X70. Z-4. R1. P0.2\n"
                 "G80\nG0 Z10.\nX0. Y0.\nM30\n");
}

TEST(SimAgainstRs274, DrillingCyclesInG98) {
  expectSamePath("G21 G17 G90 G94\nG0 X0. Y0. Z10.\nM3 S1000\n"
                 "G98 G81 X10. Y5. Z-3. R1. F120.\n"
                 "G82 X30. Z-2. R2. P0.5\n"
                 "G83 X40. Z-9. R1. Q2.5\n"
                 "G73 X50. Z-6.5 R1. Q2.\n"
                 "G86 X60. Z-4. R1. P0.\n" // LinuxCNC requires P
                 "G80\nG0 X0. Y0.\nM30\n");
}

TEST(SimAgainstRs274, IncrementalCycles) {
  // G91: R from the initial level, Z from R; X, Y per hole.
  expectSamePath("G21 G17 G90 G94\nG0 X0. Y0. Z10.\n"
                 "G91 G99 G81 X12. Y3. Z-6. R-8. F100.\n"
                 "X12.\n"
                 "X-6. Y10.\n"
                 "G90 G80\nG0 Z10.\nM30\n");
}

} // namespace
} // namespace cncc::backends::sim
