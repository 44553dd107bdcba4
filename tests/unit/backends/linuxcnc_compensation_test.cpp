// Cutter radius compensation in the virtual controller's LinuxCNC dialect:
// G41/G42 D<tool> with the tool table's radius (LinuxcncRunOptions), run
// through sim::RadiusCompensation with LinuxCNC's entry move and arcs about
// outside corners (the same moves rs274 reports for this program, as
// tests/golden/sim/linuxcnc_compensation.ngc checks against it).
#include "cncc/backends/linuxcnc_controller.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace cncc::backends::sim {
namespace {

using ::testing::HasSubstr;

LinuxcncRun run(const std::string& body, std::map<int, double> radii = {{1, 3}}) {
  LinuxcncRunOptions options;
  options.toolRadii = std::move(radii);
  return runLinuxcncProgram(
      "G21 G17 G90 G40\nG0 X-10 Y-10 Z5\nG1 Z-1 F100\n" + body + "G0 Z5\nM2\n", options);
}

struct Expected {
  LinuxcncMove::Kind kind;
  double x, y;
  double centreX = 0, centreY = 0;
};

void expectMoves(const LinuxcncRun& result, const std::vector<Expected>& expected) {
  ASSERT_FALSE(result.error) << result.error->line() << ": " << result.error->what();
  ASSERT_EQ(result.moves.size(), expected.size() + 2); // after the rapid and the plunge
  for (std::size_t index = 0; index < expected.size(); ++index) {
    const LinuxcncMove& move = result.moves[index + 2];
    EXPECT_EQ(move.kind, expected[index].kind) << "move " << index;
    EXPECT_NEAR(move.end.x, expected[index].x, 1e-9) << "move " << index;
    EXPECT_NEAR(move.end.y, expected[index].y, 1e-9) << "move " << index;
    if (move.kind == LinuxcncMove::Kind::Arc) {
      EXPECT_EQ(move.turns, -1) << "move " << index; // clockwise round the outside
      EXPECT_NEAR(move.centre.x, expected[index].centreX, 1e-9) << "move " << index;
      EXPECT_NEAR(move.centre.y, expected[index].centreY, 1e-9) << "move " << index;
    }
  }
}

constexpr auto feed = LinuxcncMove::Kind::Feed;
constexpr auto arc = LinuxcncMove::Kind::Arc;
constexpr auto traverse = LinuxcncMove::Kind::Traverse;

TEST(LinuxcncCompensation, ToolTableRadiusRoundASquare) {
  // Clockwise with G41: the entry goes to where its offset meets the first
  // side's, the corners are arcs of radius 3 about them.
  double entryY = 6 / std::sqrt(2.0) - 3;
  expectMoves(run("G41 D1 G1 X0 Y0\nY20\nX20\nY0\nX0\nG40 X-10 Y-10\n"), {{feed, -3, entryY},
                                                                          {feed, -3, 20},
                                                                          {arc, 0, 23, 0, 20},
                                                                          {feed, 20, 23},
                                                                          {arc, 23, 20, 20, 20},
                                                                          {feed, 23, 0},
                                                                          {arc, 20, -3, 20, 0},
                                                                          {feed, 0, -3},
                                                                          {feed, -10, -10},
                                                                          {traverse, -10, -10}});
}

TEST(LinuxcncCompensation, DiameterOfDynamicCompensation) {
  // G41.1 D4: radius 2, whatever the tool table holds.
  LinuxcncRun result = run("G41.1 D4 G1 X0 Y0\nY20\nX20\nG40 X30 Y30\n", {});
  ASSERT_FALSE(result.error) << result.error->what();
  ASSERT_GE(result.moves.size(), 5u);
  EXPECT_NEAR(result.moves[2].end.x, -2, 1e-9); // the entry
  EXPECT_NEAR(result.moves[3].end.x, -2, 1e-9); // the first side
  EXPECT_NEAR(result.moves[3].end.y, 20, 1e-9);
  EXPECT_NEAR(result.moves[4].end.y, 22, 1e-9); // round its end
}

TEST(LinuxcncCompensation, RefusedRatherThanGuessed) {
  auto errorOf = [](const std::string& body) {
    LinuxcncRun result = run(body);
    return result.error ? std::string(result.error->what()) : std::string("no error");
  };
  EXPECT_THAT(errorOf("G41 D2 G1 X0 Y0\nY20\nG40 X-10\n"), HasSubstr("radius of tool 2"));
  EXPECT_THAT(errorOf("G41 G1 X0 Y0\nY20\nG40 X-10\n"), HasSubstr("G41 without D"));
  EXPECT_THAT(errorOf("G1 D1 X0 Y0\n"), HasSubstr("D without G41"));
  EXPECT_THAT(errorOf("G41 D1 G1 X0 Y0\nY20\nX20\n"), HasSubstr("compensation on"));
  EXPECT_THAT(errorOf("G41 D1 G1 X0 Y0\nG2 X0 Y0 I5 J0 P2\nG40 X-10\n"),
              HasSubstr("several turns"));
}

} // namespace
} // namespace cncc::backends::sim
