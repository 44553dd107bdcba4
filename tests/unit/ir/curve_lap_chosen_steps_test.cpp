// Counts of a lap cut in steps that the lowering leaves to the legalisation
// (`counts ?`): expand-controller-loops measures the fewest uniform steps
// within the entry's amount on the lap's curve, once per entry, and writes
// its loop; the interpreter runs the lap with the same count. The lap's cut
// on a controller that reads the step rounded (`cut @n tolerance T
// controller N`) has counts whose drift moves the last point too far refused.
#include "cncc/geom/discretisation.h"
#include "cncc/geom/function_curve.h"
#include "cncc/geom/line_arc_curves.h"
#include "cncc/ir/curve_lap_steps.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/verifier.h"
#include "curve_lap_fixtures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace cncc::ir {
namespace {

using curve_lap_test::countOf;
using curve_lap_test::parsed;
using curve_lap_test::replaced;

// The circle of radius 5 cut in steps within `amount`, its count chosen.
std::string circleInSteps(std::string_view amount, std::string_view more = "") {
  std::string text =
      replaced(curve_lap_test::circleText, "chords 0.01", "steps " + std::string(amount));
  return replaced(text, "    piece at 0 over 0 .. 6.283185307179586\n",
                  "    piece at 0 over 0 .. 6.283185307179586\n    counts ?\n" + std::string(more));
}

// A chord of 2 pi / N on a circle of radius 5 deviates 5 (1 - cos(pi / N)):
// within 0.01 from N = 50 (49 leave 0.0103).
TEST(CurveLapChosenSteps, TheFewestUniformStepsWithinTheAmount) {
  curve_lap_test::PassRun run =
      curve_lap_test::runThroughPass(circleInSteps("0.01"), expandControllerLoops);
  EXPECT_EQ(countOf(run.function, Opcode::Loop), 1u);
  EXPECT_EQ(run.function.curves[0].regionSteps, std::vector<int>{50}); // as written
  std::vector<MachineEvent> feeds = curve_lap_test::feedMoves(run.before);
  ASSERT_EQ(feeds.size(), 50u);
  EXPECT_NEAR(std::hypot(feeds.back().x - 5, feeds.back().y), 0, 1e-9);

  geom::ArcCurve circle(Eigen::Vector2d(0, 0), 5, 0, 2 * curve_lap_test::pi);
  EXPECT_EQ(fewestUniformSteps(circle, 0, circle.domain().t1, 0.01), 50);
  EXPECT_FALSE(uniformStepsFit(circle, 0, circle.domain().t1, 49, 0.01));
}

// The search probes the counts the largest deviation predicts before it
// bisects. On curves where more steps never deviate more (an ellipse, a
// spiral) it returns the fewest count that fits, as every count from 1 up
// says; on a spike, where an even count has a point on its peak and an odd
// one does not, a count that fits whose count below does not, within a few
// of the fewest.
TEST(CurveLapChosenSteps, TheSearchFindsTheFewestCountThatFits) {
  using geom::FunctionCurve;
  struct Case {
    FunctionCurve curve;
    bool monotone;
  };
  std::vector<Case> cases = {
      {FunctionCurve::fromCoordinates(
           {0, 2 * curve_lap_test::pi}, [](double t) { return 30 * std::cos(t); },
           [](double t) { return 15 * std::sin(t); }),
       true},
      {FunctionCurve::fromCoordinates(
           {0, 6 * curve_lap_test::pi}, [](double t) { return (1 + t) * std::cos(t); },
           [](double t) { return (1 + t) * std::sin(t); }),
       true},
      {FunctionCurve::fromCoordinates(
           {-1, 1}, [](double t) { return 10 * t; },
           [](double t) { return 20 * std::exp(-30 * t * t); }),
       false},
  };
  for (const Case& test : cases) {
    const FunctionCurve& curve = test.curve;
    double from = curve.domain().t0;
    double to = curve.domain().t1;
    for (double budget : {0.05, 0.01}) {
      int fewest = 1;
      while (!uniformStepsFit(curve, from, to, fewest, budget)) {
        ++fewest;
      }
      int found = fewestUniformSteps(curve, from, to, budget);
      if (test.monotone) {
        EXPECT_EQ(found, fewest) << budget;
        continue;
      }
      EXPECT_TRUE(uniformStepsFit(curve, from, to, found, budget)) << budget;
      EXPECT_FALSE(uniformStepsFit(curve, from, to, found - 1, budget)) << budget;
      EXPECT_LE(found, fewest + 2) << budget;
    }
  }
}

// Past the most steps a region may take, an error at the cut naming it,
// quickly (the entry's geometry is the circle itself, as the lowering
// gives it).
TEST(CurveLapChosenSteps, TooManyStepsIsAnErrorNamingTheLimit) {
  CurveLapError error = curve_lap_test::passError(
      curve_lap_test::withCircleGeometry(parsed(circleInSteps("1e-12"))), expandControllerLoops);
  EXPECT_EQ(error.kind, CurveLapError::Kind::ProgramTooLarge);
  EXPECT_EQ(std::string(error.what()),
            "this curve needs more than 100000 uniform steps on one piece within its tolerance");
}

// A curve that is not finite is an error at once, not a search to the
// limit (whose message would blame the tolerance).
TEST(CurveLapChosenSteps, ACurveThatIsNotFiniteIsAnError) {
  CurveLapError error = curve_lap_test::passError(
      replaced(circleInSteps("0.01"), "    %5 = cos %4\n", "    %9 = neg %4\n    %5 = sqrt %9\n"),
      expandControllerLoops);
  EXPECT_EQ(error.kind, CurveLapError::Kind::NonFiniteValue);
}

// Half the circle in 6 steps of pi / 6 = 0.5235987755982988, which 8
// significant digits read as 0.52359878: the last point lies 6 * 4.4e-9
// radians on, 1.32e-7 mm along the circle.
TEST(CurveLapChosenSteps, AStepTheControllerReadsRoundedMayDriftTooFar) {
  std::string half = replaced(curve_lap_test::circleText, "6.283185307179586", "3.141592653589793");
  half = replaced(half, "6.283185307179586", "3.141592653589793");
  half = replaced(half, "chords 0.01", "steps 0.01");
  half = replaced(half, "    piece at 0 over 0 .. 3.141592653589793\n",
                  "    piece at 0 over 0 .. 3.141592653589793\n    counts 6\n");
  half = replaced(half, "  move.rapid", "  cut.begin 0\n  move.rapid");
  // The lap's cut: a controller of 8 digits, its tolerance 1e-7.
  std::string within =
      replaced(half, "  %0 = param r\n", "  cut @0 tolerance 1e-07 controller 8\n  %0 = param r\n");
  CurveLapError error = curve_lap_test::passError(within, expandControllerLoops);
  EXPECT_EQ(error.kind, CurveLapError::Kind::LiteralRounding);
  EXPECT_NE(std::string(error.what())
                .find("the controller's 8 significant digits round this curve's parameter step "
                      "0.5235987755982988 to 0.52359878: after its 6 steps the last point lies "
                      "1.32e-07 mm past"),
            std::string::npos)
      << error.what();
  // Within 1e-6, or read exactly, it stands.
  Function coarser = parsed(replaced(within, "tolerance 1e-07", "tolerance 1e-06"));
  EXPECT_TRUE(expandControllerLoops(coarser));
  Function exact = parsed(replaced(within, " controller 8", ""));
  EXPECT_TRUE(expandControllerLoops(exact));
}

TEST(CurveLapChosenSteps, TheVerifierKeepsChosenCountsToUniformSteps) {
  // Without a tolerance to choose within.
  std::vector<std::string> problems = verifyFunction(parsed(circleInSteps("0")));
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("leaves the count of region 0 to the legalisation"), std::string::npos)
      << problems[0];
  // An arc's blocks are the arc's own.
  problems = verifyFunction(parsed(circleInSteps("0.01", "    arcs 0 ccw\n")));
  ASSERT_FALSE(problems.empty());
  EXPECT_NE(problems[0].find("leaves the count of region 0 to the legalisation"), std::string::npos)
      << problems[0];
}

} // namespace
} // namespace cncc::ir
