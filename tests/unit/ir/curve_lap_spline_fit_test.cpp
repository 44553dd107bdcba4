// Sinumerik spline blocks that write-curve-blocks fits: an entry that names
// no table but says which blocks (`spline KIND ENDS [after-ramp]`) prints
// and parses, the pass fits them once within the entry's tolerance on its
// grid and writes their comment (also the cut's summary) and one
// move.spline, and the interpreter runs the lap as the pass fits it.
#include "cncc/ir/curve_blocks.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/spline_move.h"
#include "cncc/ir/verifier.h"
#include "curve_lap_fixtures.h"

#include <gtest/gtest.h>

#include <cmath>

namespace cncc::ir {
namespace {

using curve_lap_test::countOf;
using curve_lap_test::parsed;
using curve_lap_test::replaced;

// The circle of radius 5 as spline blocks the pass fits, `fit` the entry's
// `spline` line and `chosen` its chosen parameters (none if empty), in cut 0
// of the function's cut table (whose summary the pass writes).
std::string circleAsSpline(std::string_view fit, std::string_view chosen = "") {
  std::string text = curve_lap_test::circleAsFittedBlocks("spline-blocks");
  std::string lines = "    grid 0.0001\n    spline " + std::string(fit) + "\n";
  if (!chosen.empty()) {
    lines += "    chosen " + std::string(chosen) + "\n";
  }
  text = replaced(text, "    grid 0.0001\n", lines);
  text =
      replaced(text, "  %0 = param r", "  cut @0 tolerance 0.001 method cspline\n  %0 = param r");
  return replaced(text, "  move.rapid", "  cut.begin 0\n  move.rapid");
}

// A quarter turn apart around the circle.
constexpr std::string_view quarters =
    "0, 1.5707963267948966, 3.141592653589793, 4.71238898038469, 6.283185307179586";

const Instruction& only(const Function& function, Opcode opcode) {
  const Instruction* found = nullptr;
  for (const Instruction& instruction : function.instructions) {
    if (instruction.opcode == opcode) {
      EXPECT_EQ(found, nullptr) << "more than one";
      found = &instruction;
    }
  }
  EXPECT_NE(found, nullptr);
  return *found;
}

SplineBlockData blocksOf(const Function& function) {
  const Instruction& move = only(function, Opcode::Spline);
  std::optional<SplineBlockData> data = readSplineMoveTable(function.tables.at(move.index));
  EXPECT_TRUE(data.has_value());
  return data.value_or(SplineBlockData{});
}

TEST(CurveLapSplineFit, SplineBlocksWithoutATableAreFittedByThePass) {
  curve_lap_test::PassRun run =
      curve_lap_test::runThroughPass(circleAsSpline("cspline natural"), writeCurveBlocks);
  const Function& function = run.function;
  SplineBlockData blocks = blocksOf(function);
  EXPECT_EQ(blocks.kind, SplineKind::CSpline);
  EXPECT_EQ(blocks.start, geom::SplineEndCondition::Natural);
  EXPECT_GE(blocks.points.size(), 4u);
  // Every knot on the grid.
  for (const Eigen::Vector3d& knot : blocks.points) {
    EXPECT_NEAR(knot.x() * 1e4, std::round(knot.x() * 1e4), 1e-6) << knot.x();
  }
  // Its comment before it, and the cut's summary the same.
  const std::string& comment = only(function, Opcode::Comment).text;
  EXPECT_NE(comment.find("CSPLINE knots, deviation"), std::string::npos) << comment;
  EXPECT_EQ(function.cuts[0].splineBlocks, comment);
  // The interpreter ran the lap as the pass wrote it (runThroughPass),
  // comment included, within the tolerance of the circle.
  curve_lap_test::expectOnTheCircle(run.before, 0.001 + 1e-5);
}

// After a ramp an automatic start is tangent to the ramp's last chord, the
// one through the last two chosen points (a quarter circle's, from (0, -5)
// to (5, 0)); without a ramp it is natural.
TEST(CurveLapSplineFit, AfterARampTheSplineContinuesItsLastChord) {
  std::string text = circleAsSpline("aspline automatic after-ramp", quarters);
  Function function = parsed(text);
  EXPECT_EQ(printFunction(function), text);
  EXPECT_TRUE(verifyFunction(function).empty());
  ASSERT_TRUE(writeCurveBlocks(function));
  SplineBlockData blocks = blocksOf(function);
  EXPECT_EQ(blocks.kind, SplineKind::ASpline);
  EXPECT_EQ(blocks.start, geom::SplineEndCondition::Tangent);

  Function level = parsed(circleAsSpline("aspline automatic"));
  ASSERT_TRUE(writeCurveBlocks(level));
  EXPECT_EQ(blocksOf(level).start, geom::SplineEndCondition::Natural);

  // A ramp's chord needs the chosen points.
  std::vector<std::string> problems =
      verifyFunction(parsed(circleAsSpline("aspline automatic after-ramp")));
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("after a ramp's last chord but has no chosen points"),
            std::string::npos)
      << problems[0];
}

// With samples= (amount 0) a B spline's control points are the chosen
// points, on the grid; too few of them is an error at the cut.
TEST(CurveLapSplineFit, SamplesAreTheControlPoints) {
  std::string text = replaced(circleAsSpline("bspline automatic", quarters), "spline-blocks 0.001",
                              "spline-blocks 0");
  Function function = parsed(text);
  EXPECT_TRUE(verifyFunction(function).empty());
  ASSERT_TRUE(writeCurveBlocks(function));
  SplineBlockData blocks = blocksOf(function);
  ASSERT_EQ(blocks.points.size(), 4u);
  EXPECT_EQ(blocks.points[0], Eigen::Vector3d(0, 5, 0));
  EXPECT_EQ(blocks.points[1], Eigen::Vector3d(-5, 0, 0));
  EXPECT_EQ(blocks.points[2], Eigen::Vector3d(0, -5, 0));
  EXPECT_EQ(blocks.points[3], Eigen::Vector3d(5, 0, 0));

  CurveLapError error =
      curve_lap_test::passError(replaced(text, quarters, "0, 3.141592653589793"), writeCurveBlocks);
  EXPECT_EQ(std::string(error.what()),
            "cannot write this cut as BSPLINE blocks: a B spline needs at least three points");
  EXPECT_EQ(error.kind, CurveLapError::Kind::DegenerateCurve);
}

// A curve that is not finite (here the root of a negative number) is an
// error at once, not a fit searching to its bound.
TEST(CurveLapSplineFit, ACurveThatIsNotFiniteIsAnError) {
  CurveLapError error =
      curve_lap_test::passError(replaced(circleAsSpline("cspline natural"), "    %5 = cos %4\n",
                                         "    %9 = neg %4\n    %5 = sqrt %9\n"),
                                writeCurveBlocks);
  EXPECT_EQ(error.kind, CurveLapError::Kind::NonFiniteValue);
  EXPECT_EQ(std::string(error.what()), "this curve has a point that is not a finite number");
}

TEST(CurveLapSplineFit, TheFitsSettingsAreReadAsWritten) {
  for (std::string_view fit : {"bspline auto", "cspline natural after-ramp", "aspline automatic"}) {
    Function function = parsed(circleAsSpline(fit));
    ASSERT_TRUE(function.curves[0].splineFit.has_value());
    EXPECT_NE(printFunction(function).find("    spline " + std::string(fit) + "\n"),
              std::string::npos);
  }
  EXPECT_EQ(curve_lap_test::parseComplaint(circleAsSpline("zspline auto")),
            "5: expected a spline kind, found 'zspline'");
  EXPECT_EQ(curve_lap_test::parseComplaint(circleAsSpline("bspline sometimes")),
            "5: expected how a spline ends, found 'sometimes'");
  EXPECT_EQ(curve_lap_test::parseComplaint(circleAsSpline("bspline auto later")),
            "5: expected 'spline bspline|cspline|aspline automatic|natural|auto [after-ramp]'");
}

} // namespace
} // namespace cncc::ir
