// Laps cut as the target's curve blocks: an entry naming its table of NURBS
// or spline blocks prints and parses, the verifier checks the table and a
// NURBS block's weights, the interpreter runs the lap as the block, and
// write-curve-blocks writes each such lap out as that one move (a weight
// that is a parameter still one). An entry of SPL spans or of a NURBS block
// that names no table has its blocks fitted by write-curve-blocks, and the
// interpreter runs the lap as they are fitted.
#include "cncc/geom/evaluation_budget.h"
#include "cncc/geom/line_arc_curves.h"
#include "cncc/geom/nurbs_curve.h"
#include "cncc/ir/curve_blocks.h"
#include "cncc/ir/curve_lap.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/verifier.h"
#include "curve_lap_fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace cncc::ir {
namespace {

using curve_lap_test::countOf;
using curve_lap_test::parsed;
using curve_lap_test::replaced;

// An arch from (0, 0) to (10, 0) through the control point (5, 5) of
// weight w, a quadratic NURBS block at z = -1. The lap's region computes
// the curve's meaning (here only its chord: the block is what is cut).
constexpr std::string_view nurbsArchText = R"(func @arch(w = 2) {
  table @0 = [3, 0, 0, 0, 1, 1, 1, 0, 0, 0, 5, 5, 0, 10, 0, 0]
  curve @0 nurbs-blocks 0.01 over 0 .. 1 {
    piece at 0 over 0 .. 1
    blocks @0
  }
  %0 = param w
  %1 = const 0
  %2 = const -1
  %3 = const 300
  %4 = const 1
  %5 = const 10
  move.rapid %1, %1, %2
  %6 = curve.lap @0, %2, %2, %3, %4, %0, %4 {
    %7 = mul %5, %6
    curve.point %7, %1, %1
  }
}
)";

// A natural CSPLINE from (0, 0) through (5, 5) and (10, 0) to (15, 5) at
// z = -1.
constexpr std::string_view splineWaveText = R"(func @wave() {
  table @0 = [1, 3, 1, 1, 3, 5, 5, 0, 10, 0, 0, 15, 5, 0]
  curve @0 spline-blocks 0.01 over 0 .. 1 {
    piece at 0 over 0 .. 1
    blocks @0
  }
  %0 = const 0
  %1 = const -1
  %2 = const 300
  %3 = const 15
  %4 = const 5
  move.rapid %0, %0, %1
  %5 = curve.lap @0, %1, %1, %2 {
    %6 = mul %3, %5
    %7 = mul %4, %5
    curve.point %6, %7, %0
  }
}
)";

// Two cubic spans (Heidenhain SPL) from (0, 0) to (10, 0), then on to
// (20, 0): each ends at E and starts at K3 + K2 + K1 + E, here bowing up
// by K2 = (0, -4, 0) (a parabola 1 mm high) with K1 = (-10, 4, 0).
constexpr std::string_view spansText = R"(func @bows() {
  table @0 = [10, 0, 0, 0, -10, 0, 0, -4, 4, 0, 0, 0, 20, 0, 0, 0, -10, 0, 0, -4, 4, 0, 0, 0]
  curve @0 polynomial-blocks 0.01 over 0 .. 20 {
    piece at 0 over 0 .. 20
    blocks @0
  }
  %0 = const 0
  %1 = const -1
  %2 = const 300
  move.rapid %0, %0, %1
  %3 = curve.lap @0, %1, %1, %2 {
    curve.point %3, %0, %0
  }
}
)";

TEST(CurveLapBlocks, ABlocksEntryPrintsAndParsesWithItsTable) {
  for (std::string_view text : {nurbsArchText, splineWaveText, spansText}) {
    Function function = parsed(text);
    ASSERT_EQ(function.curves.size(), 1u);
    EXPECT_TRUE(function.curves[0].isBlocks());
    EXPECT_EQ(function.curves[0].blockTable, 0u);
    EXPECT_EQ(printFunction(function), text);
    EXPECT_TRUE(verifyFunction(function).empty());
  }
  EXPECT_EQ(parsed(nurbsArchText).curves[0].sampling, CurveSampling::NurbsBlocks);
  EXPECT_EQ(parsed(splineWaveText).curves[0].sampling, CurveSampling::SplineBlocks);
  EXPECT_EQ(parsed(spansText).curves[0].sampling, CurveSampling::PolynomialBlocks);
}

