// bound-controller-steps: a lap cut in steps whose count the program
// computes, past the limit of one region at the values compiled with or in
// a cut the host computes, is cut at points chosen on the host instead, the
// parameters its regions read fixed; the interpreter runs the lap so before
// the pass too.
#include "cncc/ir/curve_lap.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/verifier.h"
#include "curve_lap_fixtures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <string_view>

namespace cncc::ir {
namespace {

using curve_lap_test::countOf;
using curve_lap_test::feedMoves;
using curve_lap_test::onlyLap;
using curve_lap_test::parsed;
using curve_lap_test::replaced;

// A circle of radius r in `k r` steps the program computes (k = 100000), its
// range 0 .. 2 pi; the height h is a parameter the regions do not read.
constexpr std::string_view countedCircleText = R"(func @ring(r = 5, h = 1) {
  curve @0 steps 0.01 over 0 .. 6.283185307179586 {
    piece at 0 over 0 .. 6.283185307179586
    counts 0
  }
  %0 = param r
  %1 = param h
  %2 = const 500
  %3 = const 0
  %4 = const 100000
  %5 = mul %0, %4
  %6 = const 6.283185307179586
  %7 = neg %1
  move.rapid %0, %3, %3
  %8 = curve.lap @0, %7, %7, %2, %3, %6, %5 {
    %9 = cos %8
    %10 = mul %0, %9
    %11 = sin %8
    %12 = mul %0, %11
    curve.point %10, %12, %3
  }
}
)";

// The function of `text` through bound-controller-steps, which must change
// its lap (of cut `cut`) to chords, and the path interpreted before it.
struct Bounded {
  Function function;
  ToolPath before;
};

Bounded boundedByThePass(std::string_view text, std::uint32_t cut) {
  Bounded bounded{parsed(text), {}};
  Function& function = bounded.function;
  EXPECT_TRUE(verifyFunction(function).empty());
  EXPECT_TRUE(boundedStepsEntry(function, onlyLap(function), cut));
  bounded.before = interpret(function); // as the pass will cut it
  EXPECT_TRUE(boundControllerSteps(function));
  EXPECT_TRUE(verifyFunction(function).empty());
  EXPECT_EQ(function.curves.back().sampling, CurveSampling::ChordTolerance);
  return bounded;
}

TEST(BoundControllerSteps, ACountPastTheLimitIsCutAtPointsChosenOnTheHost) {
  auto [function, before] = boundedByThePass(countedCircleText, noCut);
  const CurveTableEntry& entry = function.curves.back();
  EXPECT_TRUE(entry.pointsAsNumbers);
  EXPECT_TRUE(entry.regionSteps.empty());
  EXPECT_TRUE(function.parameters[0].fixed);  // r: the circle's points read it
  EXPECT_FALSE(function.parameters[1].fixed); // h: the lap's height only
  ASSERT_EQ(function.warnings.size(), 1u);
  EXPECT_EQ(function.warnings[0].kind, LegalisationWarning::Kind::ParameterFixed);
  EXPECT_NE(function.warnings[0].message.find("'r' is fixed at its value 5"), std::string::npos);
  curve_lap_test::expectSamePath(before, interpret(function));

  ASSERT_TRUE(expandCurveLaps(function));
  EXPECT_EQ(countOf(function, Opcode::CurveLap), 0u);
  EXPECT_EQ(countOf(function, Opcode::Loop), 0u); // numbers, no table loop
  std::vector<MachineEvent> moves = feedMoves(interpret(function));
  // Chords of a circle of radius 5 within 0.01: about 2 pi / sqrt(8 0.01 / 5).
  EXPECT_GT(moves.size(), 40u);
  EXPECT_LT(moves.size(), 80u);
  for (const MachineEvent& move : moves) {
    EXPECT_NEAR(std::hypot(move.x, move.y), 5, 1e-9);
    EXPECT_EQ(move.z, -1);
  }
  EXPECT_NEAR(moves.back().x, 5, 1e-9);
  EXPECT_NEAR(moves.back().y, 0, 1e-9);
}

