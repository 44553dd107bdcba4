// Cutter radius compensation G41/G42 on the virtual controller: the
// executed path is the tool centre's, offset by the D register's radius,
// with Fanuc's type A start-up and cancel.
#include "cncc/backends/controller_profile.h"
#include "cncc/backends/virtual_controller.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace cncc::backends::sim {
namespace {

using ::testing::HasSubstr;

SimulationOptions withRadius(double radius) {
  SimulationOptions options;
  options.toolRadii[1] = radius;
  return options;
}

SimulationResult run(const std::string& body, const SimulationOptions& options = withRadius(2),
                     const char* profile = "fanuc") {
  return simulateProgram("%\nO1000\nG90 G00 X-10. Y-10. Z5.\nG01 Z-1. F100.\n" + body +
                             "G00 Z5.\nM30\n%\n",
                         *findControllerProfile(profile), options);
}

struct Step {
  double x, y;
};

// The end points of the moves after the plunge, in order.
std::vector<Step> endPoints(const SimulationResult& result) {
  std::vector<Step> points;
  for (std::size_t index = 2; index < result.path.events.size(); ++index) {
    const ExecutedEvent& event = result.path.events[index];
    if (event.kind != ExecutedEvent::Kind::Spindle &&
        event.kind != ExecutedEvent::Kind::ToolChange) {
      points.push_back({event.end.x, event.end.y});
    }
  }
  return points;
}

void expectPath(const SimulationResult& result, const std::vector<Step>& expected) {
  ASSERT_FALSE(result.error) << result.error->line() << ": " << result.error->what();
  std::vector<Step> actual = endPoints(result);
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t index = 0; index < expected.size(); ++index) {
    EXPECT_NEAR(actual[index].x, expected[index].x, 1e-9) << "move " << index;
    EXPECT_NEAR(actual[index].y, expected[index].y, 1e-9) << "move " << index;
  }
}

TEST(SimCompensation, OutsideOfASquareClockwiseWithG41) {
  // Clockwise round the square (0,0)-(20,20): the left is outside.
  SimulationResult result = run("G41 D1 G01 X0. Y0.\n"
                                "Y20.\n"
                                "X20.\n"
                                "Y0.\n"
                                "X0.\n"
                                "G40 X-10. Y-10.\n");
  expectPath(result, {{-2, 0},  // start-up: normal to the first side at its start
                      {-2, 22}, // right-angle outer corners meet at the intersection
                      {22, 22},
                      {22, -2},
                      {0, -2},      // the last side ends normal to itself
                      {-10, -10},   // cancel: back to the programmed point
                      {-10, -10}}); // G00 Z5.
}

TEST(SimCompensation, InsideOfTheSameSquareWithG42) {
  SimulationResult result = run("G42 D1 G01 X0. Y0.\n"
                                "Y20.\n"
                                "X20.\n"
                                "Y0.\n"
                                "X0.\n"
                                "G40 X-10. Y-10.\n");
  expectPath(result, {{2, 0}, {2, 18}, {18, 18}, {18, 2}, {0, 2}, {-10, -10}, {-10, -10}});
}

TEST(SimCompensation, NegativeRadiusSwapsTheSide) {
  SimulationResult result = run("G41 D1 G01 X0. Y0.\nY20.\nG40 X-10.\n", withRadius(-2));
  expectPath(result, {{2, 0}, {2, 20}, {-10, 20}, {-10, 20}});
}

TEST(SimCompensation, RegisterZeroAndAMissingRegister) {
  SimulationResult zero = run("G41 D0 G01 X0. Y0.\nY20.\nG40 X-10.\n");
  expectPath(zero, {{0, 0}, {0, 20}, {-10, 20}, {-10, 20}});
  SimulationResult missing = run("G41 D7 G01 X0. Y0.\nY20.\nG40 X-10.\n");
  ASSERT_TRUE(missing.error);
  EXPECT_THAT(missing.error->what(), HasSubstr("--tool-radius 7=R"));
  SimulationResult without = run("G41 G01 X0. Y0.\n");
  ASSERT_TRUE(without.error);
  EXPECT_THAT(without.error->what(), HasSubstr("G41 without D"));
}

TEST(SimCompensation, HelicalCircleInsideAHole) {
  // From the hole's centre: start-up to the circle, one full helical turn
  // counterclockwise (the left is inside: radius 10 - 2), cancel back.
  SimulationResult result = run("G00 X0. Y0.\n"
                                "G41 D1 G01 X10. Y0.\n"
                                "G03 X10. Y0. I-10. J0. Z-3.\n"
                                "G40 G01 X0. Y0.\n");
  expectPath(result, {{0, 0}, {8, 0}, {8, 0}, {0, 0}, {0, 0}});
  const ExecutedEvent& circle = result.path.events[4];
  EXPECT_EQ(circle.kind, ExecutedEvent::Kind::CounterclockwiseArc);
  EXPECT_DOUBLE_EQ(circle.start.z, -1);
  EXPECT_DOUBLE_EQ(circle.end.z, -3);
  EXPECT_NEAR(std::hypot(circle.start.x - circle.centre.x, circle.start.y - circle.centre.y), 8,
              1e-9);
}