TEST(CurveLapBlocks, TheVerifierChecksTheTableAndTheWeights) {
  std::vector<std::string> problems =
      verifyFunction(parsed(replaced(nurbsArchText, "blocks @0", "blocks @1")));
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("table 1, which does not exist"), std::string::npos) << problems[0];

  // Two weights for three control points.
  problems = verifyFunction(parsed(replaced(nurbsArchText, "%3, %4, %0, %4 {", "%3, %4, %0 {")));
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("2 weights"), std::string::npos) << problems[0];

  // A table that holds no spline blocks (kind 7).
  problems = verifyFunction(parsed(replaced(splineWaveText, "[1, 3, 1, 1, 3,", "[7, 3, 1, 1, 3,")));
  ASSERT_EQ(problems.size(), 1u);

  // Cubic spans are 12 numbers each.
  problems = verifyFunction(parsed(replaced(spansText, "0, 0, 0, 20,", "0, 0, 20,")));
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("23 numbers"), std::string::npos) << problems[0];

  // A table of blocks belongs to blocks.
  problems = verifyFunction(parsed(replaced(splineWaveText, "spline-blocks", "chords")));
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("chords and names a table of blocks"), std::string::npos)
      << problems[0];
  problems = verifyFunction(parsed(replaced(splineWaveText, "    blocks @0\n", "")));
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("names neither a table of them nor how they are fitted"),
            std::string::npos)
      << problems[0];
  // How to fit them, and their table besides.
  problems = verifyFunction(parsed(
      replaced(splineWaveText, "    blocks @0\n", "    blocks @0\n    spline bspline auto\n")));
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("from a table and says how spline blocks are fitted"),
            std::string::npos)
      << problems[0];
}

// The lap runs as the block does, before and after write-curve-blocks, and
// the weight stays the parameter: an edit moves the arch's top.
TEST(CurveLapBlocks, WriteCurveBlocksWritesTheMoveTheInterpreterRuns) {
  Function function = parsed(nurbsArchText);
  InterpreterOptions heavier;
  heavier.parameters["w"] = 5.0;
  ToolPath before = interpret(function);
  ToolPath edited = interpret(function, heavier);
  ASSERT_TRUE(writeCurveBlocks(function));
  EXPECT_TRUE(verifyFunction(function).empty());
  EXPECT_EQ(countOf(function, Opcode::CurveLap), 0u);
  ASSERT_EQ(countOf(function, Opcode::Nurbs), 1u);
  curve_lap_test::expectSamePath(before, interpret(function));
  curve_lap_test::expectSamePath(edited, interpret(function, heavier));

  // A heavier middle weight pulls the arch's top (at x = 5) towards (5, 5).
  auto topOf = [](const ToolPath& path) {
    double top = 0;
    for (const MachineEvent& event : path.events) {
      top = std::max(top, event.y);
    }
    return top;
  };
  EXPECT_NEAR(topOf(before), 5.0 * 2 / 3, 1e-4); // (w / (1 + w)) * 5 at u = 1/2
  EXPECT_NEAR(topOf(edited), 5.0 * 5 / 6, 1e-4);
  EXPECT_NEAR(before.events.back().x, 10, 1e-12);
  EXPECT_EQ(before.events.back().z, -1);
}

TEST(CurveLapBlocks, SplineBlocksAreOneMoveThrough) {
  Function function = parsed(splineWaveText);
  ToolPath before = interpret(function);
  ASSERT_TRUE(writeCurveBlocks(function));
  EXPECT_TRUE(verifyFunction(function).empty());
  EXPECT_EQ(countOf(function, Opcode::CurveLap), 0u);
  EXPECT_EQ(countOf(function, Opcode::Spline), 1u);
  curve_lap_test::expectSamePath(before, interpret(function));
  // The spline passes through its knots, the last where it ends.
  bool throughMiddleKnot = false;
  for (const MachineEvent& event : before.events) {
    throughMiddleKnot |= std::abs(event.x - 10) < 1e-9 && std::abs(event.y) < 1e-9;
  }
  EXPECT_TRUE(throughMiddleKnot);
  EXPECT_NEAR(before.events.back().x, 15, 1e-9);
  EXPECT_NEAR(before.events.back().y, 5, 1e-9);
}

