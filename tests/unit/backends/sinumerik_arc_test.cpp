// G2/G3 on the virtual Sinumerik: I J centres, CR= radii (negative: over
// 180 degrees) and helices with TURN= extra turns.
#include "cncc/backends/sinumerik_controller.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace cncc::backends::sinumerik {
namespace {

SinumerikRun runOk(const std::string& body) {
  SinumerikRun run = runSinumerikProgram("G0 X10 Y0 Z0\nG1 F100\n" + body + "M30\n");
  EXPECT_FALSE(run.error) << (run.error ? run.error->what() : "");
  return run;
}

// The largest distance of the moves' end points from `centre` minus `radius`.
double radiusError(const SinumerikRun& run, double cx, double cy, double radius) {
  double worst = 0;
  for (const ExecutedSinumerikMove& move : run.moves) {
    worst = std::max(worst, std::abs(std::hypot(move.end.x() - cx, move.end.y() - cy) - radius));
  }
  return worst;
}

TEST(SinumerikArcs, RadiusFormTakesTheShortArcOrTheLongOne) {
  // From (10, 0) to (0, 10) with radius 10: counterclockwise around the
  // origin for CR=10, around (10, 10) the long way for CR=-10.
  SinumerikRun shortArc = runOk("G3 X0 Y10 CR=10\n");
  EXPECT_LT(radiusError(shortArc, 0, 0, 10), 1e-9);
  SinumerikRun longArc = runOk("G3 X0 Y10 CR=-10\n");
  EXPECT_LT(radiusError(longArc, 10, 10, 10), 1e-9);
  // The long way, 270 degrees, passes (20, 10) and (10, 20).
  double rightmost = 0;
  for (const ExecutedSinumerikMove& move : longArc.moves) {
    rightmost = std::max(rightmost, move.end.x());
  }
  EXPECT_NEAR(rightmost, 20, 1e-3);
  for (const ExecutedSinumerikMove& move : shortArc.moves) {
    EXPECT_LE(move.end.x(), 10 + 1e-9);
  }
  ASSERT_FALSE(longArc.moves.empty());
  EXPECT_TRUE(longArc.moves.back().end.isApprox(Eigen::Vector3d(0, 10, 0)));
}

TEST(SinumerikArcs, TurnAddsFullTurnsAndSpreadsTheHelix) {
  // A full circle (end = start) with 2 more turns: 3 turns down to Z-6.
  SinumerikRun run = runOk("G2 X10 Y0 Z-6 I-10 J0 TURN=2\n");
  EXPECT_LT(radiusError(run, 0, 0, 10), 1e-9);
  int atStart = 0;
  for (const ExecutedSinumerikMove& move : run.moves) {
    if (std::abs(move.end.x() - 10) < 1e-9 && std::abs(move.end.y()) < 1e-9) {
      ++atStart;
      EXPECT_NEAR(move.end.z(), -2.0 * atStart, 1e-9);
    }
  }
  EXPECT_EQ(atStart, 3);
}

TEST(SinumerikArcs, BadArcsNameTheProblem) {
  auto errorOf = [](const std::string& body) {
    SinumerikRun run = runSinumerikProgram("G0 X10 Y0 Z0\nG1 F100\n" + body + "M30\n");
    return run.error ? std::string(run.error->what()) : std::string("no error");
  };
  EXPECT_NE(errorOf("G3 X0 Y10 CR=2\n").find("shorter than half the chord"), std::string::npos);
  EXPECT_NE(errorOf("G3 X0 Y10 CR=10 I-10\n").find("not both"), std::string::npos);
  EXPECT_NE(errorOf("G1 X0 Y10 CR=10\n").find("belong in a G2 or G3"), std::string::npos);
  EXPECT_NE(errorOf("G2 X10 Y0 I-10 TURN=1.5\n").find("whole number"), std::string::npos);
}

} // namespace
} // namespace cncc::backends::sinumerik
