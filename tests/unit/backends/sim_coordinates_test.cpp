// G91 arcs and helices, G52 local coordinates, G68 rotation and G16 polar
// coordinates on the virtual controller.
#include "cncc/backends/controller_profile.h"
#include "cncc/backends/virtual_controller.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace cncc::backends::sim {
namespace {

using ::testing::HasSubstr;

SimulationResult run(const std::string& body) {
  return simulateProgram("%\nO1000\nG90 G00 X0. Y0. Z0. F100.\n" + body + "M30\n%\n",
                         *findControllerProfile("fanuc"));
}

const ExecutedEvent& lastMove(const SimulationResult& result) {
  return result.path.events.back();
}

void expectEnd(const ExecutedEvent& event, double x, double y, double z) {
  EXPECT_NEAR(event.end.x, x, 1e-9);
  EXPECT_NEAR(event.end.y, y, 1e-9);
  EXPECT_NEAR(event.end.z, z, 1e-9);
}

std::string errorOf(const SimulationResult& result) {
  return result.error ? std::string(result.error->what()) : std::string("no error");
}

TEST(SimIncrementalArcs, CentreFromTheStartAndEndFromTheIncrements) {
  SimulationResult result = run("G00 X5. Y5.\nG91 G02 X10. Y-10. I10. J0. Z-1.\n");
  ASSERT_FALSE(result.error) << result.error->what();
  const ExecutedEvent& arc = lastMove(result);
  EXPECT_EQ(arc.kind, ExecutedEvent::Kind::ClockwiseArc);
  expectEnd(arc, 15, -5, -1);
  EXPECT_DOUBLE_EQ(arc.centre.x, 15);
  EXPECT_DOUBLE_EQ(arc.centre.y, 5);
}

TEST(SimIncrementalArcs, FullHelicalTurnsInG91) {
  SimulationResult result = run("G00 X10. Y0.\nG91 G03 X0. Y0. I-10. J0. Z-2.\n"
                                "G03 X0. Y0. I-10. J0. Z-2.\n");
  ASSERT_FALSE(result.error) << result.error->what();
  const ExecutedEvent& second = lastMove(result);
  EXPECT_EQ(second.kind, ExecutedEvent::Kind::CounterclockwiseArc);
  EXPECT_DOUBLE_EQ(second.start.z, -2);
  expectEnd(second, 10, 0, -4);
}

TEST(SimLocalCoordinates, G52ShiftsTheOriginUntilCancelled) {
  SimulationResult result = run("G52 X10. Y20.\nG00 X0. Y0.\nG01 X5.\nG52 X0. Y0.\nG00 X1.\n");
  ASSERT_FALSE(result.error) << result.error->what();
  const auto& events = result.path.events;
  ASSERT_EQ(events.size(), 4u);
  expectEnd(events[1], 10, 20, 0);
  expectEnd(events[2], 15, 20, 0);
  expectEnd(events[3], 1, 20, 0); // Y keeps its work position after the cancel
}

TEST(SimLocalCoordinates, ShiftedCyclesAndRefusals) {
  EXPECT_THAT(errorOf(run("G52 X10. Y20. Z5.\nG52 X0. Y0.\n")), HasSubstr("G52 without Z"));
  EXPECT_THAT(errorOf(run("G52 X10. Y20.\n#100 = #5001\n")), HasSubstr("#5001 while G52"));
  EXPECT_THAT(errorOf(run("G91 G52 X10.\n")), HasSubstr("G52 with G91"));
  SimulationResult drilled = run("G52 X10. Y0. Z-2.\nG00 Z10.\nG99 G81 X1. Y1. Z-1. R1.\nG80\n");
  ASSERT_FALSE(drilled.error) << drilled.error->what();
  // R1 and Z-1 are in the local system: Z-1 and -3 in work coordinates.
  expectEnd(drilled.path.events[drilled.path.events.size() - 2], 11, 1, -3);
  expectEnd(lastMove(drilled), 11, 1, -1);
}

TEST(SimRotation, G68TurnsMovesAndArcCentres) {
  SimulationResult result = run("G68 X0. Y0. R90.\nG01 X10. Y0.\nG91 X5.\nG90\n"
                                "G03 X0. Y15. I-15. J0.\nG69\nG00 X1. Y1.\n");
  ASSERT_FALSE(result.error) << result.error->what();
  const auto& events = result.path.events;
  ASSERT_EQ(events.size(), 5u);
  expectEnd(events[1], 0, 10, 0);
  expectEnd(events[2], 0, 15, 0);
  // Programmed from (15, 0) around the origin to (0, 15): turned by 90.
  EXPECT_EQ(events[3].kind, ExecutedEvent::Kind::CounterclockwiseArc);
  expectEnd(events[3], -15, 0, 0);
  EXPECT_NEAR(events[3].centre.x, 0, 1e-9);
  EXPECT_NEAR(events[3].centre.y, 0, 1e-9);
  expectEnd(events[4], 1, 1, 0);
}

TEST(SimRotation, AroundAPointAndTheRoundingToTheIncrement) {
  SimulationResult result = run("G68 X10. Y10. R30.\nG01 X20. Y10.\n");
  ASSERT_FALSE(result.error) << result.error->what();
  // 10 from the centre at 30 degrees, rounded to 0.001.
  expectEnd(lastMove(result), 18.66, 15, 0);
  EXPECT_THAT(errorOf(run("G68 X0. Y0.\n")), HasSubstr("G68 without R"));
}

TEST(SimPolar, BoltCircleWithG16AndACycle) {
  SimulationResult result = run("G00 Z10.\nG16\nG99 G81 X20. Y45. Z-1. R1.\nY135.\nG80 G15\n");
  ASSERT_FALSE(result.error) << result.error->what();
  const auto& events = result.path.events;
  expectEnd(events[2], 14.142, 14.142, 10);
  expectEnd(events.back(), -14.142, 14.142, 1);
  EXPECT_THAT(errorOf(run("G16 G91 G01 X10. Y10.\n")), HasSubstr("G16 polar coordinates with G91"));
  EXPECT_THAT(errorOf(run("G16 G02 X10. Y90. R10.\n")), HasSubstr("arcs in G16"));
}

} // namespace
} // namespace cncc::backends::sim
