// Arc regions of a lap cut in steps: a region the entry marks as an arc
// ends in curve.arc (its point and the offset to the centre), its count is
// a number of move.arc blocks, and the interpreter runs the lap with the
// blocks expand-controller-loops writes out.
#include "cncc/ir/curve_lap.h"
#include "cncc/ir/verifier.h"
#include "curve_lap_fixtures.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

namespace cncc::ir {
namespace {

using curve_lap_test::countOf;
using curve_lap_test::expandedPath;
using curve_lap_test::movesOf;
using curve_lap_test::parsed;
using curve_lap_test::pi;
using curve_lap_test::replaced;
using ::testing::Contains;
using ::testing::HasSubstr;

// A slot end: half a circle of radius r about the origin from (r, 0) to
// (-r, 0), counter-clockwise in one block, then a line 10 long back to
// (r, 0) in one step.
constexpr std::string_view slotText = R"(func @slot(r = 5) {
  curve @0 steps 0 over 0 .. 13.141592653589793 {
    piece at 0 over 0 .. 3.141592653589793
    piece at 3.141592653589793 over 0 .. 10
    counts 1, 1
    arcs 0 ccw
  }
  %0 = param r
  %1 = const 500
  %2 = const -1
  %3 = const 0
  move.rapid %0, %3, %3
  move.feed %0, %3, %2, %1
  %4 = curve.lap @0, %2, %2, %1 {
    %5 = cos %4
    %6 = mul %0, %5
    %7 = sin %4
    %8 = mul %0, %7
    %9 = neg %6
    %10 = neg %8
    curve.arc %6, %8, %3, %9, %10
  } piece {
    %11 = const 0.2
    %12 = mul %0, %11
    %13 = mul %12, %4
    %14 = neg %0
    %15 = add %14, %13
    curve.point %15, %3, %3
  }
}
)";

// Two whole turns of a helix of radius r descending 0.1 a radian.
constexpr std::string_view helixText = R"(func @helix(r = 5) {
  curve @0 steps 0 over 0 .. 12.566370614359172 {
    piece at 0 over 0 .. 12.566370614359172
    counts 2
    arcs 0 ccw turns
  }
  %0 = param r
  %1 = const 500
  %2 = const -1
  %3 = const 0
  %4 = const -0.1
  move.rapid %0, %3, %3
  move.feed %0, %3, %2, %1
  %5 = curve.lap @0, %2, %2, %1 {
    %6 = cos %5
    %7 = mul %0, %6
    %8 = sin %5
    %9 = mul %0, %8
    %10 = mul %4, %5
    %11 = neg %7
    %12 = neg %9
    curve.arc %7, %9, %10, %11, %12
  }
}
)";

TEST(CurveLapArcRegions, AnEntryPrintsAndParsesWithItsArcs) {
  Function function = parsed(slotText);
  ASSERT_EQ(function.curves.size(), 1u);
  ASSERT_EQ(function.curves[0].arcRegions.size(), 1u);
  EXPECT_EQ(function.curves[0].arcRegion(0), &function.curves[0].arcRegions[0]);
  EXPECT_EQ(function.curves[0].arcRegion(1), nullptr);
  EXPECT_TRUE(function.curves[0].arcRegions[0].counterClockwise);
  EXPECT_FALSE(function.curves[0].arcRegions[0].wholeTurns);
  EXPECT_EQ(printFunction(function), slotText);
  EXPECT_TRUE(verifyFunction(function).empty());
  Function helix = parsed(helixText);
  EXPECT_TRUE(helix.curves[0].arcRegions[0].wholeTurns);
  EXPECT_EQ(printFunction(helix), helixText);
  EXPECT_EQ(curve_lap_test::parseComplaint(replaced(slotText, "arcs 0 ccw", "arcs 0 left")),
            "6: expected 'arcs REGION ccw|cw [turns], ...'");
}

TEST(CurveLapArcRegions, TheVerifierKeepsCurveArcToTheArcRegions) {
  EXPECT_THAT(
      verifyFunction(parsed(replaced(slotText, "    arcs 0 ccw\n", ""))),
      Contains(HasSubstr("its region 0 ends in curve.arc but its curve wants curve.point")));
  EXPECT_THAT(
      verifyFunction(parsed(replaced(slotText, "arcs 0 ccw", "arcs 0 ccw, 1 cw"))),
      Contains(HasSubstr("its region 1 ends in curve.point but its curve wants curve.arc")));
  EXPECT_THAT(verifyFunction(parsed(replaced(slotText, "arcs 0 ccw", "arcs 0 ccw, 2 cw"))),
              Contains(HasSubstr("an arc region 2 that is not a later region of it")));
  EXPECT_THAT(verifyFunction(parsed(
                  replaced(replaced(slotText, "steps 0", "chords 0.01"), "    counts 1, 1\n", ""))),
              Contains(HasSubstr("has step counts, arcs, walks or an offset's growth but is not "
                                 "cut in steps")));
}

