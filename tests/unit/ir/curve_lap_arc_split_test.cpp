// split-arc-laps: on a cut the host computes, a lap in steps with arc
// regions (a curve with an arc piece that reads parameters) becomes a lap
// per piece: its arcs in blocks of whole turns at the compiled values where
// they turn whole turns, its other pieces in chords; the interpreter runs
// the lap so before the pass too. A controller's lap stays its half turns.
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

using curve_lap_test::expectSamePath;
using curve_lap_test::parsed;
using curve_lap_test::pi;
using curve_lap_test::replaced;

// A line from the centre out to radius r, then `turns` turns of the circle
// of radius r, the turn the program counts in half turns (as the lowering
// gives every target); `%7` and `%8` are the lap's two heights.
constexpr std::string_view lineAndTurnsText = R"(func @ring(r = 12, turns = 2) {
  curve @0 steps 0.05 over 0 .. 162.79644737231007 {
    piece at 0 over 0 .. 12
    piece at 12 over 0 .. 150.79644737231007
    counts 0, 0
    arcs 1 ccw
  }
  cut @0 tolerance 0.05 increment 0.001
  %0 = param r
  %1 = param turns
  %2 = const 300
  %3 = const 0
  %4 = const 1
  %5 = const 6.283185307179586
  %6 = mul %5, %1
  %7 = const -1
  %8 = const -1
  %9 = abs %6
  %10 = const 3.141592653589793
  %11 = div %9, %10
  %12 = const 0.49999999
  %13 = add %11, %12
  %14 = round %13
  cut.begin 0
  move.rapid %3, %3, %3
  move.feed %3, %3, %7, %2
  %15 = curve.lap @0, %7, %8, %2, %3, %4, %4, %3, %4, %14 {
    %16 = mul %0, %15
    curve.point %16, %3, %3
  } piece {
    %17 = mul %6, %15
    %18 = cos %17
    %19 = mul %0, %18
    %20 = sin %17
    %21 = mul %0, %20
    %22 = neg %0
    %23 = mul %22, %18
    %24 = mul %22, %20
    curve.arc %19, %21, %3, %23, %24
  }
}
)";

std::string withTurns(std::string_view turns) {
  return replaced(lineAndTurnsText, "turns = 2)", "turns = " + std::string(turns) + ")");
}

// The function of `text` through split-arc-laps, which must split its lap,
// and the path interpreted before it: the same after it.
struct Split {
  Function function;
  ToolPath before;
};

Split splitByThePass(const std::string& text) {
  Split split{parsed(text), {}};
  EXPECT_TRUE(verifyFunction(split.function).empty());
  split.before = interpret(split.function);
  EXPECT_TRUE(splitArcLaps(split.function));
  EXPECT_TRUE(verifyFunction(split.function).empty());
  expectSamePath(split.before, interpret(split.function));
  return split;
}

// The laps of the function, in order.
std::vector<const Instruction*> lapsOf(const Function& function) {
  std::vector<const Instruction*> laps;
  for (InstructionId id : function.body.instructions) {
    if (function.instructions[id].opcode == Opcode::CurveLap) {
      laps.push_back(&function.instructions[id]);
    }
  }
  return laps;
}

std::vector<MachineEvent> arcsOf(const ToolPath& path) {
  std::vector<MachineEvent> arcs;
  for (const MachineEvent& event : path.events) {
    if (event.kind == MachineEvent::Kind::Arc) {
      arcs.push_back(event);
    }
  }
  return arcs;
}

TEST(SplitArcLaps, WholeTurnsAreABlockEachAndTheLineIsChords) {
  auto [function, before] = splitByThePass(std::string(lineAndTurnsText));
  std::vector<const Instruction*> laps = lapsOf(function);
  ASSERT_EQ(laps.size(), 2u);
  const CurveTableEntry& line = function.curves[laps[0]->index];
  EXPECT_EQ(line.sampling, CurveSampling::ChordTolerance);
  EXPECT_EQ(laps[0]->regions.size(), 1u);
  const CurveTableEntry& circle = function.curves[laps[1]->index];
  EXPECT_EQ(circle.sampling, CurveSampling::Steps);
  EXPECT_EQ(circle.regionSteps, std::vector<int>{2});
  ASSERT_EQ(circle.arcRegions.size(), 1u);
  EXPECT_TRUE(circle.arcRegions.front().wholeTurns);
  EXPECT_TRUE(circle.arcRegions.front().counterClockwise);
  for (const Instruction* lap : laps) {
    EXPECT_EQ(lap->operands.size(), 3u); // no range the program computes
  }
  // Both turns end where the circle starts; the host's program has no
  // parameter to edit.
  std::vector<MachineEvent> arcs = arcsOf(before);
  ASSERT_EQ(arcs.size(), 2u);
  for (const MachineEvent& arc : arcs) {
    EXPECT_EQ(arc.x, 12);
    EXPECT_EQ(arc.y, 0);
    EXPECT_NEAR(arc.centreX, 0, 1e-12);
    EXPECT_NEAR(arc.centreY, 0, 1e-12);
  }
  EXPECT_TRUE(function.parameters[0].fixed);
  EXPECT_TRUE(function.parameters[1].fixed);
}

