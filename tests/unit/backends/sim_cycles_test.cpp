// Drilling cycles and M98 subprograms on the virtual controller.
#include "cncc/backends/controller_profile.h"
#include "cncc/backends/virtual_controller.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace cncc::backends::sim {
namespace {

using ::testing::HasSubstr;

SimulationOptions options(ControllerFamily family = ControllerFamily::Fanuc) {
  SimulationOptions result;
  result.reading.family = family;
  result.peckRetract = 0.5;
  result.peckClearance = 1;
  return result;
}

// Runs `body` after a move to X0 Y0 Z20 (the initial level) with F100.
SimulationResult run(const std::string& body, const SimulationOptions& settings = options(),
                     const char* profile = "fanuc") {
  return simulateProgram("%\nO1000\nG90 G00 X0. Y0. Z20. F100.\n" + body + "M30\n%\n",
                         *findControllerProfile(profile), settings);
}

struct Move {
  bool rapid;
  double x, y, z;
};

void expectMoves(const SimulationResult& result, const std::vector<Move>& expected) {
  ASSERT_FALSE(result.error) << result.error->line() << ": " << result.error->what();
  std::vector<Move> actual;
  for (std::size_t index = 1; index < result.path.events.size(); ++index) {
    const ExecutedEvent& event = result.path.events[index];
    if (event.kind == ExecutedEvent::Kind::Rapid || event.kind == ExecutedEvent::Kind::Feed) {
      actual.push_back(
          {event.kind == ExecutedEvent::Kind::Rapid, event.end.x, event.end.y, event.end.z});
    }
  }
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t index = 0; index < expected.size(); ++index) {
    EXPECT_EQ(actual[index].rapid, expected[index].rapid) << "move " << index;
    EXPECT_NEAR(actual[index].x, expected[index].x, 1e-9) << "move " << index;
    EXPECT_NEAR(actual[index].y, expected[index].y, 1e-9) << "move " << index;
    EXPECT_NEAR(actual[index].z, expected[index].z, 1e-9) << "move " << index;
  }
}

std::string errorOf(const SimulationResult& result) {
  return result.error ? std::string(result.error->what()) : std::string("no error");
}

TEST(SimCycles, G81ReturnsToTheRPointWithG99AndTheInitialLevelWithG98) {
  expectMoves(run("G99 G81 X10. Y5. Z-3. R2.\nG98 X20.\nG80\n"), {{true, 10, 5, 20},
                                                                  {true, 10, 5, 2},
                                                                  {false, 10, 5, -3},
                                                                  {true, 10, 5, 2}, // G99
                                                                  {true, 20, 5, 2},
                                                                  {false, 20, 5, -3},
                                                                  {true, 20, 5, 20}}); // G98
}

TEST(SimCycles, IncrementalHolesWithRepeats) {
  // G91: R from the initial level, Z from the R point, X per hole; K3.
  expectMoves(run("G91 G99 G81 X10. Z-5. R-18. K3\nG90 G80\n"), {{true, 10, 0, 20},
                                                                 {true, 10, 0, 2},
                                                                 {false, 10, 0, -3},
                                                                 {true, 10, 0, 2},
                                                                 {true, 20, 0, 2},
                                                                 {false, 20, 0, -3},
                                                                 {true, 20, 0, 2},
                                                                 {true, 30, 0, 2},
                                                                 {false, 30, 0, -3},
                                                                 {true, 30, 0, 2}});
}

TEST(SimCycles, PeckDrillingG83BacksOutToR) {
  expectMoves(run("G98 G83 X0. Y0. Z-7. R1. Q3.\nG80\n"),
              {{true, 0, 0, 1},
               {false, 0, 0, -2},
               {true, 0, 0, 1},
               {true, 0, 0, -1}, // clearance 1 above the last depth
               {false, 0, 0, -5},
               {true, 0, 0, 1},
               {true, 0, 0, -4},
               {false, 0, 0, -7},
               {true, 0, 0, 20}});
}

