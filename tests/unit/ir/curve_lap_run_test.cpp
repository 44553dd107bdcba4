// curve.lap run: the curve its regions compute (lapCurve) and the
// interpreter running it (its text and rules: curve_lap_ir_test.cpp).
#include "cncc/geom/composite_curve.h"
#include "cncc/geom/function_curve.h"
#include "cncc/geom/line_arc_curves.h"
#include "cncc/ir/builder.h"
#include "cncc/ir/curve_lap.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/printer.h"
#include "cncc/ir/verifier.h"
#include "line_then_half_circle.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "curve_lap_fixtures.h"

namespace cncc::ir {
namespace {

using namespace curve_lap_test;
using ::testing::Contains;
using ::testing::HasSubstr;
using ::testing::IsEmpty;

// ---------------------------------------------------------------- lapCurve

TEST(IrCurveLapCurve, CirclePieceFromItsRegion) {
  Function function = parsed(circleText);
  std::shared_ptr<const geom::Curve> curve =
      lapCurve(function, onlyLap(function), [](ValueId) { return 5.0; });
  EXPECT_EQ(curve->domain().t0, 0);
  EXPECT_EQ(curve->domain().t1, 2 * pi);
  for (double t : {0.0, 0.3, pi / 2, 2.0, pi, 5.0, 2 * pi}) {
    Eigen::Vector3d point = curve->point(t);
    EXPECT_NEAR(point.x(), 5 * std::cos(t), 1e-14) << t;
    EXPECT_NEAR(point.y(), 5 * std::sin(t), 1e-14) << t;
    EXPECT_EQ(point.z(), 0) << t;
    // Finite differences of the region's points: the circle's tangent.
    EXPECT_NEAR(curve->derivative(t).x(), -5 * std::sin(t), 1e-6) << t;
  }
}

TEST(IrCurveLapCurve, KnotSpansAreRegionsAtTheirOwnU) {
  Function function = parsed(pathText);
  std::shared_ptr<const geom::Curve> curve =
      lapCurve(function, onlyLap(function), [](ValueId) { return std::nullopt; });
  EXPECT_EQ(curve->domain().t0, 0);
  EXPECT_EQ(curve->domain().t1, 13);
  for (double t : {0.0, 4.5, 10.0, 10.25, 11.0, 11.5, 12.0, 12.75, 13.0}) {
    EXPECT_NEAR(curve->point(t).x(), t, 1e-12) << t;
    EXPECT_EQ(curve->point(t).y(), 0) << t;
  }
  EXPECT_EQ(curve->breakpoints(), (std::vector<double>{0, 10, 11, 12, 13}));
}

// A line from (0, 0) to (10, 0), then a half circle of radius r about
// (10, r): the regions' arithmetic, and the same curve from geom.
Function lineThenHalfCircle(std::shared_ptr<const geom::Curve> geometry = nullptr) {
  FunctionBuilder builder("path");
  ValueId r = builder.parameter(builder.addParameter("r", 5));
  CurveTableEntry entry;
  entry.pieces = {{0, 0, 10}, {10, 0, pi}};
  entry.to = 10 + pi;
  entry.amount = 0.005;
  entry.geometry = std::move(geometry);
  std::uint32_t curve = builder.addCurve(entry);
  ValueId zero = builder.constant(0);
  ValueId t = builder.beginCurveLap(curve, builder.constant(0), builder.constant(-2),
                                    builder.constant(400));
  builder.curvePoint(t, zero, zero);
  ValueId x = builder.binary(Opcode::Add, builder.constant(10),
                             builder.binary(Opcode::Mul, r, builder.unary(Opcode::Sin, t)));
  ValueId y =
      builder.binary(Opcode::Sub, r, builder.binary(Opcode::Mul, r, builder.unary(Opcode::Cos, t)));
  builder.curvePoint(x, y, zero);
  return builder.finish();
}

TEST(IrCurveLapCurve, TwoPiecePathFromItsRegions) {
  Function function = lineThenHalfCircle();
  std::shared_ptr<const geom::Curve> curve =
      lapCurve(function, onlyLap(function), [](ValueId) { return 5.0; });
  std::shared_ptr<const geom::Curve> expected = test_support::lineThenHalfCircleGeometry(5);
  EXPECT_EQ(curve->domain().t0, 0);
  EXPECT_EQ(curve->domain().t1, 10 + pi);
  EXPECT_EQ(geom::piecesOf(*curve).size(), 2u);
  for (int k = 0; k <= 40; ++k) {
    double t = (10 + pi) * k / 40;
    EXPECT_NEAR((curve->point(t) - expected->point(t)).norm(), 0, 1e-13) << t;
    EXPECT_EQ(function.curves[0].locate(t).region, t < 10 ? 0u : 1u) << t;
  }
  EXPECT_NEAR((curve->point(10 + pi / 2) - Eigen::Vector3d(15, 5, 0)).norm(), 0, 1e-13);
  // The geometry, when the entry has one, is the curve.
  Function withGeometry = lineThenHalfCircle(expected);
  EXPECT_EQ(lapCurve(withGeometry, onlyLap(withGeometry), {}), expected);
}

TEST(IrCurveLapCurve, UnknownOutsideValueIsAnErrorAtTheCurve) {
  Function function = lineThenHalfCircle();
  frontend::SourceSpan span;
  span.begin = 7;
  function.curves[0].curveSpan = span;
  try {
    lapCurve(function, onlyLap(function), [](ValueId) { return std::nullopt; });
    FAIL() << "no error";
  } catch (const CurveLapError& error) {
    EXPECT_EQ(error.kind, CurveLapError::Kind::DegenerateCurve);
    EXPECT_EQ(error.span.begin, 7u);
    EXPECT_THAT(error.what(), HasSubstr("a value not known here (the result of 'param'"));
  }
}

// The line's region ends at x = 9, the half circle starts at x = 10.
TEST(IrCurveLapCurve, PiecesThatDoNotJoinAreAnError) {
  Function function = lineThenHalfCircle();
  function.curves[0].pieces[0].to = 9;
  function.curves[0].pieces[1].start = 9;
  function.curves[0].to = 9 + pi;
  try {
    lapCurve(function, onlyLap(function), [](ValueId) { return 5.0; });
    FAIL() << "no error";
  } catch (const CurveLapError& error) {
    EXPECT_EQ(error.kind, CurveLapError::Kind::DegenerateCurve);
    EXPECT_THAT(error.what(), HasSubstr("do not join"));
  }
}

// The composite curve's parameter must be the one locate() reads.
TEST(IrCurveLapCurve, PieceStartsMustBeThePiecesLengths) {
  Function function = lineThenHalfCircle();
  function.curves[0].pieces[1].start = 9;
  try {
    lapCurve(function, onlyLap(function), [](ValueId) { return 5.0; });
    FAIL() << "no error";
  } catch (const CurveLapError& error) {
    EXPECT_THAT(error.what(), HasSubstr("piece 1 of the curve starts at 9 in the table but at 10"));
  }
}

// ---------------------------------------------------------------- interpreter

TEST(IrCurveLapInterpreter, CircleLapMovesAlongTheRegionsPoints) {
  for (double r : {5.0, 20.0}) {
    Function function = parsed(circleText);
    InterpreterOptions options;
    options.parameters["r"] = r;
    std::vector<MachineEvent> moves = feedMoves(interpret(function, options));
    std::vector<double> parameters = lapParameters(
        function.curves[0], *lapCurve(function, onlyLap(function), [r](ValueId) { return r; }));
    ASSERT_EQ(moves.size(), parameters.size() - 1);
    Eigen::Vector2d previous(r, 0);
    for (std::size_t k = 0; k < moves.size(); ++k) {
      EXPECT_NEAR(moves[k].x, r * std::cos(parameters[k + 1]), 1e-12);
      EXPECT_NEAR(moves[k].y, r * std::sin(parameters[k + 1]), 1e-12);
      EXPECT_EQ(moves[k].z, -1);
      EXPECT_EQ(moves[k].feed, 500);
      // The chord keeps the tolerance: its middle within 0.01 of the circle.
      Eigen::Vector2d point(moves[k].x, moves[k].y);
      EXPECT_LE(r - ((point + previous) / 2).norm(), 0.01 + 1e-9);
      previous = point;
    }
    EXPECT_NEAR(moves.back().x, r, 1e-12);
    EXPECT_NEAR(moves.back().y, 0, 1e-12);
  }
}

TEST(IrCurveLapInterpreter, RampLapDescendsByTheLapsProgress) {
  Function function = parsed(pathText);
  std::vector<MachineEvent> moves = feedMoves(interpret(function));
  const CurveTableEntry& entry = function.curves[0];
  std::shared_ptr<const geom::Curve> curve =
      lapCurve(function, onlyLap(function), [](ValueId) { return std::nullopt; });
  std::vector<double> parameters = lapParameters(entry, *curve);
  std::vector<double> progress = lapProgress(entry, *curve, parameters);
  ASSERT_EQ(moves.size(), 7u); // eight samples, the first where the tool is
  for (std::size_t k = 0; k < moves.size(); ++k) {
    EXPECT_NEAR(moves[k].x, 13.0 * static_cast<double>(k + 1) / 7, 1e-12);
    EXPECT_EQ(moves[k].z, 0 + (-1 - 0) * progress[k + 1]);
    EXPECT_NEAR(moves[k].z, -moves[k].x / 13, 1e-9); // a line: progress is the length done
    EXPECT_EQ(moves[k].feed, 100);
  }
  EXPECT_NEAR(moves.back().z, -1, 1e-12);
}

TEST(IrCurveLapInterpreter, TheSameLapInEachPassGoesTheSameWay) {
  Function function = passesAroundTwoPieces();
  std::vector<MachineEvent> moves = feedMoves(interpret(function));
  ASSERT_FALSE(moves.empty());
  std::size_t perPass = moves.size() / 3;
  ASSERT_EQ(perPass * 3, moves.size());
  for (std::size_t k = 0; k < perPass; ++k) {
    for (std::size_t pass = 1; pass < 3; ++pass) {
      EXPECT_EQ(moves[pass * perPass + k].x, moves[k].x);
      EXPECT_EQ(moves[pass * perPass + k].y, moves[k].y);
      EXPECT_EQ(moves[pass * perPass + k].z, -static_cast<double>(pass + 1));
    }
  }
}

TEST(IrCurveLapInterpreter, WithAndWithoutGeometryTheSamePoints) {
  // The geometry and the regions compute the same points; chosen on
  // either, the moves go to the regions' points.
  std::vector<MachineEvent> fromRegions = feedMoves(interpret(lineThenHalfCircle()));
  std::vector<MachineEvent> fromGeometry =
      feedMoves(interpret(lineThenHalfCircle(test_support::lineThenHalfCircleGeometry(5))));
  ASSERT_GT(fromGeometry.size(), 20u);
  ASSERT_NEAR(static_cast<double>(fromRegions.size()), static_cast<double>(fromGeometry.size()), 2);
  for (const std::vector<MachineEvent>& moves : {fromRegions, fromGeometry}) {
    for (const MachineEvent& move : moves) {
      double offCircle = std::hypot(move.x - 10, move.y - 5) - 5;
      EXPECT_TRUE(move.y == 0 || std::abs(offCircle) < 1e-12) << move.x;
    }
    EXPECT_NEAR(moves.back().x, 10, 1e-12);
    EXPECT_NEAR(moves.back().y, 10, 1e-12);
    EXPECT_NEAR(moves.back().z, -2, 1e-12);
  }
}

// The interpreter and expand-curve-laps choose the same points and raise
// them alike: the path before and after expansion is the same to the bit,
// with the entry's geometry or the regions' curve (read from text).
TEST(IrCurveLapInterpreter, ThePathOfTheExpandedLaps) {
  std::vector<Function> functions;
  functions.push_back(lineThenHalfCircle(test_support::lineThenHalfCircleGeometry(5)));
  functions.push_back(lineThenHalfCircle());
  functions.push_back(parsed(circleText));
  functions.push_back(parsed(pathText));
  functions.push_back(passesAroundTwoPieces());
  for (Function& function : functions) {
    ToolPath before = interpret(function);
    ASSERT_GT(feedMoves(before).size(), 5u) << function.name;
    ASSERT_TRUE(expandCurveLaps(function));
    EXPECT_EQ(countOf(function, Opcode::CurveLap), 0u);
    EXPECT_THAT(verifyFunction(function), IsEmpty()) << function.name;
    expectSamePath(before, interpret(function));
  }
}

TEST(IrCurveLapInterpreter, ACurveWithoutFinitePointsIsTheRunsError) {
  Function function = parsed(replaced(circleText, "%6 = mul %0, %5", "%6 = sqrt %2"));
  EXPECT_THAT(verifyFunction(function), IsEmpty());
  std::string expected;
  try {
    lapParameters(function.curves[0],
                  *lapCurve(function, onlyLap(function), [](ValueId) { return 5.0; }));
  } catch (const CurveLapError& error) {
    expected = error.what();
  }
  ASSERT_FALSE(expected.empty());
  try {
    interpret(function);
    FAIL() << "no error";
  } catch (const InterpreterError& error) {
    EXPECT_EQ(error.what(), expected);
  }
}

TEST(IrCurveLapInterpreter, PointsCountAsSteps) {
  Function function = parsed(circleText);
  InterpreterOptions options;
  std::size_t moves = feedMoves(interpret(function)).size();
  ASSERT_GT(moves, 40u);
  options.maximumSteps = moves; // fewer than the points and their regions' work
  EXPECT_THROW(interpret(function, options), InterpreterError);
  options.maximumSteps = 7 * moves; // each point: one step and its region's five
  EXPECT_NO_THROW(interpret(function, options));
  options.maximumSteps = std::numeric_limits<std::size_t>::max();
  options.maximumEvents = 10;
  EXPECT_THROW(interpret(function, options), InterpreterError);
}

} // namespace
} // namespace cncc::ir