TEST(SimCompensation, TangentEntryIntoAFullCircleCutsItOnce) {
  // Entry and exit arcs tangent to the circle: the compensated circle's ends
  // meet up to rounding, which must not make it a second turn.
  SimulationResult result = run("G00 X0. Y0.\n"
                                "G41 D1 G01 X5. Y-5.\n"
                                "G03 X10. Y0. R5.\n"
                                "G03 X10. Y0. I-10. J0.\n"
                                "G03 X5. Y5. R5.\n"
                                "G40 G01 X0. Y0.\n");
  ASSERT_FALSE(result.error) << result.error->what();
  int circles = 0;
  for (const ExecutedEvent& event : result.path.events) {
    if (event.kind == ExecutedEvent::Kind::CounterclockwiseArc) {
      bool fullTurn = event.start.x == event.end.x && event.start.y == event.end.y;
      circles += fullTurn ? 1 : 0;
      if (fullTurn) {
        EXPECT_NEAR(event.start.x, 8, 1e-9); // radius 10 - 2
        EXPECT_NEAR(event.start.y, 0, 1e-9);
      }
    }
  }
  EXPECT_EQ(circles, 1);
  // The entry arc, radius 5 - 2 around (5, 0), ends on the circle.
  expectPath(result, {{0, 0}, {5, -3}, {8, 0}, {8, 0}, {5, 3}, {0, 0}, {0, 0}});
}

TEST(SimCompensation, APlungeBetweenBlocksRunsAtTheCorner) {
  SimulationResult result = run("G00 Z5.\n"
                                "G41 D1 G00 X0. Y0.\n"
                                "G01 Z-2.\n"
                                "Y20.\n"
                                "G40 X-10.\n");
  ASSERT_FALSE(result.error) << result.error->what();
  // After the start-up at (-2, 0) the plunge goes straight down there.
  const ExecutedEvent& plunge = result.path.events[4];
  EXPECT_EQ(plunge.kind, ExecutedEvent::Kind::Feed);
  EXPECT_DOUBLE_EQ(plunge.start.x, -2);
  EXPECT_DOUBLE_EQ(plunge.end.x, -2);
  EXPECT_DOUBLE_EQ(plunge.end.z, -2);
}

TEST(SimCompensation, RefusedRatherThanGuessed) {
  auto errorOf = [](const std::string& body) {
    SimulationResult result = run(body);
    return result.error ? std::string(result.error->what()) : std::string("no error");
  };
  EXPECT_THAT(errorOf("G41 D1 G02 X0. Y0. I5. J5.\n"), HasSubstr("starts on an arc"));
  EXPECT_THAT(errorOf("G41 D1 G01 X0. Y0.\nY20.\nG40 G02 X10. Y30. I10. J0.\n"),
              HasSubstr("G40 cancels on an arc"));
  EXPECT_THAT(errorOf("G41 D1 G01 X0. Y0.\nY20.\nG40\n"), HasSubstr("without an X or Y move"));
  EXPECT_THAT(errorOf("G41 D1 G01 X0. Y0.\nZ-2.\nM08\nY20.\nG40 X-10.\n"),
              HasSubstr("two blocks in a row"));
  EXPECT_THAT(errorOf("G41 D1 G01 X0. Y0.\nY20.\nX20.\n"), HasSubstr("compensation on"));
  EXPECT_THAT(errorOf("G41 D1 G01 X0. Y0.\nY20.\nG42 X20.\n"), HasSubstr("changing G41/G42"));
}

TEST(SimCompensation, ToolTooLargeForTheArcIsAnAlarm) {
  // A counterclockwise arc of radius 1 with the 2 mm tool on its inside.
  SimulationResult result = run("G41 D1 G01 X0. Y0.\nG03 X2. Y0. I1. J0.\nG40 G01 X10.\n");
  ASSERT_TRUE(result.error);
  EXPECT_EQ(result.error->line(), 6);
  EXPECT_THAT(result.error->what(), HasSubstr("smaller than the tool radius"));
}

TEST(SimCompensation, OvercutOfAShortStepIsAnAlarm) {
  // A 1 mm step inside a pocket corner with a 2 mm tool: the compensated
  // step runs backwards.
  SimulationResult result = run("G42 D1 G01 X0. Y0.\nY20.\nX1.\nY19.\nX20.\nG40 X30.\n");
  ASSERT_TRUE(result.error);
  EXPECT_THAT(result.error->what(), HasSubstr("interference"));
}