TEST(SimCycles, HighSpeedPeckG73RetractsBySetting) {
  expectMoves(
      run("G99 G73 Z-5. R1. Q3.\nG80\n"),
      {{true, 0, 0, 1}, {false, 0, 0, -2}, {true, 0, 0, -1.5}, {false, 0, 0, -5}, {true, 0, 0, 1}});
}

TEST(SimCycles, BoringFeedsOutAndG86StopsTheSpindle) {
  expectMoves(run("G99 G85 Z-4. R1.\nG80\n"),
              {{true, 0, 0, 1}, {false, 0, 0, -4}, {false, 0, 0, 1}});
  SimulationResult g86 = run("S500 M03\nG98 G86 Z-4. R1.\nG80\n");
  ASSERT_FALSE(g86.error) << g86.error->what();
  int stops = 0;
  for (const ExecutedEvent& event : g86.path.events) {
    stops += event.kind == ExecutedEvent::Kind::Spindle && event.number == 0 ? 1 : 0;
  }
  EXPECT_EQ(stops, 1);
}

TEST(SimCycles, DataIsModalUntilG80OrAMotionCode) {
  // A block with only X drills again with the same R and Z; after G80 an
  // X is a move in the motion mode from before the cycle (G00 here).
  expectMoves(run("G99 G81 X1. Z-1. R1.\nX2.\nG80\nX3.\n"), {{true, 1, 0, 20},
                                                             {true, 1, 0, 1},
                                                             {false, 1, 0, -1},
                                                             {true, 1, 0, 1},
                                                             {true, 2, 0, 1},
                                                             {false, 2, 0, -1},
                                                             {true, 2, 0, 1},
                                                             {true, 3, 0, 1}});
  EXPECT_THAT(errorOf(run("G99 G81 X1. Z-1. R1.\nG80\nG81 X2.\n")), HasSubstr("G81 without R"));
  SimulationResult motion = run("G99 G81 X1. Z-1. R1.\nG00 X5.\n");
  ASSERT_FALSE(motion.error) << motion.error->what();
  EXPECT_DOUBLE_EQ(motion.path.events.back().end.x, 5);
  EXPECT_DOUBLE_EQ(motion.path.events.back().end.z, 1);
}

TEST(SimCycles, RefusedRatherThanGuessed) {
  EXPECT_THAT(errorOf(run("G81 X1. Z-1. R1.\n")), HasSubstr("G98 or G99"));
  EXPECT_THAT(errorOf(run("G99 G76 X1. Z-1. R1. Q1.\n")), HasSubstr("G76 is not simulated"));
  // The back boring and manual-return cycles of G81-G89 are refused by name too.
  EXPECT_THAT(errorOf(run("G99 G87 X1. Z-1. R1. Q1.\n")), HasSubstr("G87 is not simulated"));
  EXPECT_THAT(errorOf(run("G99 G88 X1. Z-1. R1. P1.\n")), HasSubstr("G88 is not simulated"));
  EXPECT_THAT(errorOf(run("G99 G83 X1. Z-1. R1.\n")), HasSubstr("without Q"));
  EXPECT_THAT(errorOf(run("G99 G83 X1. Z-1. R1. Q5\n")), HasSubstr("Q without a decimal point"));
  EXPECT_THAT(errorOf(run("G99 G81 X1. Z2. R1.\n")), HasSubstr("not below its R point"));
  EXPECT_THAT(errorOf(run("G99 G84 X1. Z-2. R1.\n")), HasSubstr("spindle stopped"));
  SimulationOptions unset;
  EXPECT_THAT(errorOf(run("G99 G73 X1. Z-2. R1. Q1.\n", unset)), HasSubstr("Fanuc parameter 5114"));
  EXPECT_THAT(errorOf(run("G99 G81 X1. Z-2. R1. L2\n")), HasSubstr("is K on this control"));
}

