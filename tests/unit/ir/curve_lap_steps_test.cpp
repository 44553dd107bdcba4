// Laps cut in steps: an entry giving each region's number of uniform steps
// is printed and parsed with its counts, the verifier keeps the counts to
// the regions, and expand-controller-loops writes each such lap out as a
// loop per region, which runs the points the interpreter runs the lap with.
#include "cncc/ir/curve_lap.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/verifier.h"
#include "curve_lap_fixtures.h"

#include <gtest/gtest.h>

#include <cmath>

namespace cncc::ir {
namespace {

using curve_lap_test::circleText;
using curve_lap_test::countOf;
using curve_lap_test::feedMoves;
using curve_lap_test::parsed;
using curve_lap_test::pi;
using curve_lap_test::replaced;

// The circle of radius r about the origin in 8 uniform steps.
std::string steppedCircleText(std::string_view counts = "8") {
  return replaced(
      replaced(circleText, "chords 0.01", "steps 0"), "piece at 0 over 0 .. 6.283185307179586\n",
      "piece at 0 over 0 .. 6.283185307179586\n    counts " + std::string(counts) + "\n");
}

// A line from (0, 0) to (10, 0) in one step, then a quarter circle of
// radius 10 about the origin from (10, 0) to (0, 10) in 4 steps.
constexpr std::string_view lineThenArcText = R"(func @hook() {
  curve @0 steps 0.01 over 0 .. 11.5707963267949 {
    piece at 0 over 0 .. 10
    piece at 10 over 0 .. 1.5707963267948966
    counts 1, 4
  }
  %0 = const 0
  %1 = const 100
  %2 = const -2
  move.rapid %0, %0, %0
  %3 = curve.lap @0, %2, %2, %1 {
    curve.point %3, %0, %0
  } piece {
    %4 = const 10
    %5 = cos %3
    %6 = mul %4, %5
    %7 = sin %3
    %8 = mul %4, %7
    curve.point %6, %8, %0
  }
}
)";

// An arc of radius r from angle 0 to angle a in n steps, a and n computed
// by the program (parameters): the lap's range and count are its operands.
constexpr std::string_view computedArcText = R"(func @fan(r = 5, a = 3, n = 8) {
  curve @0 steps 0 over 0 .. 3 {
    piece at 0 over 0 .. 3
    counts 0
  }
  %0 = param r
  %1 = param a
  %2 = param n
  %3 = const 500
  %4 = const -1
  %5 = const 0
  move.rapid %0, %5, %5
  %6 = curve.lap @0, %4, %4, %3, %5, %1, %2 {
    %7 = cos %6
    %8 = mul %0, %7
    %9 = sin %6
    %10 = mul %0, %9
    curve.point %8, %10, %5
  }
}
)";

TEST(CurveLapSteps, ARangeAndCountTheProgramComputesAreTheLapsOperands) {
  Function function = parsed(computedArcText);
  EXPECT_EQ(printFunction(function), computedArcText);
  EXPECT_TRUE(verifyFunction(function).empty());
  ToolPath before = interpret(function);
  ASSERT_TRUE(expandControllerLoops(function));
  EXPECT_TRUE(verifyFunction(function).empty());
  EXPECT_EQ(countOf(function, Opcode::Loop), 1u);
  curve_lap_test::expectSamePath(before, interpret(function));

  // Edited at the machine: a quarter turn in 5 steps.
  InterpreterOptions options;
  options.parameters = {{"a", pi / 2}, {"n", 5}};
  std::vector<MachineEvent> moves = feedMoves(interpret(function, options));
  ASSERT_EQ(moves.size(), 5u);
  for (std::size_t k = 0; k < moves.size(); ++k) {
    EXPECT_NEAR(std::atan2(moves[k].y, moves[k].x), static_cast<double>(k + 1) * pi / 10, 1e-12);
  }
  EXPECT_NEAR(moves.back().y, 5, 1e-12);
}

TEST(CurveLapSteps, AComputedRegionOfOneStepGoesToItsEnd) {
  Function function = parsed(replaced(replaced(computedArcText, "%2 = param n", "%2 = const 1"),
                                      "func @fan(r = 5, a = 3, n = 8)", "func @fan(r = 5, a = 3)"));
  ToolPath before = interpret(function);
  ASSERT_TRUE(expandControllerLoops(function));
  EXPECT_EQ(countOf(function, Opcode::Loop), 0u);
  std::vector<MachineEvent> moves = feedMoves(interpret(function));
  ASSERT_EQ(moves.size(), 1u);
  EXPECT_NEAR(std::atan2(moves[0].y, moves[0].x), 3, 1e-12);
  curve_lap_test::expectSamePath(before, interpret(function));
}

TEST(CurveLapSteps, AStepsEntryPrintsAndParsesWithItsCounts) {
  Function function = parsed(lineThenArcText);
  ASSERT_EQ(function.curves.size(), 1u);
  EXPECT_EQ(function.curves[0].sampling, CurveSampling::Steps);
  EXPECT_EQ(function.curves[0].regionSteps, (std::vector<int>{1, 4}));
  EXPECT_EQ(printFunction(function), lineThenArcText);
  EXPECT_TRUE(verifyFunction(function).empty());
  EXPECT_TRUE(verifyFunction(parsed(steppedCircleText())).empty()); // counts given: amount 0
}

