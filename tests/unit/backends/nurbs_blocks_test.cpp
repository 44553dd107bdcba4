// G06.2 NURBS blocks (Fanuc, Mitsubishi M80): the printer's rules, and the
// printed blocks run on the virtual controller, which evaluates the NURBS
// from the blocks as it reads them, compared with the source curve.
//
// What is asserted: every point the controller executes is within 1e-6 mm of
// the NURBS through the control points as the blocks give them, and within
// 1e-6 mm plus the IS-B rounding of the control points (half of 0.001 mm on
// each of X and Y: 7.1e-4 mm, a NURBS moving no further than its control
// points) of the source NURBS.
#include "cncc/backends/controller_profile.h"
#include "cncc/backends/gcode_writer.h"
#include "cncc/backends/nurbs_blocks.h"
#include "cncc/backends/sim_operation_count.h"
#include "cncc/backends/virtual_controller.h"
#include "cncc/geom/bspline_fitting.h"
#include "cncc/geom/deviation.h"
#include "cncc/geom/line_arc_curves.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace cncc::backends {
namespace {

using ::testing::HasSubstr;

geom::NurbsCurve sProfile(double w6 = 3) {
  std::vector<Eigen::Vector3d> points{
      {25, 50, 0},           {42.8735, 24.1467, 0},  {70.5832, 72.3597, 0},
      {86.608, 165.3624, 0}, {112.4532, 38.3852, 0}, {132.4671, 35.1148, 0},
      {175, 150, 0}};
  geom::KnotVector knots({0, 0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1, 1}, 3);
  return geom::NurbsCurve(std::move(knots), std::move(points), {1, 1, 1, 1, 1, w6, 1});
}

// Control points on the 0.001 mm grid, weights and knots exact in 4 decimals:
// nothing for the controller to round.
geom::NurbsCurve gridCurve() {
  std::vector<Eigen::Vector3d> points{
      {0, 0, 0}, {10, 20, 0}, {30, -5.5, 0}, {45.125, 12, 0}, {60, 0, 0}};
  geom::KnotVector knots({0, 0, 0, 0, 0.5, 1, 1, 1, 1}, 3);
  return geom::NurbsCurve(std::move(knots), std::move(points), {1, 2, 0.5, 1.5, 1});
}

NurbsBlockOptions optionsFor(const geom::NurbsCurve& curve, NurbsDialect dialect, double z) {
  NurbsBlockOptions options;
  options.dialect = dialect;
  options.z = z;
  options.feed = 300;
  options.currentPosition = curve.controlPoints().front() + Eigen::Vector3d(0, 0, z);
  return options;
}

std::string numberText(double value) {
  return formatGcodeNumber(value, 3);
}

// A program that reaches the first control point, plunges, runs the blocks
// and retracts.
std::string programAround(const NurbsBlocks& blocks, const Eigen::Vector3d& start) {
  std::string text = "%\nO1000\nG21 G17 G90 G40\n";
  text += "G00 Z5.\nG00 X" + numberText(start.x()) + " Y" + numberText(start.y()) + "\n";
  text += "G01 Z" + numberText(start.z()) + " F300.\n";
  for (const std::string& line : blocks.lines) {
    text += line + "\n";
  }
  text += "G00 Z5.\nM30\n%\n";
  return text;
}

// The points the controller executed along the NURBS (the feed moves after
// the plunge, up to the retract).
std::vector<Eigen::Vector3d> executedNurbs(const sim::SimulationResult& result, double z) {
  std::vector<Eigen::Vector3d> points;
  for (const sim::ExecutedEvent& event : result.path.events) {
    if (event.kind == sim::ExecutedEvent::Kind::Feed && event.start.z == z && event.end.z == z) {
      if (points.empty()) {
        points.emplace_back(event.start.x, event.start.y, 0);
      }
      points.emplace_back(event.end.x, event.end.y, 0);
    }
  }
  return points;
}

// The largest distance from an executed point to the curve.
double largestPointDistance(const std::vector<Eigen::Vector3d>& points, const geom::Curve& curve) {
  geom::CurveProximity proximity(curve, 1e-8);
  double largest = 0;
  for (const Eigen::Vector3d& point : points) {
    largest = std::max(largest, proximity.closestPoint(point).distance);
  }
  return largest;
}

sim::SimulationResult run(const std::string& text, std::string_view profile) {
  sim::SimulationResult result = sim::simulateProgram(text, *findControllerProfile(profile));
  if (result.error) {
    ADD_FAILURE() << "line " << result.error->line() << ": " << result.error->what() << "\n"
                  << text;
  }
  return result;
}

TEST(NurbsBlocks, FanucBlocksFollowTheManualsLayout) {
  geom::NurbsCurve curve = sProfile();
  NurbsBlocks blocks = writeNurbsBlocks(curve, optionsFor(curve, NurbsDialect::Fanuc, -1));
  ASSERT_TRUE(blocks.errors.empty()) << blocks.errors.front();
  ASSERT_EQ(blocks.lines.size(), 7u + 4u); // a block per point, then the last 4 knots
  EXPECT_EQ(blocks.lines[0], "G06.2 P4 K0. X25. Y50. Z-1. R1. F300.");
  // 42.8735 is a little below it in binary: it rounds down.
  EXPECT_EQ(blocks.lines[1], "K0. X42.873 Y24.147 Z-1. R1.");
  EXPECT_EQ(blocks.lines[5], "K0.5 X132.467 Y35.115 Z-1. R3.");
  EXPECT_EQ(blocks.lines[7], "K1.");
  EXPECT_EQ(blocks.lines[10], "K1.");
}

TEST(NurbsBlocks, MitsubishiStartsHighSpeedModeAndMapsKnots) {
  geom::NurbsCurve curve = sProfile();
  NurbsBlocks blocks = writeNurbsBlocks(curve, optionsFor(curve, NurbsDialect::Mitsubishi, -1));
  ASSERT_TRUE(blocks.errors.empty()) << blocks.errors.front();
  ASSERT_EQ(blocks.lines.size(), 1u + 7u + 4u);
  EXPECT_EQ(blocks.lines[0], "G05 P10000");
  EXPECT_EQ(blocks.lines[1], "G06.2 P4 K1. X25. Y50. Z-1. R1. F300.");
  EXPECT_EQ(blocks.lines[5], "K25.5 X112.453 Y38.385 Z-1. R1.");
  EXPECT_EQ(blocks.lines.back(), "K99.");
  for (double knot : blocks.knots) {
    EXPECT_GE(knot, 0.0001);
    EXPECT_LE(knot, 99.9999);
  }
}

TEST(NurbsBlocks, MitsubishiScalesLargeWeightsTogether) {
  geom::NurbsCurve curve = sProfile(300); // 300 is beyond 99.9999
  NurbsBlocks blocks = writeNurbsBlocks(curve, optionsFor(curve, NurbsDialect::Mitsubishi, 0));
  ASSERT_TRUE(blocks.errors.empty()) << blocks.errors.front();
  EXPECT_NEAR(blocks.weights[5], 99.9999, 1e-9);
  // The 4 decimals of the scaled weight 1 (0.3333) keep the ratio to 1e-4.
  EXPECT_NEAR(blocks.weights[5] / blocks.weights[0], 300, 300 * 1e-4);
  // Run: the scaled curve is the same curve.
  sim::SimulationResult result = run(programAround(blocks, {25, 50, 0}), "m80");
  EXPECT_LE(largestPointDistance(executedNurbs(result, 0), curve), 7.1e-4 + 1e-6);
}

TEST(NurbsBlocks, RulesAreErrorsNamingTheRule) {
  geom::NurbsCurve curve = sProfile();
  NurbsBlockOptions options = optionsFor(curve, NurbsDialect::Fanuc, 0);
  options.currentPosition = {0, 0, 5};
  NurbsBlocks notHere = writeNurbsBlocks(curve, options);
  ASSERT_EQ(notHere.errors.size(), 1u);
  EXPECT_THAT(notHere.errors[0], HasSubstr("first control point (25., 50., 0.) must be the "
                                           "current position (0., 0., 5.)"));
  EXPECT_TRUE(notHere.lines.empty());

  options = optionsFor(curve, NurbsDialect::Fanuc, 0);
  options.cutterCompensation = true;
  EXPECT_THAT(writeNurbsBlocks(curve, options).errors.at(0), HasSubstr("G41/G42 must be off"));

  std::vector<Eigen::Vector3d> six(6, Eigen::Vector3d(1, 2, 0));
  six.back() = {9, 9, 0};
  geom::NurbsCurve quintic(geom::KnotVector::clampedUniform(5, 6), six,
                           std::vector<double>(6, 1.0));
  NurbsBlocks degreeFive = writeNurbsBlocks(quintic, optionsFor(quintic, NurbsDialect::Fanuc, 0));
  EXPECT_THAT(degreeFive.errors.at(0), HasSubstr("the order P must be 2 to 4; this curve has "
                                                 "order 6"));

  std::vector<Eigen::Vector3d> zigzag{{0, 0, 0}, {1, 1, 0}, {2, 0, 0},
                                      {3, 1, 0}, {4, 0, 0}, {5, 1, 0}};
  std::vector<double> unitWeights(6, 1.0);
  geom::NurbsCurve unclamped(geom::KnotVector({0, 1, 2, 3, 4, 5, 6, 7, 8, 9}, 3), zigzag,
                             unitWeights);
  NurbsBlockOptions unclampedOptions = optionsFor(unclamped, NurbsDialect::Fanuc, 0);
  EXPECT_THAT(writeNurbsBlocks(unclamped, unclampedOptions).errors.at(0),
              HasSubstr("the first and the last 4 knots must be equal (clamped ends)"));
}

TEST(NurbsBlocks, SymbolicWeightsStayVariables) {
  geom::NurbsCurve curve = sProfile();
  NurbsBlockOptions options = optionsFor(curve, NurbsDialect::Fanuc, 0);
  options.weightVariables = {"", "", "", "", "", "#3", ""};
  NurbsBlocks blocks = writeNurbsBlocks(curve, options);
  ASSERT_TRUE(blocks.errors.empty());
  EXPECT_EQ(blocks.lines[5], "K0.5 X132.467 Y35.115 Z0. R#3");
}

// The Fanuc options for blocks at a pass loop's height held in #5.
NurbsBlockOptions atVariableHeight(const geom::NurbsCurve& curve) {
  NurbsBlockOptions options = optionsFor(curve, NurbsDialect::Fanuc, 0);
  options.zCoordinate = "#5";
  options.zOperand = "#5";
  return options;
}

// A pass loop's height the program computes: Z its variable on every block
// (above a control point of its own z, their sum), the first point's X and
// Y still checked against the current position.
TEST(NurbsBlocks, ComputedHeightStaysItsVariable) {
  geom::NurbsCurve curve = sProfile();
  NurbsBlockOptions options = atVariableHeight(curve);
  NurbsBlocks blocks = writeNurbsBlocks(curve, options);
  ASSERT_TRUE(blocks.errors.empty()) << blocks.errors.front();
  EXPECT_EQ(blocks.lines[0], "G06.2 P4 K0. X25. Y50. Z#5 R1. F300.");
  EXPECT_EQ(blocks.lines[5], "K0.5 X132.467 Y35.115 Z#5 R3.");
  std::vector<Eigen::Vector3d> raised = curve.controlPoints();
  raised[1].z() = -1.5;
  geom::NurbsCurve dipped(curve.knots(), raised, curve.weights());
  blocks = writeNurbsBlocks(dipped, options);
  ASSERT_TRUE(blocks.errors.empty()) << blocks.errors.front();
  EXPECT_EQ(blocks.lines[1], "K0. X42.873 Y24.147 Z[#5-1.5] R1.");
  options.currentPosition.x() += 1;
  EXPECT_FALSE(writeNurbsBlocks(curve, options).errors.empty());
}

// The blocks in a pass loop at its height Z#5, run by the controller: each
// trip cuts the curve at its own depth, and the loop's cost is counted per
// feed block (the plunge and the NURBS, not the NURBS's interpolated moves).
TEST(NurbsBlocks, PassLoopRunsTheBlocksAtEachHeight) {
  geom::NurbsCurve curve = sProfile();
  NurbsBlocks blocks = writeNurbsBlocks(curve, atVariableHeight(curve));
  ASSERT_TRUE(blocks.errors.empty()) << blocks.errors.front();
  std::string text = "%\nO1000\nG21 G17 G90 G40\n#4=1.\nWHILE [#4 LE 3.] DO1\n#5=-#4\n"
                     "G00 Z5.\nG00 X25. Y50.\nG01 Z#5 F300.\n";
  for (const std::string& line : blocks.lines) {
    text += line + "\n";
  }
  text += "G00 Z5.\n#4=#4+1.\nEND1\nM30\n%\n";
  const ControllerProfile& profile = *findControllerProfile("fanuc");
  sim::SimulationResult result = run(text, "fanuc");
  for (double z : {-1.0, -2.0, -3.0}) {
    std::vector<Eigen::Vector3d> points = executedNurbs(result, z);
    ASSERT_GT(points.size(), 50u) << z;
    EXPECT_LT(largestPointDistance(points, curve), 1e-3) << z;
  }
  sim::LoopOperationCounts counts =
      sim::countLoopOperations(sim::readProgram(text, profile), result);
  EXPECT_EQ(counts.feedMoves, 6u);
}

// The exactness check: nothing to round, so the executed points are on the
// source NURBS to 1e-6 mm, and the path covers it from end to end.
TEST(NurbsBlocks, ControllerEvaluatesTheBlocksExactly) {
  geom::NurbsCurve curve = gridCurve();
  for (auto [dialect, profile] :
       {std::pair{NurbsDialect::Fanuc, "fanuc"}, std::pair{NurbsDialect::Mitsubishi, "m80"}}) {
    SCOPED_TRACE(profile);
    NurbsBlocks blocks = writeNurbsBlocks(curve, optionsFor(curve, dialect, -2));
    ASSERT_TRUE(blocks.errors.empty()) << blocks.errors.front();
    sim::SimulationResult result = run(programAround(blocks, {0, 0, -2}), profile);
    std::vector<Eigen::Vector3d> points = executedNurbs(result, -2);
    ASSERT_GT(points.size(), 50u);
    EXPECT_LT(largestPointDistance(points, curve), 1e-6);
    EXPECT_LT((points.back() - Eigen::Vector3d(60, 0, 0)).norm(), 1e-9);
    // Chords of about 1e-5 mm sagitta: the path is the curve to 2e-5 mm.
    EXPECT_LT(geom::measureDeviation(points, curve, {1e-7}).maxDeviation(), 2e-5);
  }
}

TEST(NurbsBlocks, SProfileOnBothControllersWithinTheRounding) {
  geom::NurbsCurve curve = sProfile();
  for (auto [dialect, profile] :
       {std::pair{NurbsDialect::Fanuc, "fanuc"}, std::pair{NurbsDialect::Mitsubishi, "m80"}}) {
    SCOPED_TRACE(profile);
    NurbsBlocks blocks = writeNurbsBlocks(curve, optionsFor(curve, dialect, -1));
    ASSERT_TRUE(blocks.errors.empty());
    sim::SimulationResult result = run(programAround(blocks, {25, 50, -1}), profile);
    std::vector<Eigen::Vector3d> points = executedNurbs(result, -1);
    // Against the NURBS through the control points as printed (IS-B).
    std::vector<Eigen::Vector3d> rounded;
    for (const Eigen::Vector3d& point : curve.controlPoints()) {
      rounded.emplace_back(std::stod(numberText(point.x())), std::stod(numberText(point.y())), 0);
    }
    geom::NurbsCurve printed(curve.knots(), rounded, curve.weights());
    EXPECT_LT(largestPointDistance(points, printed), 1e-6);
    EXPECT_LE(largestPointDistance(points, curve), 7.1e-4 + 1e-6);
  }
}

TEST(NurbsBlocks, AnalyticCurvesAreFittedWithinTheTolerance) {
  geom::ArcCurve arc({0, 0}, 20, 0, 1.5 * std::numbers::pi);
  geom::BSplineFitOptions fit;
  fit.degree = 3;
  fit.tolerance = 0.004;
  geom::NurbsCurve fitted = geom::fitBSpline(arc, fit).spline;
  NurbsBlocks blocks = writeNurbsBlocks(fitted, optionsFor(fitted, NurbsDialect::Fanuc, 0));
  ASSERT_TRUE(blocks.errors.empty());
  sim::SimulationResult result = run(programAround(blocks, {20, 0, 0}), "fanuc");
  std::vector<Eigen::Vector3d> points = executedNurbs(result, 0);
  // The fit's tolerance plus the rounding of its control points, plus the chords.
  EXPECT_LE(geom::measureDeviation(points, arc, {1e-6}).maxDeviation(), 0.004 + 7.1e-4 + 1e-5);
  EXPECT_LT(blocks.lines.size(), 40u);
}

TEST(NurbsBlocks, ControllerRefusesBrokenNurbs) {
  const ControllerProfile& m80 = *findControllerProfile("m80");
  const ControllerProfile& fanuc = *findControllerProfile("fanuc");
  auto errorOf = [](const std::string& body, const ControllerProfile& profile) {
    sim::SimulationResult result =
        sim::simulateProgram("%\nO1000\nG90 G00 X0. Y0. Z0.\n" + body + "M30\n%\n", profile);
    return result.error ? std::string(result.error->what()) : std::string("no error");
  };
  std::string curve = "G06.2 P3 K1. X0. Y0. R1. F100.\nK1. X1. Y1. R1.\nK1. X2. Y0. R1.\n"
                      "K2.\nK2.\nK2.\n";
  EXPECT_EQ(errorOf(curve, fanuc), "no error");
  EXPECT_THAT(errorOf(curve, m80), HasSubstr("needs G05 P10000 first"));
  EXPECT_EQ(errorOf("G05 P10000\n" + curve, m80), "no error");
  EXPECT_THAT(errorOf("G06.2 P3 K0. X0. Y0. F100.\nK0. X1. Y1.\nK0. X2. Y0.\nK1.\nK1.\n", fanuc),
              HasSubstr("has 5 knots; 3 control points of order 3 need 6"));
  EXPECT_THAT(
      errorOf("G06.2 P3 K0. X5. Y0. F100.\nK0. X1. Y1.\nK0. X2. Y0.\nK1.\nK1.\nK1.\n", fanuc),
      HasSubstr("is not the current position"));
  EXPECT_THAT(
      errorOf("G06.2 P3 K0. X0. Y0. F100.\nK0. X1. Y1.\nK0.5 X2. Y0.\nK1.\nK1.\nK1.\n", fanuc),
      HasSubstr("the first and last 3 knots must be equal"));
  EXPECT_THAT(errorOf("G06.2 P3 K0. X0. Y0. F100.\nK0. X1. Y1. M08\n", fanuc),
              HasSubstr("no auxiliary function"));
  EXPECT_THAT(errorOf("G05 P10000\nG06.2 P3 K0.00001 X0. Y0. F100.\n", m80),
              HasSubstr("K has 5 decimals"));
}

} // namespace
} // namespace cncc::backends