TEST(SimCycles, MitsubishiRepeatsWithL) {
  SimulationResult result = run("G91 G99 G81 X10. Z-5. R-18. L2\nG90 G80\n",
                                options(ControllerFamily::Mitsubishi), "m80");
  ASSERT_FALSE(result.error) << result.error->what();
  EXPECT_DOUBLE_EQ(result.path.events.back().end.x, 20);
  EXPECT_THAT(
      errorOf(run("G99 G81 X1. Z-2. R1. K2\n", options(ControllerFamily::Mitsubishi), "m80")),
      HasSubstr("is L on this control"));
}

// M98: the subprogram runs with its caller's locals, L times.
TEST(SimSubprograms, RepeatsShareTheCallersLocals) {
  SimulationResult result = simulateProgram("%\nO1000\n#1 = 0\nM98 P2000 L4\n#100 = #1\nM30\n"
                                            "O2000\n#1 = #1 + 2.5\nM99\n%\n",
                                            *findControllerProfile("fanuc"), options());
  ASSERT_FALSE(result.error) << result.error->what();
  EXPECT_DOUBLE_EQ(*result.commonVariables.at(100), 10);
}

TEST(SimSubprograms, FanucPacksTheRepeatCountInP) {
  std::string text = "%\nO1000\n#1 = 0\nM98 P30020\n#100 = #1\nM30\nO20\n#1 = #1 + 1\nM99\n%\n";
  SimulationResult fanuc = simulateProgram(text, *findControllerProfile("fanuc"), options());
  ASSERT_FALSE(fanuc.error) << fanuc.error->what();
  EXPECT_DOUBLE_EQ(*fanuc.commonVariables.at(100), 3);
  // On the M80, P is the program number, up to 8 digits.
  SimulationResult m80 =
      simulateProgram(text, *findControllerProfile("m80"), options(ControllerFamily::Mitsubishi));
  EXPECT_THAT(errorOf(m80), HasSubstr("no program O30020"));
}

TEST(SimSubprograms, MacroCallsInsideKeepTheirOwnLocals) {
  SimulationResult result = simulateProgram("%\nO1000\n#1 = 5\nM98 P2000\n#100 = #1\nM30\n"
                                            "O2000\nG65 P3000 A1.\n#1 = #1 * 2\nM99\n"
                                            "O3000\n#1 = #1 + 100\nM99\n%\n",
                                            *findControllerProfile("fanuc"), options());
  ASSERT_FALSE(result.error) << result.error->what();
  EXPECT_DOUBLE_EQ(*result.commonVariables.at(100), 10);
}

TEST(SimSubprograms, EndlessRecursionStopsAtTheNestingLimit) {
  SimulationResult result = simulateProgram("%\nO1000\nM98 P2000\nM30\nO2000\nM98 P2000\nM99\n%\n",
                                            *findControllerProfile("fanuc"), options());
  EXPECT_THAT(errorOf(result), HasSubstr("calls nested 11 deep"));
  EXPECT_EQ(result.error->line(), 6);
}

TEST(SimSubprograms, M99PReturnsToABlockOfTheCaller) {
  SimulationResult result =
      simulateProgram("%\nO1000\n#100 = 0\nM98 P2000\n#100 = 1\nN50 #101 = 2\nM30\n"
                      "O2000\nM99 P50\n%\n",
                      *findControllerProfile("fanuc"), options());
  ASSERT_FALSE(result.error) << result.error->what();
  EXPECT_DOUBLE_EQ(*result.commonVariables.at(100), 0); // skipped
  EXPECT_DOUBLE_EQ(*result.commonVariables.at(101), 2);
  SimulationResult missing = simulateProgram("%\nO1000\nM98 P2000\nM30\nO2000\nM99 P60\n%\n",
                                             *findControllerProfile("fanuc"), options());
  EXPECT_THAT(errorOf(missing), HasSubstr("no block N60"));
  SimulationResult repeats = simulateProgram("%\nO1000\nM98 P2000 L2\nN5 M30\nO2000\nM99 P5\n%\n",
                                             *findControllerProfile("fanuc"), options());
  EXPECT_THAT(errorOf(repeats), HasSubstr("repeats left"));
}

} // namespace
} // namespace cncc::backends::sim