TEST(SplitArcLaps, APartTurnIsTheFewestBlocksShortOfAFullTurn) {
  // 3/4 of a turn: one block; 3/2 turns: two of 3/4 each.
  for (auto [turns, blocks] : {std::pair{"0.75", 1}, std::pair{"1.5", 2}}) {
    auto [function, before] = splitByThePass(withTurns(turns));
    const CurveTableEntry& circle = function.curves[lapsOf(function).back()->index];
    EXPECT_EQ(circle.regionSteps, std::vector<int>{blocks}) << turns;
    EXPECT_FALSE(circle.arcRegions.front().wholeTurns) << turns;
    std::vector<MachineEvent> arcs = arcsOf(before);
    ASSERT_EQ(arcs.size(), static_cast<std::size_t>(blocks)) << turns;
    double angle = 2 * pi * std::stod(turns);
    EXPECT_NEAR(arcs.back().x, 12 * std::cos(angle), 1e-9) << turns;
    EXPECT_NEAR(arcs.back().y, 12 * std::sin(angle), 1e-9) << turns;
  }
}

TEST(SplitArcLaps, ARampsPiecesDescendByTheirSharesOfIt) {
  // Read from text, the lap's curve is its regions over the ranges laid out:
  // each over its parameter, 0 .. 1 (of the line, of the turns).
  std::string ramp = replaced(lineAndTurnsText, "%8 = const -1", "%8 = const -3");
  ramp = replaced(ramp, "over 0 .. 162.79644737231007", "over 0 .. 2");
  ramp = replaced(ramp, "piece at 0 over 0 .. 12", "piece at 0 over 0 .. 1");
  ramp = replaced(ramp, "piece at 12 over 0 .. 150.79644737231007", "piece at 1 over 0 .. 1");
  auto [function, before] = splitByThePass(ramp);
  std::vector<const Instruction*> laps = lapsOf(function);
  ASSERT_EQ(laps.size(), 2u);
  const CurveTableEntry& line = function.curves[laps[0]->index];
  const CurveTableEntry& circle = function.curves[laps[1]->index];
  double lineShare = 12 / (12 + 2 * pi * 12 * 2);
  EXPECT_NEAR(line.progressFrom, 0, 1e-12);
  EXPECT_NEAR(line.progressShare, lineShare, 1e-6);
  EXPECT_NEAR(circle.progressFrom, lineShare, 1e-6);
  EXPECT_NEAR(circle.progressFrom + circle.progressShare, 1, 1e-12);
  // The last turn ends at the lap's lower height.
  EXPECT_NEAR(arcsOf(before).back().z, -3, 1e-12);
}

TEST(SplitArcLaps, ACutTheControllerComputesKeepsItsHalfTurns) {
  Function function =
      parsed(replaced(lineAndTurnsText, "increment 0.001", "increment 0.001 controller 8"));
  ASSERT_TRUE(verifyFunction(function).empty());
  ToolPath before = interpret(function);
  EXPECT_EQ(arcsOf(before).size(), 4u); // two turns in half turns
  splitArcLaps(function);
  EXPECT_EQ(lapsOf(function).size(), 1u);
  EXPECT_FALSE(function.parameters[0].fixed);
}

TEST(SplitArcLaps, TurnsPastTheLimitAreAnError) {
  Function function = parsed(withTurns("1e6"));
  try {
    splitArcLaps(function);
    ADD_FAILURE() << "the pass split a million turns";
  } catch (const CurveLapError& error) {
    EXPECT_EQ(error.kind, CurveLapError::Kind::ProgramTooLarge);
    EXPECT_NE(std::string(error.what()).find("the limit is 100000 turns"), std::string::npos)
        << error.what();
  }
}

} // namespace
} // namespace cncc::ir