TEST(BoundControllerSteps, ACountWithinTheLimitStaysTheProgramsCount) {
  Function function = parsed(replaced(countedCircleText, "r = 5", "r = 0.5"));
  EXPECT_FALSE(boundedStepsEntry(function, onlyLap(function), noCut));
  EXPECT_FALSE(boundControllerSteps(function));
  EXPECT_FALSE(function.parameters[0].fixed);
  EXPECT_TRUE(function.warnings.empty());
  ASSERT_TRUE(expandControllerLoops(function));
  EXPECT_EQ(countOf(function, Opcode::Loop), 1u); // 50000 steps the controller counts
}

// The count through an `if` of the source: a select whose branch not taken
// at the compiled values reads the pass loop's variable, which is not known
// when compiling. The branch taken decides, as the program would.
TEST(BoundControllerSteps, ACountThroughASelectIsReadOnTheBranchTaken) {
  // countedCircleText's circle, its parameters and constants up to %4.
  std::string_view head = countedCircleText.substr(0, countedCircleText.find("  %5 = mul"));
  Function function = parsed(std::string(head) + R"(  %5 = const 1
  %6 = const 2
  %7 = const 6.283185307179586
  %8 = gt %0, %3
  %9 = neg %1
  move.rapid %0, %3, %3
  %10 = loop %5, %6 {
    %11 = mul %0, %4
    %12 = mul %10, %4
    %13 = select %8, %11, %12
    %14 = curve.lap @0, %9, %9, %2, %3, %7, %13 {
      %15 = cos %14
      %16 = mul %0, %15
      %17 = sin %14
      %18 = mul %0, %17
      curve.point %16, %18, %3
    }
  }
}
)");
  ASSERT_TRUE(verifyFunction(function).empty());
  ASSERT_TRUE(boundControllerSteps(function)); // 500000 steps: past the limit
  EXPECT_TRUE(function.parameters[0].fixed);
  EXPECT_EQ(function.curves.back().sampling, CurveSampling::ChordTolerance);
}

// The chords are chosen over the ranges at the compiled values: a parameter
// only a computed range reads is fixed too (an edit would not move them).
TEST(BoundControllerSteps, AParameterTheRangeReadsIsFixedToo) {
  std::string text = replaced(countedCircleText, "(r = 5, h = 1)", "(r = 5, h = 1, turns = 1)");
  text = replaced(text, "  %1 = param h\n", "  %1 = param h\n  %turns = param turns\n");
  text = replaced(text, "  %7 = neg %1\n", "  %7 = neg %1\n  %range = mul %6, %turns\n");
  text = replaced(text, "%3, %6, %5 {", "%3, %range, %5 {");
  auto [function, before] = boundedByThePass(text, noCut);
  EXPECT_TRUE(function.parameters[0].fixed);  // r: the circle's points
  EXPECT_FALSE(function.parameters[1].fixed); // h: the lap's height
  EXPECT_TRUE(function.parameters[2].fixed);  // turns: the range
  ASSERT_EQ(function.warnings.size(), 2u);
  EXPECT_NE(function.warnings[1].message.find("'turns' is fixed at its value 1"),
            std::string::npos);
  curve_lap_test::expectSamePath(before, interpret(function));
}

// countedCircleText's lap within the limit (r = 0.5: 50000 steps), in a
// cut whose numbers the host computes (no controller digits) or a
// controller does.
std::string circleInACut(std::string_view cutLine) {
  std::string text = replaced(countedCircleText, "r = 5", "r = 0.5");
  text = replaced(text, "  %0 = param r\n", std::string(cutLine) + "  %0 = param r\n");
  return replaced(text, "  move.rapid %0, %3, %3\n", "  cut.begin 0\n  move.rapid %0, %3, %3\n");
}