TEST(CurveLapArcRegions, AnArcRegionRunsAsTheControllersCircle) {
  Function function = parsed(slotText);
  InterpreterOptions options;
  options.parameters = {{"r", 7}};
  std::vector<MachineEvent> moves = movesOf(expandedPath(function, options));
  ASSERT_EQ(moves.size(), 3u); // the plunge, the half circle, the line
  EXPECT_EQ(moves[1].kind, MachineEvent::Kind::Arc);
  EXPECT_FALSE(moves[1].clockwise);
  EXPECT_NEAR(moves[1].x, -7, 1e-12);
  EXPECT_NEAR(moves[1].y, 0, 1e-12);
  EXPECT_EQ(moves[1].z, -1);
  EXPECT_NEAR(moves[1].centreX, 0, 1e-12);
  EXPECT_NEAR(moves[1].centreY, 0, 1e-12);
  EXPECT_EQ(moves[2].kind, MachineEvent::Kind::Feed);
  EXPECT_NEAR(moves[2].x, 7, 1e-12);
  EXPECT_EQ(countOf(function, Opcode::Arc), 1u);
  EXPECT_EQ(countOf(function, Opcode::Loop), 0u);
}

TEST(CurveLapArcRegions, ABlockCountSplitsTheArcInEqualTurns) {
  for (int blocks : {3, 6}) {
    Function function =
        parsed(replaced(slotText, "counts 1, 1", "counts " + std::to_string(blocks) + ", 1"));
    std::vector<MachineEvent> moves = movesOf(expandedPath(function));
    ASSERT_EQ(moves.size(), static_cast<std::size_t>(blocks) + 2);
    for (int j = 1; j <= blocks; ++j) {
      const MachineEvent& block = moves[static_cast<std::size_t>(j)];
      EXPECT_EQ(block.kind, MachineEvent::Kind::Arc);
      EXPECT_NEAR(std::atan2(block.y, block.x), j * pi / blocks, 1e-12) << j;
    }
    // Four blocks at most are written out; more go in a loop.
    EXPECT_EQ(countOf(function, Opcode::Loop), blocks > 4 ? 1u : 0u) << blocks;
    EXPECT_EQ(countOf(function, Opcode::Arc), blocks > 4 ? 1u : static_cast<std::size_t>(blocks));
  }
}

TEST(CurveLapArcRegions, WholeTurnsEndExactlyWhereTheyStart) {
  Function function = parsed(helixText);
  std::vector<MachineEvent> moves = movesOf(expandedPath(function));
  ASSERT_EQ(moves.size(), 3u);
  for (std::size_t turn = 1; turn <= 2; ++turn) {
    EXPECT_EQ(moves[turn].kind, MachineEvent::Kind::Arc);
    EXPECT_EQ(moves[turn].x, 5); // not r cos 2 pi turns
    EXPECT_EQ(moves[turn].y, 0);
    EXPECT_NEAR(moves[turn].z, -1 - 0.2 * pi * static_cast<double>(turn), 1e-12);
  }
}

TEST(CurveLapArcRegions, TheProgramComputesTheBlocksOfASymbolicArc) {
  // The count an operand, the range the fraction 0 .. 1 of the turn.
  std::string text = replaced(replaced(replaced(slotText, "counts 1, 1", "counts 0, 1"),
                                       "func @slot(r = 5)", "func @slot(r = 5, n = 2)"),
                              "curve.lap @0, %2, %2, %1 {\n    %5 = cos %4",
                              "curve.lap @0, %2, %2, %1, %3, %16, %17 {\n    %18 = mul %4, %19\n"
                              "    %5 = cos %18");
  text = replaced(text, "    %7 = sin %4", "    %7 = sin %18");
  text = replaced(text, "  move.rapid %0, %3, %3\n",
                  "  %16 = const 1\n  %17 = param n\n  %19 = const 3.141592653589793\n"
                  "  move.rapid %0, %3, %3\n");
  Function function = parsed(text);
  ASSERT_TRUE(verifyFunction(function).empty());
  InterpreterOptions options;
  options.parameters = {{"n", 5}};
  std::vector<MachineEvent> moves = movesOf(expandedPath(function, options));
  ASSERT_EQ(moves.size(), 7u);
  EXPECT_NEAR(std::atan2(moves[1].y, moves[1].x), pi / 5, 1e-12);
  EXPECT_NEAR(moves[5].x, -5, 1e-12);
  EXPECT_EQ(countOf(function, Opcode::Loop), 1u);
}

// From z = 0 to z = -1: the half circle (5 pi long) takes 5 pi / (5 pi +
// 10) of the descent, a helix, the line the rest.
TEST(CurveLapArcRegions, ARampDescendsAlongTheArcByItsShare) {
  Function function =
      parsed(replaced(replaced(slotText, "  %3 = const 0\n", "  %3 = const 0\n  %20 = const 0\n"),
                      "curve.lap @0, %2, %2", "curve.lap @0, %20, %2"));
  std::vector<MachineEvent> moves = movesOf(expandedPath(function));
  ASSERT_EQ(moves.size(), 3u);
  double arcShare = 5 * pi / (5 * pi + 10);
  EXPECT_NEAR(moves[1].z, -arcShare, 1e-9);
  EXPECT_NEAR(moves[2].z, -1, 1e-12);
}

} // namespace
} // namespace cncc::ir
