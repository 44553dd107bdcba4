// move.spline in the IR: text round trip, the verifier's check of its
// blocks, and the interpreter following the spline geom's models say the
// controller builds.
#include "cncc/geom/controller_bspline.h"
#include "cncc/geom/curve_deviation.h"
#include "cncc/geom/interpolating_splines.h"
#include "cncc/ir/builder.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/printer.h"
#include "cncc/ir/spline_move.h"
#include "cncc/ir/verifier.h"
#include "text_round_trip.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

namespace cncc::ir {
namespace {

using ::testing::HasSubstr;
using ::testing::IsEmpty;

SplineBlockData cubicBSpline() {
  SplineBlockData data;
  data.kind = SplineKind::BSpline;
  data.degree = 3;
  data.points = {{10, 10, 0}, {20, -10, 0}, {30, 10, 0}, {40, 0, 0}};
  data.weights = {1, 2, 0.5, 1};
  data.intervals = {0, 0, 1, 1};
  return data;
}

SplineBlockData cSplineThrough() {
  SplineBlockData data;
  data.kind = SplineKind::CSpline;
  data.start = geom::SplineEndCondition::Tangent;
  data.end = geom::SplineEndCondition::Natural;
  data.points = {{10, 5, 0}, {20, 0, 0}, {30, 5, 0}, {40, 0, 0}};
  return data;
}

// A ramp's last chord along +x into (0, 0, -1), then the spline at z = -1.
Function splinePart(const SplineBlockData& data) {
  FunctionBuilder builder("spline");
  std::uint32_t table = builder.addTable(splineMoveTable(data));
  ValueId feed = builder.constant(300);
  ValueId depth = builder.constant(-1);
  builder.rapid(builder.constant(-5), builder.constant(0), builder.constant(5));
  builder.feed(builder.constant(-5), builder.constant(0), builder.constant(-0.5), feed);
  builder.feed(builder.constant(0), builder.constant(0), depth, feed);
  builder.spline(table, depth, feed);
  return builder.finish();
}

TEST(SplineIrTest, PrintsParsesAndVerifies) {
  for (const SplineBlockData& data : {cubicBSpline(), cSplineThrough()}) {
    Function function = splinePart(data);
    EXPECT_THAT(verifyFunction(function), IsEmpty());
    std::string text = printFunction(function);
    EXPECT_THAT(text, HasSubstr("move.spline @0, %"));
    std::optional<Function> parsed = test_support::parsedBack(text);
    ASSERT_TRUE(parsed);
    EXPECT_THAT(verifyFunction(*parsed), IsEmpty());
    std::optional<SplineBlockData> read = readSplineMoveTable(parsed->tables[0]);
    ASSERT_TRUE(read);
    EXPECT_EQ(read->points.size(), data.points.size());
    EXPECT_EQ(read->weights, data.weights);
    EXPECT_EQ(read->start, data.start);
  }
}

TEST(SplineIrTest, VerifierChecksTheBlocks) {
  Function shortTable = splinePart(cubicBSpline());
  shortTable.tables[0].pop_back(); // one interval short
  std::vector<std::string> problems = verifyFunction(shortTable);
  ASSERT_FALSE(problems.empty());
  EXPECT_THAT(problems.front(), HasSubstr("does not hold 4 points with weights and intervals"));
  Function badWeight = splinePart(cubicBSpline());
  badWeight.tables[0][5 + 12] = 0; // the first PW
  ASSERT_FALSE(verifyFunction(badWeight).empty());
  EXPECT_THAT(verifyFunction(badWeight).front(), HasSubstr("weight that is not positive"));
  Function badKind = splinePart(cSplineThrough());
  badKind.tables[0][0] = 7;
  ASSERT_FALSE(verifyFunction(badKind).empty());
  EXPECT_THAT(verifyFunction(badKind).front(), HasSubstr("kind (0 to 2)"));
  Function noTable = splinePart(cSplineThrough());
  noTable.tables.clear();
  ASSERT_FALSE(verifyFunction(noTable).empty());
  EXPECT_THAT(verifyFunction(noTable).front(), HasSubstr("table 0, which does not exist"));
}

TEST(SplineIrTest, ParserWantsATableAndTwoOperands) {
  ParseError error;
  EXPECT_FALSE(parseFunction("func @f() {\n  %0 = const 1\n  move.spline %0, %0\n}\n", error));
  EXPECT_EQ(error.line, 3);
  EXPECT_THAT(error.message, HasSubstr("move.spline @n"));
}

// The chords' points lie on the modelled spline: the B spline of the
// blocks from where the machine is; the C spline tangent to the ramp's
// last chord (+x), as the controller's BTAN.
TEST(SplineIrTest, InterpreterFollowsTheControllersSpline) {
  SplineBlockData bspline = cubicBSpline();
  std::vector<Eigen::Vector3d> lowered = bspline.points;
  for (Eigen::Vector3d& point : lowered) {
    point.z() = -1;
  }
  geom::NurbsCurve expectedB =
      geom::bsplineOfBlocks({0, 0, -1}, 3, lowered, bspline.weights, bspline.intervals);
  std::vector<Eigen::Vector3d> points = cSplineThrough().points;
  points.insert(points.begin(), Eigen::Vector3d(0, 0, 0));
  geom::SplineTransitions transitions;
  transitions.start = geom::SplineEndCondition::Tangent;
  transitions.startDirection = Eigen::Vector3d(1, 0, 0);
  transitions.end = geom::SplineEndCondition::Natural;
  for (Eigen::Vector3d& point : points) {
    point.z() = -1;
  }
  geom::PiecewisePolynomialCurve expectedC = geom::cSpline(points, transitions);
  geom::SplineTransitions natural = transitions;
  natural.start = geom::SplineEndCondition::Natural;
  geom::PiecewisePolynomialCurve naturalC = geom::cSpline(points, natural);
  struct Case {
    SplineBlockData data;
    const geom::Curve* expected;
  };
  for (const Case& c : {Case{bspline, &expectedB}, Case{cSplineThrough(), &expectedC}}) {
    ToolPath path = interpret(splinePart(c.data));
    std::vector<Eigen::Vector3d> chords{{0, 0, -1}};
    for (const MachineEvent& event : path.events) {
      if (event.splineTable != 0) {
        EXPECT_EQ(event.splineTable, 1u);
        EXPECT_EQ(event.splineStart, chords.size() == 1);
        EXPECT_EQ(event.feed, 300);
        chords.emplace_back(event.x, event.y, event.z);
      }
    }
    ASSERT_GT(chords.size(), 20u);
    EXPECT_TRUE(chords.back().isApprox(Eigen::Vector3d(40, 0, -1), 1e-12));
    EXPECT_LT(geom::measureDeviation(chords, *c.expected, {1e-6}).maxDeviation(), 2e-5);
  }
  // A natural start would be another curve: the ramp's direction counts.
  ToolPath path = interpret(splinePart(cSplineThrough()));
  std::vector<Eigen::Vector3d> chords{{0, 0, -1}};
  for (const MachineEvent& event : path.events) {
    if (event.splineTable != 0) {
      chords.emplace_back(event.x, event.y, event.z);
    }
  }
  EXPECT_GT(geom::measureDeviation(chords, naturalC, {1e-6}).maxDeviation(), 1e-3);
}

TEST(SplineIrTest, InterpreterStopsWhereTheControllerAlarms) {
  SplineBlockData data = cubicBSpline();
  data.intervals[0] = 1; // inside the clamped start of a cubic
  try {
    interpret(splinePart(data));
    FAIL() << "expected an error";
  } catch (const InterpreterError& error) {
    EXPECT_THAT(error.what(), HasSubstr("a spline move has no curve: PL of point 1"));
  }
}

} // namespace
} // namespace cncc::ir
