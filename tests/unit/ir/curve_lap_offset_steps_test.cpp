// The counts of a lap beside a curve whose tool radius the program reads
// (`offset left|right radius R largest L`): expand-controller-loops
// measures N0 and q on the regions and writes N(r) = N0 sqrt(1 + q r) as
// the program's arithmetic on the distance the lap reads; the interpreter
// runs the lap with the same count at whatever radius the part is given.
#include "cncc/geom/line_arc_curves.h"
#include "cncc/ir/curve_lap_offset_steps.h"
#include "cncc/ir/curve_lap_steps.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/verifier.h"
#include "curve_lap_fixtures.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace cncc::ir {
namespace {

using curve_lap_test::onlyLap;
using curve_lap_test::parsed;
using curve_lap_test::replaced;
using ::testing::Contains;
using ::testing::HasSubstr;

// A circle of radius 10 cut outside it (on its right) by a tool of diameter
// `dia`: the region's point is the tool centre at d = -dia / 2, the lap's
// last operand; the count is left to the legalisation.
constexpr std::string_view ringText = R"(func @ring(dia = 4) {
  curve @0 steps 0.01 over 0 .. 6.283185307179586 {
    piece at 0 over 0 .. 6.283185307179586
    counts ?
    offset right radius 2 largest inf
  }
  %0 = param dia
  %1 = const -0.5
  %2 = mul %0, %1
  %3 = const 500
  %4 = const -1
  %5 = const 0
  %6 = const 10
  %7 = sub %6, %2
  move.rapid %7, %5, %5
  move.feed %7, %5, %4, %3
  %8 = curve.lap @0, %4, %4, %3, %2 {
    %9 = sub %6, %2
    %10 = cos %8
    %11 = mul %9, %10
    %12 = sin %8
    %13 = mul %9, %12
    curve.point %11, %13, %5
  }
}
)";

// N0 is the fewest steps on the drawn circle (10 (1 - cos(pi / N)) <= 0.01
// from N = 71), and N(r) keeps the chords of the exact offset, the circle of
// radius 10 + r, within the entry's 0.01 at every radius the part may take.
TEST(CurveLapOffsetSteps, TheCountGrowsWithTheRadiusAndKeepsTheTolerance) {
  Function function = parsed(ringText);
  ASSERT_TRUE(verifyFunction(function).empty());
  std::vector<OffsetRegionGrowth> growth = measureOffsetGrowth(function, onlyLap(function));
  ASSERT_EQ(growth.size(), 1u);
  EXPECT_EQ(growth[0].drawnSteps, 71);
  EXPECT_GT(growth[0].growth, 0);
  const OffsetStepGrowth& offset = *function.curves[0].offsetGrowth;
  double previous = 0;
  for (double radius : {0.25, 2.0, 5.0, 20.0}) {
    double steps = offsetStepsAt(growth[0], offset, -radius);
    EXPECT_GE(steps, previous) << radius;
    previous = steps;
    geom::ArcCurve exact(Eigen::Vector2d(0, 0), 10 + radius, 0, 2 * curve_lap_test::pi);
    EXPECT_TRUE(uniformStepsFit(exact, 0, 2 * curve_lap_test::pi, static_cast<int>(steps), 0.01))
        << radius;
  }
}

// The pass writes the count as the program's arithmetic (no number of
// steps is left in the loop), and the interpreter runs the lap before the
// pass with the count the program computes after it, at the default and
// at edited diameters.
TEST(CurveLapOffsetSteps, ThePassAndTheInterpreterCountAlike) {
  curve_lap_test::PassRun run =
      curve_lap_test::runThroughPass(std::string(ringText), expandControllerLoops);
  EXPECT_EQ(curve_lap_test::countOf(run.function, Opcode::Round), 1u);
  EXPECT_EQ(curve_lap_test::countOf(run.function, Opcode::Sqrt), 1u);
  Function before = parsed(ringText);
  for (double diameter : {0.5, 9.0, 30.0}) {
    InterpreterOptions options;
    options.parameters = {{"dia", diameter}};
    ToolPath unexpanded = interpret(before, options);
    curve_lap_test::expectSamePath(unexpanded, interpret(run.function, options));
    std::size_t feeds = curve_lap_test::feedMoves(unexpanded).size();
    std::vector<OffsetRegionGrowth> growth = measureOffsetGrowth(before, onlyLap(before));
    double steps = offsetStepsAt(growth[0], *before.curves[0].offsetGrowth, -diameter / 2);
    EXPECT_EQ(feeds, static_cast<std::size_t>(steps) + 1) << diameter; // and the plunge
  }
}

TEST(CurveLapOffsetSteps, TheTextAndTheVerifierKeepTheGrowth) {
  Function function = parsed(ringText);
  EXPECT_EQ(printFunction(function), ringText);
  auto problems = [&](std::string_view from, std::string_view to) {
    return verifyFunction(parsed(replaced(ringText, from, to)));
  };
  EXPECT_THAT(problems("offset right radius 2", "offset right radius 0"),
              Contains(HasSubstr("not a side of 1 or -1 and a positive radius below the largest")));
  EXPECT_THAT(problems("largest inf", "largest 1"),
              Contains(HasSubstr("a positive radius below the largest")));
  EXPECT_THAT(problems("steps 0.01", "chords 0.01"),
              Contains(HasSubstr("an offset's growth but is not cut in steps")));
  EXPECT_EQ(curve_lap_test::parseComplaint(replaced(ringText, "offset right", "offset inside")),
            "5: expected 'offset left|right radius R largest L'");
  // The lap reads the distance last: without it, one operand short.
  EXPECT_EQ(curve_lap_test::parseComplaint(
                replaced(ringText, "curve.lap @0, %4, %4, %3, %2 {", "curve.lap @0, %4, %4, %3 {")),
            "17: curve @0 wants 1 operands after the lap's three (a range and a count for each "
            "region whose steps the program computes, then an offset's distance)");
}

// A curve that is not finite is an error at the curve, not a search.
TEST(CurveLapOffsetSteps, ACurveThatIsNotFiniteIsAnError) {
  Function function = parsed(replaced(ringText, "%6 = const 10", "%6 = const nan"));
  try {
    measureOffsetGrowth(function, onlyLap(function));
    ADD_FAILURE() << "measured";
  } catch (const CurveLapError& error) {
    EXPECT_EQ(error.kind, CurveLapError::Kind::NonFiniteValue);
  }
}

} // namespace
} // namespace cncc::ir
