// Walked regions of a lap cut in steps: a region the entry walks ends in
// curve.walk (its point and the step from its parameter to the next), the
// walk goes from the region's start to min(u + step, end) while u is below
// the end, and expand-controller-loops writes it as a loop advancing by
// loop.next that runs the same points.
#include "curve_lap_fixtures.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

namespace cncc::ir {
namespace {

using curve_lap_test::countOf;
using curve_lap_test::expandedPath;
using curve_lap_test::movesOf;
using curve_lap_test::parsed;
using curve_lap_test::replaced;
using ::testing::Contains;
using ::testing::HasSubstr;

// A line along x, 10 long over u in 0 .. 1, walked by a step that grows
// with u: 0.1 + 0.4 u (a parameter s scales it).
constexpr std::string_view walkText = R"(func @walk(s = 1) {
  curve @0 steps 0 over 0 .. 1 {
    piece at 0 over 0 .. 1
    counts 10
    walks 0
  }
  %0 = param s
  %1 = const 0
  %2 = const 100
  %3 = const -1
  %4 = const 10
  %5 = const 0.1
  %6 = const 0.4
  move.rapid %1, %1, %1
  %7 = curve.lap @0, %3, %3, %2 {
    %8 = mul %4, %7
    %9 = mul %6, %7
    %10 = add %5, %9
    %11 = mul %0, %10
    curve.walk %8, %1, %1, %11
  }
}
)";

// The parameters the walk reaches, as the walk computes them.
std::vector<double> walkedParameters(double scale) {
  std::vector<double> parameters;
  for (double u = 0; u < 1;) {
    u = std::min(u + scale * (0.1 + 0.4 * u), 1.0);
    parameters.push_back(u);
  }
  return parameters;
}

TEST(CurveLapWalk, AnEntryPrintsAndParsesWithItsWalks) {
  Function function = parsed(walkText);
  EXPECT_EQ(function.curves[0].walkRegions, (std::vector<std::size_t>{0}));
  EXPECT_TRUE(function.curves[0].isWalkRegion(0));
  EXPECT_EQ(printFunction(function), walkText);
  EXPECT_TRUE(verifyFunction(function).empty());
}

TEST(CurveLapWalk, TheVerifierKeepsCurveWalkToTheWalkedRegions) {
  EXPECT_THAT(
      verifyFunction(parsed(replaced(walkText, "    walks 0\n", ""))),
      Contains(HasSubstr("its region 0 ends in curve.walk but its curve wants curve.point")));
  EXPECT_THAT(verifyFunction(parsed(replaced(walkText, "walks 0", "walks 0\n    arcs 0 ccw"))),
              Contains(HasSubstr("has region 0 both an arc and walked")));
  EXPECT_THAT(verifyFunction(parsed(replaced(walkText, "walks 0", "walks 1"))),
              Contains(HasSubstr("a walked region 1 that is not a later region of it")));
  EXPECT_EQ(curve_lap_test::parseComplaint(
                replaced(walkText, "curve.walk %8, %1, %1, %11", "curve.walk %8, %1, %1")),
            "20: expected 'curve.walk' with 4 operands");
}

TEST(CurveLapWalk, TheWalkTakesTheStepItsRegionComputes) {
  Function function = parsed(walkText);
  std::vector<MachineEvent> moves = movesOf(expandedPath(function));
  std::vector<double> parameters = walkedParameters(1);
  ASSERT_EQ(moves.size(), parameters.size());
  for (std::size_t k = 0; k < moves.size(); ++k) {
    EXPECT_NEAR(moves[k].x, 10 * parameters[k], 1e-12) << k;
    EXPECT_EQ(moves[k].z, -1);
  }
  EXPECT_EQ(moves.back().x, 10); // the last step ends at the region's end
  EXPECT_EQ(countOf(function, Opcode::LoopNext), 1u);
}

TEST(CurveLapWalk, TheLoopComputesTheStepAtRunTime) {
  Function function = parsed(walkText);
  InterpreterOptions options;
  options.parameters = {{"s", 0.5}};
  std::vector<MachineEvent> moves = movesOf(expandedPath(function, options));
  EXPECT_EQ(moves.size(), walkedParameters(0.5).size());
  EXPECT_GT(moves.size(), walkedParameters(1).size());
}

TEST(CurveLapWalk, AWalkThatDoesNotAdvanceStopsTheRun) {
  Function function = parsed(walkText);
  InterpreterOptions options;
  options.parameters = {{"s", 0}};
  EXPECT_THROW(interpret(function, options), InterpreterError);
  ASSERT_TRUE(expandControllerLoops(function));
  EXPECT_THROW(interpret(function, options), InterpreterError);
}

// From z = 0 to z = -1: each point as deep as the share of the walk done.
TEST(CurveLapWalk, ARampDescendsAlongTheWalk) {
  Function function =
      parsed(replaced(replaced(walkText, "  %3 = const -1\n", "  %3 = const -1\n  %12 = const 0\n"),
                      "curve.lap @0, %3, %3", "curve.lap @0, %12, %3"));
  std::vector<MachineEvent> moves = movesOf(expandedPath(function));
  std::vector<double> parameters = walkedParameters(1);
  ASSERT_EQ(moves.size(), parameters.size());
  for (std::size_t k = 0; k < moves.size(); ++k) {
    EXPECT_NEAR(moves[k].z, -parameters[k], 1e-12) << k;
  }
}

// A step that is not a number: the walk before the legalisation does what
// the loop after it does (min as the program computes it).
TEST(CurveLapWalk, ANonFiniteStepRunsAsTheLoopRunsIt) {
  Function function = parsed(walkText);
  InterpreterOptions options;
  options.parameters = {{"s", std::nan("")}};
  auto run = [&](const Function& walked) -> std::optional<ToolPath> {
    try {
      return interpret(walked, options);
    } catch (const InterpreterError&) {
      return std::nullopt;
    }
  };
  std::optional<ToolPath> before = run(function);
  ASSERT_TRUE(expandControllerLoops(function));
  std::optional<ToolPath> after = run(function);
  ASSERT_EQ(before.has_value(), after.has_value());
  if (before) {
    curve_lap_test::expectSameMoves(*before, *after);
  }
}

} // namespace
} // namespace cncc::ir