TEST(BoundControllerSteps, StepsOfACutTheHostComputesAreItsChords) {
  auto [function, before] =
      boundedByThePass(circleInACut("  cut @0 tolerance 0.01 increment 0.001\n"), 0);
  const CurveTableEntry& entry = function.curves.back();
  // The chords the host's lowering chose: within the tolerance less the
  // rounding of three axes, over the curve as laid out, a table of the
  // region's parameters (no numbers: the host computes every one anyway).
  EXPECT_DOUBLE_EQ(entry.amount, 0.01 - 0.0005 * std::sqrt(3.0));
  EXPECT_FALSE(entry.pointsAsNumbers);
  ASSERT_EQ(entry.pieces.size(), 1u);
  EXPECT_DOUBLE_EQ(entry.to, 6.283185307179586);
  EXPECT_TRUE(function.parameters[0].fixed);  // r: the circle's points read it
  EXPECT_FALSE(function.parameters[1].fixed); // h: the lap's height only
  EXPECT_TRUE(function.warnings.empty());     // the host's program has no parameters
  curve_lap_test::expectSamePath(before, interpret(function));

  ASSERT_TRUE(expandCurveLaps(function));
  EXPECT_EQ(countOf(function, Opcode::CurveLap), 0u);
  std::vector<MachineEvent> moves = feedMoves(interpret(function));
  // Chords of a circle of radius 0.5 within 0.0091: about 2 pi / sqrt(8 0.0091 / 0.5),
  // not the program's 50000 steps.
  EXPECT_GT(moves.size(), 12u);
  EXPECT_LT(moves.size(), 30u);
  for (const MachineEvent& move : moves) {
    EXPECT_NEAR(std::hypot(move.x, move.y), 0.5, 1e-9);
  }
}

TEST(BoundControllerSteps, StepsOfACutTheControllerComputesStayItsCount) {
  Function function =
      parsed(circleInACut("  cut @0 tolerance 0.01 increment 0.001 controller 8\n"));
  ASSERT_TRUE(verifyFunction(function).empty());
  EXPECT_FALSE(boundedStepsEntry(function, onlyLap(function), 0));
  EXPECT_FALSE(boundControllerSteps(function));
  EXPECT_FALSE(function.parameters[0].fixed);
}

// Three circles of radius r i, i = 1 .. 3, in 100 steps each, in a loop
// the program runs, in a cut the host computes: the lap's range and count
// are numbers, but its curve has no one value at the compiled values (and
// a lowered entry's geometry is the loop's first trip), so the pass leaves
// it; unroll-host-control writes the loop out first, and then each trip's
// lap is cut in the host's chords for its radius, as the interpreter runs
// the loop before.
TEST(BoundControllerSteps, ALapThatReadsALoopsVariableStaysItsSteps) {
  Function function = parsed(R"(func @rings(r = 0.5) {
  curve @0 steps 0.01 over 0 .. 6.283185307179586 {
    piece at 0 over 0 .. 6.283185307179586
    counts 0
  }
  cut @0 tolerance 0.01 increment 0.001
  %0 = param r
  %1 = const 500
  %2 = const 0
  %3 = const 100
  %4 = const 6.283185307179586
  %5 = const 1
  %6 = const 3
  %7 = const -1
  cut.begin 0
  %8 = loop %5, %6 {
    %9 = mul %0, %8
    move.rapid %9, %2, %2
    %10 = curve.lap @0, %7, %7, %1, %2, %4, %3 {
      %11 = cos %10
      %12 = mul %9, %11
      %13 = sin %10
      %14 = mul %9, %13
      curve.point %12, %14, %2
    }
  }
}
)");
  ASSERT_TRUE(verifyFunction(function).empty());
  EXPECT_FALSE(boundedStepsEntry(function, onlyLap(function), 0));
  EXPECT_FALSE(boundControllerSteps(function));
  EXPECT_FALSE(function.parameters[0].fixed);
  std::vector<MachineEvent> moves = feedMoves(interpret(function));
  EXPECT_LT(moves.size(), 300u); // fewer than 100 steps a circle
  EXPECT_NEAR(std::hypot(moves.back().x, moves.back().y), 1.5, 1e-9);

  EXPECT_TRUE(unrollHostControl(function));
  EXPECT_EQ(function.cuts.size(), 1u); // begun before the loop: one cut
  EXPECT_TRUE(boundControllerSteps(function));
  EXPECT_TRUE(function.parameters[0].fixed);
  std::vector<MachineEvent> written = feedMoves(interpret(function));
  ASSERT_EQ(written.size(), moves.size());
  for (std::size_t k = 0; k < moves.size(); ++k) {
    EXPECT_EQ(written[k].x, moves[k].x) << k;
    EXPECT_EQ(written[k].y, moves[k].y) << k;
  }
}

} // namespace
} // namespace cncc::ir
