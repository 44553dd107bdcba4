// expand-curve-laps: a curve.lap written out as loops over tables gives
// the points its entry chooses, the ramp's heights, host point tables where
// marked, and refuses a curve whose points cannot be chosen.
#include "cncc/geom/composite_curve.h"
#include "cncc/geom/discretisation.h"
#include "cncc/geom/function_curve.h"
#include "cncc/geom/line_arc_curves.h"
#include "cncc/ir/builder.h"
#include "cncc/ir/curve_lap.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/verifier.h"
#include "curve_lap_fixtures.h"
#include "line_then_half_circle.h"

#include <gtest/gtest.h>

#include <cmath>

namespace cncc::ir {
namespace {

constexpr double pi = 3.14159265358979323846;

// A line from (0, 0) to (10, 0), then a half circle of radius r about
// (10, r) to (10, 2r): two pieces, the second's radius the parameter `r`.
struct LineThenHalfCircle {
  double radius = 5;
  bool radiusIsParameter = true; // or a number in the regions

  std::shared_ptr<const geom::Curve> geometry() const {
    return test_support::lineThenHalfCircleGeometry(radius);
  }

  CurveTableEntry entry(double tolerance) const {
    CurveTableEntry entry;
    entry.pieces = {{0, 0, 10}, {10, 0, pi}};
    entry.from = 0;
    entry.to = 10 + pi;
    entry.amount = tolerance;
    entry.geometry = geometry();
    return entry;
  }