TEST(CurveLapSteps, TheVerifierKeepsACountToEachRegion) {
  std::vector<std::string> problems = verifyFunction(parsed(steppedCircleText("8, 2")));
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("2 step counts for 1 regions"), std::string::npos) << problems[0];
  EXPECT_NE(curve_lap_test::parseComplaint(steppedCircleText("0")).find("wants 3 operands"),
            std::string::npos); // a count the program computes: its range and count
  EXPECT_EQ(verifyFunction(parsed(steppedCircleText("100001"))).size(), 1u);

  Function chords = parsed(replaced(circleText, "piece at 0 over 0 .. 6.283185307179586\n",
                                    "piece at 0 over 0 .. 6.283185307179586\n    counts 8\n"));
  problems = verifyFunction(chords);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("not cut in steps"), std::string::npos) << problems[0];
}

TEST(CurveLapSteps, TheStepsAreUniformInEachRegion) {
  std::vector<LapStep> steps = lapSteps(
      lapStepRanges(parsed(lineThenArcText).curves[0], [](std::size_t) { return StepRange{}; }));
  ASSERT_EQ(steps.size(), 5u);
  EXPECT_EQ(steps[0].region, 0u);
  EXPECT_EQ(steps[0].local, 10); // a region of one step: its end
  for (int i = 1; i <= 4; ++i) {
    EXPECT_EQ(steps[static_cast<std::size_t>(i)].region, 1u);
    EXPECT_DOUBLE_EQ(steps[static_cast<std::size_t>(i)].local, i * pi / 8);
  }
}

TEST(CurveLapSteps, TheStepsAreParametersOfTheWholeCurve) {
  Function function = parsed(lineThenArcText);
  std::shared_ptr<const geom::Curve> curve =
      lapCurve(function, curve_lap_test::onlyLap(function), [](ValueId) { return 0.0; });
  std::vector<double> parameters = lapParameters(function.curves[0], *curve);
  ASSERT_EQ(parameters.size(), 6u);
  EXPECT_EQ(parameters[0], 0);
  EXPECT_EQ(parameters[1], 10); // the line's end
  for (std::size_t k = 2; k < parameters.size(); ++k) {
    EXPECT_DOUBLE_EQ(parameters[k], 10 + static_cast<double>(k - 1) * pi / 8);
  }
}

TEST(CurveLapSteps, ExpandingWritesALoopPerRegionOfMoreThanOneStep) {
  Function function = parsed(lineThenArcText);
  ToolPath before = interpret(function);
  ASSERT_TRUE(expandControllerLoops(function));
  EXPECT_TRUE(verifyFunction(function).empty());
  EXPECT_EQ(countOf(function, Opcode::CurveLap), 0u);
  EXPECT_EQ(countOf(function, Opcode::Loop), 1u); // the line's one step needs none
  EXPECT_TRUE(function.tables.empty());           // nothing tabled: the program computes it
  ToolPath after = interpret(function);
  curve_lap_test::expectSamePath(before, after);

  std::vector<MachineEvent> moves = feedMoves(after);
  ASSERT_EQ(moves.size(), 5u);
  EXPECT_EQ(moves[0].x, 10);
  EXPECT_EQ(moves[0].z, -2);
  for (std::size_t k = 1; k < moves.size(); ++k) {
    EXPECT_NEAR(std::hypot(moves[k].x, moves[k].y), 10, 1e-12);
    EXPECT_NEAR(std::atan2(moves[k].y, moves[k].x), static_cast<double>(k) * pi / 8, 1e-12);
  }
}

TEST(CurveLapSteps, TheLoopReadsTheParameterAtRunTime) {
  Function function = parsed(steppedCircleText());
  ASSERT_TRUE(runPasses(function, std::vector<std::string>{"expand-controller-loops"}, {}));
  InterpreterOptions options;
  options.parameters = {{"r", 7}};
  std::vector<MachineEvent> moves = feedMoves(interpret(function, options));
  ASSERT_EQ(moves.size(), 8u);
  for (const MachineEvent& move : moves) {
    EXPECT_NEAR(std::hypot(move.x, move.y), 7, 1e-12);
  }
}

// From z = 0 to z = -2: the line (10 long) takes 10 / (10 + 5 pi) of the
// descent, the quarter circle the rest, each in proportion to its steps.
TEST(CurveLapSteps, ARampLapDescendsByEachRegionsShareOfTheLength) {
  Function function = parsed(
      replaced(replaced(lineThenArcText, "%2 = const -2\n", "%2 = const -2\n  %9 = const 0\n"),
               "curve.lap @0, %2, %2", "curve.lap @0, %9, %2"));
  ToolPath before = interpret(function);
  std::vector<MachineEvent> moves = feedMoves(before);
  ASSERT_EQ(moves.size(), 5u);
  double lineShare = 10 / (10 + 5 * pi);
  EXPECT_NEAR(moves[0].z, -2 * lineShare, 1e-9);
  for (std::size_t k = 1; k < moves.size(); ++k) {
    double done = lineShare + (1 - lineShare) * static_cast<double>(k) / 4;
    EXPECT_NEAR(moves[k].z, -2 * done, 1e-9) << k;
  }
  ASSERT_TRUE(expandControllerLoops(function));
  EXPECT_TRUE(verifyFunction(function).empty());
  curve_lap_test::expectSamePath(before, interpret(function));
}

TEST(CurveLapSteps, ExpandingCurveLapsWritesTheStepsFirst) {
  Function function = parsed(steppedCircleText());
  ToolPath before = interpret(function);
  ASSERT_TRUE(expandCurveLaps(function));
  EXPECT_TRUE(function.curves.empty());
  EXPECT_EQ(countOf(function, Opcode::Loop), 1u);
  curve_lap_test::expectSamePath(before, interpret(function));
}

} // namespace
} // namespace cncc::ir
