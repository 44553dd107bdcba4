// choose-controller-steps: on a target whose controller computes, a lap of
// chords along a curve of constants is cut in steps the controller counts
// (the same regions, its counts measured by expand-controller-loops); a lap
// on the host, or one whose regions read a parameter, stays chords. The
// interpreter runs such a lap stepped before the pass too.
#include "cncc/ir/curve_lap.h"
#include "cncc/ir/verifier.h"
#include "curve_lap_fixtures.h"

#include <gtest/gtest.h>

#include <cmath>

namespace cncc::ir {
namespace {

using curve_lap_test::circleText;
using curve_lap_test::countOf;
using curve_lap_test::expandedPath;
using curve_lap_test::expectSamePath;
using curve_lap_test::feedMoves;
using curve_lap_test::parsed;
using curve_lap_test::replaced;

// circleText's circle of radius 5 as a constant, in cut 0 of a controller
// target that computes with 8 digits on a grid of 0.001.
std::string constantCircle(std::string_view cutLine) {
  std::string text = replaced(circleText, "func @circle(r = 5) {", "func @circle() {");
  text = replaced(text, "  %0 = param r\n", std::string(cutLine) + "  %0 = const 5\n");
  return replaced(text, "  %4 = curve.lap", "  cut.begin 0\n  %4 = curve.lap");
}
constexpr std::string_view controllerCut = "  cut @0 tolerance 0.01 increment 0.001 controller 8\n";

// The function's path before the pass (its laps stepped already, as the
// pass will cut them), and its entry 0 after it; the pass must cut that
// entry in steps and leave a function that verifies and runs the same path.
struct Stepped {
  ToolPath before;
  CurveTableEntry entry;
};

Stepped steppedByThePass(Function& function) {
  EXPECT_TRUE(verifyFunction(function).empty());
  Stepped stepped{interpret(function), {}};
  EXPECT_TRUE(chooseControllerSteps(function));
  EXPECT_TRUE(verifyFunction(function).empty());
  stepped.entry = function.curves[0];
  EXPECT_EQ(stepped.entry.sampling, CurveSampling::Steps);
  expectSamePath(stepped.before, interpret(function));
  return stepped;
}

TEST(ChooseControllerSteps, ChordsOfConstantsAreCutInStepsTheControllerCounts) {
  Function function = parsed(constantCircle(controllerCut));
  auto [before, entry] = steppedByThePass(function);
  // 0.01 less half an increment on two axes (the circle lies in z = 0) and
  // the literals' share of the increment.
  EXPECT_NEAR(entry.amount, 0.01 - std::sqrt(2.0) * 0.0005 - 0.02 * 0.001, 1e-15);
  EXPECT_EQ(entry.regionSteps, std::vector<int>{stepsChosenByLegalisation});

  ToolPath after = expandedPath(function);
  EXPECT_EQ(countOf(function, Opcode::Loop), 1u);
  EXPECT_EQ(function.tables.size(), 0u); // the loop computes its parameter
  // Within 0.00927 of a circle of radius 5: 2 pi / (2 acos(1 - 0.00927 / 5)).
  EXPECT_EQ(feedMoves(after).size(), 52u);
  expectSamePath(before, after);
}

TEST(ChooseControllerSteps, SamplesOfOneRegionAreItsStepsReadWithinTheDefaultTolerance) {
  // samples=13 on the circle: 12 equal steps of the parameter, as the host's
  // 13 points, read within the default tolerance (the cut has none).
  std::string text =
      replaced(constantCircle("  cut @0 tolerance nan increment 0.001 controller 8\n"),
               "curve @0 chords 0.01", "curve @0 samples 13");
  Function function = parsed(text);
  auto [before, entry] = steppedByThePass(function);
  EXPECT_EQ(entry.regionSteps, std::vector<int>{12});

  ToolPath after = expandedPath(function);
  EXPECT_EQ(countOf(function, Opcode::Loop), 1u);
  EXPECT_EQ(function.tables.size(), 0u);
  EXPECT_EQ(feedMoves(after).size(), 12u);
  expectSamePath(before, after);
}

TEST(ChooseControllerSteps, SamplesOverSeveralRegionsStay) {
  // samples= over two pieces: the samples do not fall on the pieces' ends.
  std::string text =
      replaced(constantCircle(controllerCut), "curve @0 chords 0.01", "curve @0 samples 13");
  text = replaced(text, "    piece at 0 over 0 .. 6.283185307179586\n",
                  "    piece at 0 over 0 .. 3.141592653589793\n"
                  "    piece at 3.141592653589793 over 3.141592653589793 .. 6.283185307179586\n");
  text = replaced(text, "    curve.point %6, %8, %3\n  }\n",
                  "    curve.point %6, %8, %3\n  } piece {\n"
                  "    %9 = cos %4\n    %10 = mul %0, %9\n    %11 = sin %4\n"
                  "    %12 = mul %0, %11\n    curve.point %10, %12, %3\n  }\n");
  Function function = parsed(text);
  ASSERT_TRUE(verifyFunction(function).empty());
  EXPECT_FALSE(chooseControllerSteps(function));
  EXPECT_EQ(function.curves[0].sampling, CurveSampling::Samples);
}

TEST(ChooseControllerSteps, ChordsOnTheHostStay) {
  Function function =
      parsed(constantCircle("  cut @0 tolerance 0.01 increment 0.001\n")); // no controller
  EXPECT_FALSE(chooseControllerSteps(function));
  EXPECT_EQ(function.curves[0].sampling, CurveSampling::ChordTolerance);
}

TEST(ChooseControllerSteps, ChordsReadingAParameterStay) {
  // The radius a parameter the regions read: the lowering plans the steps
  // of such a curve itself, or fixes what it reads.
  std::string text =
      replaced(circleText, "  %0 = param r\n", std::string(controllerCut) + "  %0 = param r\n");
  Function function = parsed(replaced(text, "  %4 = curve.lap", "  cut.begin 0\n  %4 = curve.lap"));
  ASSERT_TRUE(verifyFunction(function).empty());
  EXPECT_FALSE(chooseControllerSteps(function));
  EXPECT_EQ(function.curves[0].sampling, CurveSampling::ChordTolerance);
}

TEST(ChooseControllerSteps, ChordsWhosePointsTheHostComputesStay) {
  // Points printed as numbers (a cut beside its curve on a controller).
  std::string text =
      replaced(constantCircle(controllerCut), "    piece at 0 over 0 .. 6.283185307179586\n",
               "    piece at 0 over 0 .. 6.283185307179586\n    numbers\n");
  Function function = parsed(text);
  ASSERT_TRUE(verifyFunction(function).empty());
  EXPECT_FALSE(chooseControllerSteps(function));
}

TEST(ChooseControllerSteps, AShareOfALongerDescentDescendsByItInSteps) {
  // A ramp lap from z = 0 to -1 over the second quarter of a longer
  // descent (a piece between arcs cut as arcs): in steps it keeps its share.
  std::string text =
      replaced(constantCircle(controllerCut), "    piece at 0 over 0 .. 6.283185307179586\n",
               "    piece at 0 over 0 .. 6.283185307179586\n    progress 0.25 share 0.25\n");
  Function function =
      parsed(replaced(text, "curve.lap @0, %2, %2, %1", "curve.lap @0, %3, %2, %1"));
  auto [before, entry] = steppedByThePass(function);
  EXPECT_EQ(entry.progressFrom, 0.25);
  EXPECT_EQ(entry.progressShare, 0.25);
  ToolPath after = expandedPath(function);
  std::vector<MachineEvent> moves = feedMoves(after);
  ASSERT_FALSE(moves.empty());
  // From a quarter of the way down to half of it.
  EXPECT_NEAR(moves.back().z, -0.5, 1e-12);
  EXPECT_GT(moves.front().z, -0.5);
  EXPECT_LT(moves.front().z, -0.25);
  expectSamePath(before, after);
}

TEST(ChooseControllerSteps, NothingLeftOfTheToleranceStaysChords) {
  // 0.0007 less the rounding of two axes on a grid of 0.001 (0.000707).
  Function function =
      parsed(constantCircle("  cut @0 tolerance 0.0007 increment 0.001 controller 8\n"));
  EXPECT_FALSE(chooseControllerSteps(function));
}

} // namespace
} // namespace cncc::ir