  // The lap's two regions: the line's point at its own t, the circle's.
  void regions(FunctionBuilder& builder, ValueId t, ValueId r) const {
    ValueId zero = builder.constant(0);
    builder.curvePoint(t, zero, zero);
    zero = builder.constant(0); // each region its own
    if (!radiusIsParameter) {
      r = builder.constant(radius);
    }
    ValueId x = builder.binary(Opcode::Add, builder.constant(10),
                               builder.binary(Opcode::Mul, r, builder.unary(Opcode::Sin, t)));
    ValueId y = builder.binary(Opcode::Sub, r,
                               builder.binary(Opcode::Mul, r, builder.unary(Opcode::Cos, t)));
    builder.curvePoint(x, y, zero);
  }
};

// A function cutting the curve in one lap at z = -1 after a ramp lap from
// z = 0 when `ramp`.
Function lapFunction(const LineThenHalfCircle& shape, double tolerance, bool ramp) {
  FunctionBuilder builder("lap");
  ValueId r = builder.parameter(builder.addParameter("r", shape.radius));
  std::uint32_t curve = builder.addCurve(shape.entry(tolerance));
  ValueId feed = builder.constant(500);
  ValueId top = builder.constant(0);
  ValueId bottom = builder.constant(-1);
  builder.rapid(top, top, builder.constant(5));
  builder.feed(top, top, ramp ? top : bottom, feed);
  if (ramp) {
    shape.regions(builder, builder.beginCurveLap(curve, top, bottom, feed), r);
  }
  shape.regions(builder, builder.beginCurveLap(curve, bottom, bottom, feed), r);
  return builder.finish();
}

std::vector<MachineEvent> feeds(const Function& function) {
  return curve_lap_test::feedMoves(interpret(function));
}

TEST(CurveLapExpansion, MovesToThePointsTheChordWalkChoosesInLoopsOverTables) {
  LineThenHalfCircle shape;
  Function function = lapFunction(shape, 0.01, false);
  ASSERT_TRUE(expandCurveLaps(function));
  EXPECT_TRUE(verifyFunction(function).empty()) << verifyFunction(function).front();
  EXPECT_TRUE(function.curves.empty());
  for (const Instruction& instruction : function.instructions) {
    EXPECT_NE(instruction.opcode, Opcode::CurveLap);
  }
  geom::CurveSamples samples = geom::discretiseByChordTolerance(*shape.geometry(), 0.01);
  std::vector<MachineEvent> moves = feeds(function);
  ASSERT_EQ(moves.size(), samples.points.size()); // the plunge, then each point after the first
  for (std::size_t i = 1; i < samples.points.size(); ++i) {
    EXPECT_NEAR(moves[i].x, samples.points[i].x(), 1e-12) << i;
    EXPECT_NEAR(moves[i].y, samples.points[i].y(), 1e-12) << i;
    EXPECT_EQ(moves[i].z, -1) << i;
  }
  // The line's one point is its end, where the circle begins (the later
  // piece at a join): one run, one table of the circle's parameters.
  EXPECT_EQ(function.tables.size(), 1u);
}

TEST(CurveLapExpansion, TheRegionsStillReadTheParameter) {
  // The points are chosen at r = 5, the regions evaluate them at the value run with.
  LineThenHalfCircle shape;
  Function function = lapFunction(shape, 0.01, false);
  ASSERT_TRUE(expandCurveLaps(function));
  InterpreterOptions options;
  options.parameters["r"] = 6;
  std::vector<MachineEvent> moves = curve_lap_test::feedMoves(interpret(function, options));
  EXPECT_NEAR(moves.back().x, 10, 1e-9);
  EXPECT_NEAR(moves.back().y, 12, 1e-9);
}

TEST(CurveLapExpansion, ARampLapDescendsInProportionToTheLengthDone) {
  LineThenHalfCircle shape;
  Function function = lapFunction(shape, 0.01, true);
  ASSERT_TRUE(expandCurveLaps(function));
  EXPECT_TRUE(verifyFunction(function).empty());
  std::vector<MachineEvent> moves = feeds(function);
  double length = 10 + pi * shape.radius;
  // The ramp lap's moves follow the plunge; the level lap's the ramp lap's.
  std::size_t points = (moves.size() - 1) / 2;
  for (std::size_t i = 1; i <= points; ++i) {
    const MachineEvent& move = moves[i];
    // On the circle, sin s = (x - 10) / r and cos s = (r - y) / r.
    double done =
        move.y == 0 ? move.x : 10 + shape.radius * std::atan2(move.x - 10, shape.radius - move.y);
    EXPECT_NEAR(move.z, -std::min(1.0, done / length), 1e-6) << i;
  }
  EXPECT_EQ(moves[points].z, -1);
  EXPECT_EQ(moves.back().z, -1);
  // The circle's parameters and the ramp's progress.
  EXPECT_EQ(function.tables.size(), 2u);
}

TEST(CurveLapExpansion, MarkedRegionsWithoutParametersBecomePointTables) {
  LineThenHalfCircle shape;
  shape.radiusIsParameter = false;
  Function plain = lapFunction(shape, 0.01, false);
  Function tabled = plain;
  tabled.curves[0].hostPointRegions = {1};
  ASSERT_TRUE(expandCurveLaps(plain));
  ASSERT_TRUE(expandCurveLaps(tabled));
  // The circle's parameters, then its x and y (z is a number everywhere).
  EXPECT_EQ(tabled.tables.size(), 3u);
  for (const Instruction& instruction : tabled.instructions) {
    EXPECT_NE(instruction.opcode, Opcode::Sin); // the host computed the points
  }
  std::vector<MachineEvent> expected = feeds(plain);
  std::vector<MachineEvent> moves = feeds(tabled);
  ASSERT_EQ(moves.size(), expected.size());
  for (std::size_t i = 0; i < moves.size(); ++i) {
    EXPECT_EQ(moves[i].x, expected[i].x) << i;
    EXPECT_EQ(moves[i].y, expected[i].y) << i;
    EXPECT_EQ(moves[i].z, expected[i].z) << i;
  }
}

// An entry of points as numbers: a feed move to each, the numbers the
// regions compute at the chosen parameters, no table and no loop; a ramp
// lap descends by the same progress as the tables'.
TEST(CurveLapExpansion, PointsAsNumbersAreFeedMovesToNumbers) {
  LineThenHalfCircle shape;
  shape.radiusIsParameter = false;
  for (bool ramp : {false, true}) {
    Function plain = lapFunction(shape, 0.01, ramp);
    Function numbers = plain;
    numbers.curves[0].pointsAsNumbers = true;
    ASSERT_TRUE(expandCurveLaps(plain));
    ASSERT_TRUE(expandCurveLaps(numbers));
    EXPECT_TRUE(verifyFunction(numbers).empty());
    EXPECT_TRUE(numbers.tables.empty());
    for (const Instruction& instruction : numbers.instructions) {
      EXPECT_NE(instruction.opcode, Opcode::Loop);
      EXPECT_NE(instruction.opcode, Opcode::Sin);
    }
    std::vector<MachineEvent> expected = feeds(plain);
    std::vector<MachineEvent> moves = feeds(numbers);
    ASSERT_EQ(moves.size(), expected.size()) << ramp;
    for (std::size_t i = 0; i < moves.size(); ++i) {
      EXPECT_EQ(moves[i].x, expected[i].x) << i;
      EXPECT_EQ(moves[i].y, expected[i].y) << i;
      EXPECT_NEAR(moves[i].z, expected[i].z, 1e-12) << i;
    }
  }
}

TEST(CurveLapExpansion, AMarkedRegionThatReadsAParameterStaysInTheProgram) {
  LineThenHalfCircle shape;
  Function function = lapFunction(shape, 0.01, false);
  function.curves[0].hostPointRegions = {1};
  ASSERT_TRUE(expandCurveLaps(function));
  EXPECT_EQ(function.tables.size(), 1u);
}

TEST(CurveLapExpansion, ACurveWithoutFinitePointsIsAnErrorAtTheCurve) {
  LineThenHalfCircle shape;
  Function function = lapFunction(shape, 0.01, false);
  CurveTableEntry& entry = function.curves[0];
  entry.geometry = std::make_shared<geom::FunctionCurve>(geom::FunctionCurve::fromCoordinates(
      {0, 1}, [](double t) { return t < 0.5 ? t : std::nan(""); }, [](double) { return 0.0; }));
  entry.pieces = {{0, 0, 0.5}, {0.5, 0, 0.5}};
  entry.to = 1;
  entry.curveSpan = frontend::SourceSpan{{}, 7, 10};
  try {
    expandCurveLaps(function);
    FAIL() << "expected a CurveLapError";
  } catch (const CurveLapError& error) {
    EXPECT_EQ(error.span.begin, 7u);
    EXPECT_EQ(error.kind, CurveLapError::Kind::DegenerateCurve);
  }
}

TEST(CurveLapExpansion, AFunctionWithoutLapsIsUnchanged) {
  FunctionBuilder builder("none");
  ValueId zero = builder.constant(0);
  builder.rapid(zero, zero, zero);
  Function function = builder.finish();
  EXPECT_FALSE(expandCurveLaps(function));
  EXPECT_EQ(function.instructions.size(), 2u);
}

} // namespace
} // namespace cncc::ir