// Cubic spans are a move.polynomial each, their ends raised by the lap's
// height; once the laps are expanded, the table nothing reads goes.
TEST(CurveLapBlocks, CubicSpansAreAMoveEach) {
  Function function = parsed(spansText);
  ToolPath before = interpret(function);
  ASSERT_TRUE(writeCurveBlocks(function));
  EXPECT_TRUE(verifyFunction(function).empty());
  EXPECT_EQ(countOf(function, Opcode::Polynomial), 2u);
  curve_lap_test::expectSamePath(before, interpret(function));
  double top = 0;
  for (const MachineEvent& event : before.events) {
    top = std::max(top, event.y);
    EXPECT_EQ(event.z, -1);
  }
  EXPECT_NEAR(top, 1, 1e-4);
  EXPECT_EQ(before.events.back().x, 20);

  Function expanded = parsed(spansText);
  ASSERT_TRUE(expandCurveLaps(expanded));
  EXPECT_TRUE(expanded.tables.empty());
  EXPECT_TRUE(expanded.curves.empty());
  curve_lap_test::expectSamePath(before, interpret(expanded));
}

TEST(CurveLapBlocks, SplSpansWithoutATableAreFittedByThePass) {
  curve_lap_test::PassRun run = curve_lap_test::runThroughPass(
      curve_lap_test::circleAsFittedBlocks("polynomial-blocks"), writeCurveBlocks);
  EXPECT_GE(countOf(run.function, Opcode::Polynomial), 4u);
  curve_lap_test::expectOnTheCircle(run.before, 0.001 + 0.0001);
  // A circle's spans join smoothly: no stop to warn of.
  EXPECT_TRUE(run.function.warnings.empty());
}

TEST(CurveLapBlocks, ANurbsBlockWithoutATableIsFittedByThePass) {
  std::string text = curve_lap_test::circleAsFittedBlocks("nurbs-blocks");
  Function function = parsed(text);
  EXPECT_TRUE(verifyFunction(function).empty());
  ToolPath before = interpret(function);
  std::size_t tables = function.tables.size();
  ASSERT_TRUE(writeCurveBlocks(function));
  EXPECT_TRUE(verifyFunction(function).empty());
  ASSERT_EQ(countOf(function, Opcode::Nurbs), 1u);
  EXPECT_EQ(function.tables.size(), tables + 1); // the block's data
  curve_lap_test::expectSamePath(before, interpret(function));
  curve_lap_test::expectOnTheCircle(before, 0.001 + 0.0001);
  // Weights belong to a NURBS of the lap's own, whose table it names.
  std::vector<std::string> problems =
      verifyFunction(parsed(replaced(text, "%2, %2, %1 {", "%2, %2, %1, %0 {")));
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("weights for a NURBS block that write-curve-blocks fits"),
            std::string::npos)
      << problems[0];
}

// A fit asks a bounded number of points of the curve: a tolerance no
// B-spline of a reasonable size keeps is an error naming the bound, in
// about a second, not a search of minutes. The entry's geometry is the
// circle itself (as the lowering gives it), so the bound's points are
// geometry's, not the region interpreted at each.
TEST(CurveLapBlocks, AFitPastItsBoundIsAnErrorNamingIt) {
  CurveLapError error =
      curve_lap_test::passError(curve_lap_test::withCircleGeometry(parsed(
                                    replaced(curve_lap_test::circleAsFittedBlocks("nurbs-blocks"),
                                             "nurbs-blocks 0.001", "nurbs-blocks 1e-12"))),
                                writeCurveBlocks);
  EXPECT_NE(std::string(error.what()).find("asked more than 2500000 points of the curve"),
            std::string::npos)
      << error.what();
}

