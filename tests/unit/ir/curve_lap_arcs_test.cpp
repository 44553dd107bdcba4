// Laps cut as arcs: an entry asking for arcs is printed and parsed with its
// grid, the verifier keeps grids to arcs, and fit-arcs writes each such lap
// out as the moves the interpreter runs it with, every end and centre on
// the grid, the circle kept within the tolerance.
#include "cncc/ir/curve_lap.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/verifier.h"
#include "curve_lap_fixtures.h"

#include "cncc/geom/evaluation_budget.h"
#include "cncc/geom/line_arc_curves.h"

#include <gtest/gtest.h>

#include <cmath>

namespace cncc::ir {
namespace {

using curve_lap_test::circleText;
using curve_lap_test::countOf;
using curve_lap_test::parsed;
using curve_lap_test::replaced;

// The circle of radius r about the origin, its lap cut as arcs within
// 0.004 on the grid 0.001.
std::string arcsCircleText() {
  return replaced(replaced(circleText, "chords 0.01", "arcs 0.004"),
                  "piece at 0 over 0 .. 6.283185307179586\n",
                  "piece at 0 over 0 .. 6.283185307179586\n    grid 0.001\n");
}

bool onGrid(double value, double grid) {
  return std::fabs(value / grid - std::round(value / grid)) < 1e-6;
}

TEST(CurveLapArcs, AnArcsEntryPrintsAndParsesWithItsGrid) {
  Function function = parsed(arcsCircleText());
  ASSERT_EQ(function.curves.size(), 1u);
  EXPECT_EQ(function.curves[0].sampling, CurveSampling::Arcs);
  EXPECT_EQ(function.curves[0].amount, 0.004);
  EXPECT_EQ(function.curves[0].grid, 0.001);
  EXPECT_EQ(printFunction(function), arcsCircleText());
  EXPECT_TRUE(verifyFunction(function).empty());
}

TEST(CurveLapArcs, TheVerifierKeepsAGridToArcs) {
  Function chords = parsed(replaced(circleText, "piece at 0 over 0 .. 6.283185307179586\n",
                                    "piece at 0 over 0 .. 6.283185307179586\n    grid 0.001\n"));
  std::vector<std::string> problems = verifyFunction(chords);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("grid 0.001"), std::string::npos) << problems[0];

  Function negative = parsed(replaced(arcsCircleText(), "grid 0.001", "grid -0.001"));
  EXPECT_EQ(verifyFunction(negative).size(), 1u);

  Function chosen = parsed(replaced(arcsCircleText(), "grid 0.001", "grid 0.001\n    chosen 0, 1"));
  problems = verifyFunction(chosen);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("cut by arcs"), std::string::npos) << problems[0];
}

TEST(CurveLapArcs, FitArcsWritesTheMovesTheInterpreterRuns) {
  Function function = parsed(arcsCircleText());
  ToolPath before = interpret(function);
  ASSERT_TRUE(fitLapArcs(function));
  EXPECT_TRUE(verifyFunction(function).empty());
  EXPECT_EQ(countOf(function, Opcode::CurveLap), 0u);
  EXPECT_GE(countOf(function, Opcode::Arc), 2u); // at most 180 degrees each
  EXPECT_LE(countOf(function, Opcode::Arc), 4u); // a circle is a few arcs
  ToolPath after = interpret(function);
  curve_lap_test::expectSamePath(before, after);

  // Each arc ends on the grid, on the circle within the tolerance, its
  // centre the circle's within rounding, at the lap's height.
  for (const MachineEvent& event : after.events) {
    if (event.kind != MachineEvent::Kind::Arc) {
      continue;
    }
    EXPECT_TRUE(onGrid(event.x, 0.001) && onGrid(event.y, 0.001)) << event.x << " " << event.y;
    EXPECT_NEAR(std::hypot(event.x, event.y), 5, 0.004);
    EXPECT_NEAR(event.centreX, 0, 0.004);
    EXPECT_NEAR(event.centreY, 0, 0.004);
    EXPECT_EQ(event.z, -1);
  }
  const MachineEvent& last = after.events.back();
  EXPECT_NEAR(last.x, 5, 1e-12);
  EXPECT_NEAR(last.y, 0, 1e-12);
}

TEST(CurveLapArcs, ExpandingFitsArcsFirstAndEmptiesTheCurveTable) {
  Function function = parsed(arcsCircleText());
  ToolPath before = interpret(function);
  ASSERT_TRUE(expandCurveLaps(function));
  EXPECT_TRUE(function.curves.empty());
  EXPECT_GE(countOf(function, Opcode::Arc), 2u);
  curve_lap_test::expectSamePath(before, interpret(function));
}

TEST(CurveLapArcs, TheArcsFollowTheParameter) {
  Function function = parsed(arcsCircleText());
  InterpreterOptions options;
  options.parameters = {{"r", 8}};
  ToolPath path = interpret(function, options);
  for (const MachineEvent& event : path.events) {
    if (event.kind == MachineEvent::Kind::Arc) {
      EXPECT_NEAR(std::hypot(event.x, event.y), 8, 0.004);
    }
  }
}

TEST(CurveLapArcs, ALapCutAsArcsIsLevel) {
  Function function =
      parsed(replaced(arcsCircleText(), "curve.lap @0, %2, %2", "curve.lap @0, %3, %2"));
  EXPECT_THROW(interpret(function), InterpreterError);
  EXPECT_THROW(fitLapArcs(function), CurveLapError);
}

TEST(CurveLapArcs, ACurveThatLeavesItsPlaneIsNotFitted) {
  Function function =
      parsed(replaced(arcsCircleText(), "curve.point %6, %8, %3", "curve.point %6, %8, %4"));
  try {
    fitLapArcs(function);
    FAIL() << "a helix was fitted with arcs in a plane";
  } catch (const CurveLapError& error) {
    EXPECT_EQ(error.kind, CurveLapError::Kind::DegenerateCurve);
    EXPECT_NE(std::string(error.what()).find("z = const"), std::string::npos) << error.what();
  }
}

TEST(CurveLapArcs, AFitFarPastItsBudgetIsRefusedFromTheChordsEstimate) {
  // A circle of radius 10 turning 1e9 radians: about 1e10 chords within 0.01,
  // so the fit would spend its whole budget of points before giving up.
  geom::ArcCurve turns({0, 0}, 10.0, 0.0, 1e9);
  geom::BudgetedCurve counted(turns, 100 * maximumArcFitEvaluations);
  try {
    fitArcsWithinBudget(counted, {0.01}, {}, {});
    FAIL() << "arcs were fitted to a billion radians";
  } catch (const CurveLapError& error) {
    EXPECT_EQ(error.kind, CurveLapError::Kind::ProgramTooLarge) << error.what();
  }
  EXPECT_LT(counted.used(), 10'000u); // the estimate's samples, not the fit's
}

TEST(CurveLapArcs, ArcMovesOnTheGridDropWhatRoundsToNothing) {
  geom::ArcSegment tiny;
  tiny.kind = geom::ArcSegmentKind::Line;
  tiny.start = {0, 0, 0};
  tiny.end = {0.0002, 0, 0};
  geom::ArcSegment line = tiny;
  line.start = tiny.end;
  line.end = {3, 4, 0};
  LapArcs arcs = arcMovesOnGrid({tiny, line}, 0.001);
  ASSERT_EQ(arcs.moves.size(), 1u);
  EXPECT_FALSE(arcs.moves[0].turn);
  EXPECT_EQ(arcs.moves[0].end, Eigen::Vector2d(3, 4));
}

} // namespace
} // namespace cncc::ir