// Clockwise round the square (0,0)-(20,20) with G41 (outside) and G39 at
// each corner: the tool centre goes round it on arcs of the radius.
const std::vector<Step> squareWithCornerArcs = {
    {-2, 0},  {-2, 20}, {0, 22}, // the side, the arc about (0, 20)
    {20, 22}, {22, 20}, {22, 0}, {20, -2}, {0, -2}, {-10, -10}, {-10, -10}};

void expectCornerArcsClockwise(const SimulationResult& result) {
  expectPath(result, squareWithCornerArcs);
  const ExecutedEvent& arc = result.path.events[4]; // after the rapid, plunge, start-up, side
  EXPECT_EQ(arc.kind, ExecutedEvent::Kind::ClockwiseArc);
  EXPECT_NEAR(arc.centre.x, 0, 1e-12);
  EXPECT_NEAR(arc.centre.y, 20, 1e-12);
  EXPECT_NEAR(arc.start.x, -2, 1e-12);
  EXPECT_NEAR(arc.start.y, 20, 1e-12);
}

TEST(SimCompensation, FanucG39TowardsIAndJGoesRoundTheCorner) {
  expectCornerArcsClockwise(run("G41 D1 G01 X0. Y0.\n"
                                "Y20.\n"
                                "G39 I10. J0.\n"
                                "X20.\n"
                                "G39 I0. J-10.\n"
                                "Y0.\n"
                                "G39 I-1. J0.\n"
                                "X0.\n"
                                "G40 X-10. Y-10.\n"));
}

TEST(SimCompensation, FanucG39WithoutIAndJTurnsToTheNextBlock) {
  expectCornerArcsClockwise(run("G41 D1 G01 X0. Y0.\nY20.\nG39\nX20.\nG39\nY0.\nG39\nX0.\n"
                                "G40 X-10. Y-10.\n"));
}

TEST(SimCompensation, FanucG39TowardsAnotherDirectionEndsThereThenJoins) {
  // The arc ends normal to I J (45 degrees), then a line to where the next
  // block's offset starts.
  SimulationResult result = run("G41 D1 G01 X0. Y0.\nY20.\nG39 I1. J1.\nX20.\nG40 X30. Y30.\n");
  double half = std::sqrt(2.0);
  expectPath(result,
             {{-2, 0}, {-2, 20}, {-half, 20 + half}, {0, 22}, {20, 22}, {30, 30}, {30, 30}});
}

TEST(SimCompensation, MitsubishiG39GoesOnTheMoveEndingAtTheCorner) {
  expectCornerArcsClockwise(run("G41 D1 G01 X0. Y0.\n"
                                "G39 Y20.\n"
                                "G39 X20.\n"
                                "G39 G01 Y0.\n"
                                "X0.\n"
                                "G40 X-10. Y-10.\n",
                                withRadius(2), "m80"));
}

TEST(SimCompensation, CornerArcRefusedRatherThanGuessed) {
  auto errorOf = [](const std::string& body, const char* profile = "fanuc") {
    SimulationResult result = run(body, withRadius(2), profile);
    return result.error ? std::string(result.error->what()) : std::string("no error");
  };
  // G42 keeps the tool inside the clockwise square: its corners are concave.
  EXPECT_THAT(errorOf("G42 D1 G01 X0. Y0.\nY20.\nG39\nX20.\nG40 X30.\n"),
              HasSubstr("inside corner"));
  EXPECT_THAT(errorOf("G01 X0. Y0.\nG39 I1. J0.\nX5.\n"), HasSubstr("needs G41/G42 on"));
  EXPECT_THAT(errorOf("G41 D1 G01 X0. Y0.\nG39\nY20.\nG40 X-10.\n"), HasSubstr("needs G41/G42 on"));
  EXPECT_THAT(errorOf("G41 D1 G01 X0. Y0.\nY20.\nG39 X5. Y20.\nX20.\nG40 X30.\n"),
              HasSubstr("no move in a G39 block"));
  EXPECT_THAT(errorOf("G41 D1 G01 X0. Y0.\nY20.\nG39\nG40 X-10.\n"),
              HasSubstr("before the cancel move"));
  EXPECT_THAT(errorOf("G41 D1 G01 X0. Y0.\nY20.\nG39\nX20.\nG40 X30.\n", "m80"),
              HasSubstr("goes on the move"));
  EXPECT_THAT(errorOf("G41 D1 G01 X0. Y0.\nY20.\nG39 Z-2.\nX20.\nG40 X30.\n", "m80"),
              HasSubstr("compensated move in the plane"));
}

} // namespace
} // namespace cncc::backends::sim