TEST(CurveLapBlocks, AFitFarPastItsBoundIsRefusedFromTheChordsEstimate) {
  // A circle of radius 10 turning 1e9 radians: about 1e10 chords within
  // 0.01, so the fit would spend its whole budget of points first.
  geom::ArcCurve turns({0, 0}, 10.0, 0.0, 1e9);
  geom::BudgetedCurve counted(turns, 100 * maximumCurveEvaluations);
  CurveTableEntry entry;
  entry.sampling = CurveSampling::NurbsBlocks;
  entry.amount = 0.01;
  try {
    lapFittedNurbs(entry, counted);
    FAIL() << "a B-spline was fitted to a billion radians";
  } catch (const CurveLapError& error) {
    EXPECT_NE(std::string(error.what()).find("asked more than"), std::string::npos) << error.what();
  }
  EXPECT_LT(counted.used(), 10'000u); // the estimate's samples, not the fit's
}

// An L of two pieces, (0, 0) to (10, 0) to (10, 10), cut at z = -1 and
// z = -2 as SPL spans the pass fits.
constexpr std::string_view cornerText = R"(func @corner() {
  curve @0 polynomial-blocks 0.001 over 0 .. 2 {
    piece at 0 over 0 .. 1
    piece at 1 over 0 .. 1
    grid 0.0001
  }
  %0 = const 0
  %1 = const -1
  %2 = const 300
  %3 = const 10
  %4 = const -2
  move.feed %0, %0, %1, %2
  %5 = curve.lap @0, %1, %1, %2 {
    %6 = mul %3, %5
    curve.point %6, %0, %0
  } piece {
    %7 = mul %3, %5
    curve.point %3, %7, %0
  }
  move.feed %0, %0, %4, %2
  %8 = curve.lap @0, %4, %4, %2 {
    %9 = mul %3, %8
    curve.point %9, %0, %0
  } piece {
    %10 = mul %3, %8
    curve.point %3, %10, %0
  }
}
)";

// The TNC stops where spans turn: the pass warns of the corner once for the
// entry, however many laps cut it. The entry's geometry is the L as a cubic
// B-spline with a triple knot at the corner, whose spans the pass takes as
// they are (the regions say the same L).
TEST(CurveLapBlocks, SpansThroughACornerAreAWarningOfThePass) {
  Function function = parsed(cornerText);
  ASSERT_TRUE(verifyFunction(function).empty()) << verifyFunction(function).front();
  std::vector<Eigen::Vector3d> points = {{0, 0, 0},  {10 / 3.0, 0, 0},  {20 / 3.0, 0, 0},
                                         {10, 0, 0}, {10, 10 / 3.0, 0}, {10, 20 / 3.0, 0},
                                         {10, 10, 0}};
  function.curves[0].geometry = std::make_shared<geom::NurbsCurve>(
      geom::NurbsCurve::bspline(geom::KnotVector({0, 0, 0, 0, 1, 1, 1, 2, 2, 2, 2}, 3), points));
  ToolPath before = interpret(function);
  ASSERT_TRUE(writeCurveBlocks(function));
  EXPECT_EQ(countOf(function, Opcode::Polynomial), 4u); // two spans a lap
  curve_lap_test::expectSamePath(before, interpret(function));
  ASSERT_EQ(function.warnings.size(), 1u);
  EXPECT_EQ(function.warnings[0].kind, LegalisationWarning::Kind::SplineExactStop);
  EXPECT_NE(function.warnings[0].message.find("1 of this curve's spline transitions turn by more "
                                              "than 0.1 degrees (the largest 90)"),
            std::string::npos)
      << function.warnings[0].message;
}

// Blocks are cut at one height: a ramp lap is refused by the pass and by
// the interpreter.
TEST(CurveLapBlocks, ARampLapOfBlocksIsRefused) {
  std::string ramp =
      replaced(splineWaveText, "curve.lap @0, %1, %1, %2", "curve.lap @0, %0, %1, %2");
  Function function = parsed(ramp);
  EXPECT_TRUE(verifyFunction(function).empty());
  EXPECT_THROW(interpret(function), InterpreterError);
  EXPECT_THROW(writeCurveBlocks(function), CurveLapError);
}

// The other laps stay for the later legalisations; a function without
// blocks is not changed.
TEST(CurveLapBlocks, OtherLapsStay) {
  Function function = parsed(curve_lap_test::circleText);
  EXPECT_FALSE(writeCurveBlocks(function));
  EXPECT_EQ(countOf(function, Opcode::CurveLap), 1u);
}

} // namespace
} // namespace cncc::ir
