// curve.lap in the IR core: its text and the curve table's, the verifier's
// rules, and the passes treating a lap like a loop over unknown parameters
// (running it: curve_lap_run_test.cpp).
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

TEST(IrCurveLapText, PrintParsePrintIsExact) {
  for (std::string_view text : {circleText, pathText}) {
    EXPECT_EQ(printFunction(parsed(text)), text);
  }
}

TEST(IrCurveLapText, ParsedTableHasTheLayoutAndNoGeometry) {
  Function function = parsed(pathText);
  ASSERT_EQ(function.curves.size(), 2u);
  const CurveTableEntry& entry = function.curves[0];
  EXPECT_EQ(entry.sampling, CurveSampling::Samples);
  EXPECT_EQ(entry.amount, 8);
  EXPECT_EQ(entry.to, 13);
  ASSERT_EQ(entry.pieces.size(), 2u);
  EXPECT_EQ(entry.pieces[1].start, 10);
  ASSERT_EQ(entry.pieces[1].spans.size(), 3u);
  EXPECT_EQ(entry.pieces[1].spans[2], std::make_pair(2.0, 3.0));
  EXPECT_EQ(entry.hostPointRegions, (std::vector<std::size_t>{1, 3}));
  EXPECT_EQ(entry.geometry, nullptr);
  EXPECT_EQ(function.curves[1].sampling, CurveSampling::Spacing);
  EXPECT_EQ(function.curves[1].to, 1e300);
  EXPECT_EQ(function.curves[1].progressFrom, 0.25);
  EXPECT_EQ(function.curves[1].progressShare, 0.5);
  ASSERT_NE(function.curves[1].chosenParameters, nullptr);
  EXPECT_EQ(*function.curves[1].chosenParameters, (std::vector<double>{-1, 0.1, 1e300}));
  EXPECT_EQ(function.curves[0].chosenParameters, nullptr);
  EXPECT_EQ(function.curves[0].progressShare, 1);
  EXPECT_FALSE(function.curves[0].pointsAsNumbers);
  EXPECT_TRUE(function.curves[1].pointsAsNumbers);
  EXPECT_EQ(onlyLap(function).regions.size(), 4u);
  EXPECT_THAT(verifyFunction(function), IsEmpty());
}

// Chosen parameters two entries share (a ramp's, which spline blocks after
// it go through) are written once: `chosen as @e` names the earlier entry,
// and reading it back shares them again.
TEST(IrCurveLapText, SharedChosenParametersAreWrittenOnce) {
  Function function = parsed(pathText);
  function.curves.push_back(function.curves[1]);
  std::string text = printFunction(function);
  EXPECT_NE(text.find("    chosen as @1\n"), std::string::npos);
  Function again = parsed(text);
  ASSERT_EQ(again.curves.size(), 3u);
  EXPECT_EQ(again.curves[2].chosenParameters, again.curves[1].chosenParameters);
  EXPECT_EQ(printFunction(again), text);
  std::string unshared = replaced(pathText, "    chosen -1, 0.1, 1e+300\n", "    chosen as @0\n");
  EXPECT_EQ(parseComplaint(unshared), "12: curve @0 before this one has no chosen parameters");
}

TEST(IrCurveLapText, ShortestRoundTripNumbers) {
  Function function = parsed(circleText);
  function.curves[0].amount = 0.1 + 0.2; // 0.30000000000000004
  function.curves[0].pieces[0].start = -0.0;
  Function again = parsed(printFunction(function));
  EXPECT_EQ(again.curves[0].amount, 0.1 + 0.2);
  EXPECT_TRUE(std::signbit(again.curves[0].pieces[0].start));
}

TEST(IrCurveLapText, ParserRefusesLapsThatDoNotFitTheirCurve) {
  EXPECT_EQ(parseComplaint(replaced(circleText, "curve.lap @0", "curve.lap @3")),
            "10: curve @3 is not in the curve table");
  EXPECT_EQ(parseComplaint(replaced(pathText, "  } piece {\n    %8", "    %8")),
            "27: 'curve.point' ends a curve.lap region: expected '} piece {' or '}'");
  EXPECT_EQ(parseComplaint(replaced(circleText, "    curve.point %6, %8, %3\n", "")),
            "15: a curve.lap region must end with 'curve.point'");
  EXPECT_EQ(parseComplaint(replaced(circleText, "    curve.point %6, %8, %3\n",
                                    "    curve.point %6, %8, %3\n  } piece {\n")),
            "16: this curve.lap has more regions than the 1 its curve needs");
  std::string threeRegions = replaced(pathText,
                                      "  } piece {\n    %8 = const 12\n    %9 = add %8, %3\n    "
                                      "curve.point %9, %0, %0\n",
                                      "");
  EXPECT_EQ(parseComplaint(threeRegions), "27: this curve.lap has 3 regions, its curve needs 4");
  EXPECT_EQ(parseComplaint(replaced(circleText, "chords", "strides")),
            "2: a curve's laps are cut by 'chords', 'samples', 'spacing', 'arcs', 'steps', "
            "'nurbs-blocks', 'spline-blocks' or "
            "'polynomial-blocks'");
  EXPECT_EQ(parseComplaint(replaced(pathText, "    host 1, 3\n", "    host 1, x\n")),
            "6: expected a whole number, found 'x'");
  EXPECT_EQ(parseComplaint(replaced(pathText, "spans 0 .. 1,", "spans 0 1,")),
            "5: expected a knot span 'from .. to'");
  EXPECT_EQ(parseComplaint(replaced(circleText, "  }\n  %0", "  }}\n  %0")),
            "4: expected 'piece at start over from .. to', 'grid', 'blocks', 'spline', 'counts', "
            "'offset', 'asks', 'arcs', 'walks', 'progress', 'host', 'numbers', 'chosen' or '}'");
  EXPECT_EQ(parseComplaint(replaced(circleText, "  %4 = curve.lap", "  curve.lap")),
            "10: this operation has a result; write '%name = ...'");
}

// ---------------------------------------------------------------- verifier

TEST(IrCurveLapVerifier, LapNamesAnEntryOfTheTable) {
  Function function = parsed(circleText);
  const_cast<Instruction&>(onlyLap(function)).index = 1;
  EXPECT_THAT(verifyFunction(function), Contains(HasSubstr("names curve 1, which is not in")));
}

TEST(IrCurveLapVerifier, LapHasARegionPerPieceAndKnotSpan) {
  Function function = parsed(circleText);
  function.curves[0].pieces.push_back({6.283185307179586, 0, 1, {{0, 0.5}, {0.5, 1}}});
  function.curves[0].to = 7.283185307179586;
  EXPECT_THAT(verifyFunction(function), Contains(HasSubstr("has 1 regions, needs 3")));
}

TEST(IrCurveLapVerifier, RegionEndsWithCurvePoint) {
  Function function = parsed(circleText);
  Instruction& lap = const_cast<Instruction&>(onlyLap(function));
  std::swap(lap.regions[0].instructions.back(), lap.regions[0].instructions.front());
  std::vector<std::string> problems = verifyFunction(function);
  EXPECT_THAT(problems, Contains(HasSubstr("a curve.lap region does not end with curve.point")));
  EXPECT_THAT(problems, Contains(HasSubstr("(curve.point) is not the last of a curve.lap region")));
}

TEST(IrCurveLapVerifier, CurvePointOnlyInALap) {
  FunctionBuilder builder("stray");
  ValueId zero = builder.constant(0);
  builder.operation(Opcode::CurvePoint, {zero, zero, zero});
  ValueId one = builder.constant(1);
  builder.beginLoop(zero, one);
  builder.operation(Opcode::CurvePoint, {zero, zero, zero});
  builder.endLoop();
  std::vector<std::string> problems = verifyFunction(builder.finish());
  EXPECT_EQ(problems.size(), 2u);
  EXPECT_THAT(problems, Contains(HasSubstr("instruction 1 (curve.point) is not the last")));
  EXPECT_THAT(problems, Contains(HasSubstr("instruction 4 (curve.point) is not the last")));
}

TEST(IrCurveLapVerifier, ParameterIsVisibleInTheRegionsOnly) {
  FunctionBuilder builder("leak");
  CurveTableEntry entry;
  entry.pieces = {{0, 0, 1}, {1, 0, 1}};
  entry.to = 2;
  entry.amount = 0.1;
  std::uint32_t curve = builder.addCurve(entry);
  ValueId zero = builder.constant(0);
  ValueId t = builder.beginCurveLap(curve, zero, zero, builder.constant(100));
  ValueId inFirst = builder.binary(Opcode::Mul, t, builder.constant(2));
  builder.curvePoint(inFirst, t, zero);
  builder.curvePoint(t, inFirst, zero); // a value of the sibling region
  builder.feed(t, zero, zero, zero);    // the parameter after the lap
  Function function = builder.finish();
  std::vector<std::string> problems = verifyFunction(function);
  EXPECT_EQ(problems.size(), 2u);
  EXPECT_THAT(problems, Contains(HasSubstr("(curve.point) uses %4 where it is not visible")));
  EXPECT_THAT(problems, Contains(HasSubstr("(move.feed) uses %2 where it is not visible")));
}

// Each way an entry can be wrong, on an entry no lap uses.
TEST(IrCurveLapVerifier, EntryIsSane) {
  struct Case {
    const char* problem;
    void (*spoil)(CurveTableEntry&);
  };
  const Case cases[] = {
      {"has no pieces", [](CurveTableEntry& e) { e.pieces.clear(); }},
      {"runs over 2 .. 1, not a finite range",
       [](CurveTableEntry& e) {
         e.from = 2;
         e.to = 1;
       }},
      {"runs over 0 .. inf", [](CurveTableEntry& e) { e.to = INFINITY; }},
      {"chooses its points by 0, which is not a positive number",
       [](CurveTableEntry& e) { e.amount = 0; }},
      {"chooses its points by nan, which is not", [](CurveTableEntry& e) { e.amount = NAN; }},
      {"piece 0 at 0 runs over 2 .. 1", [](CurveTableEntry& e) { e.pieces[0].from = 2; }},
      {"piece 1 at nan runs over", [](CurveTableEntry& e) { e.pieces[1].start = NAN; }},
      {"piece 1 starts before the piece ahead of it",
       [](CurveTableEntry& e) { e.pieces[1].start = -1; }},
      {"piece 1 has knot span 1 .. 0.5, not increasing within 0 .. 2",
       [](CurveTableEntry& e) {
         e.pieces[1].spans[1] = {1, 0.5};
       }},
      {"piece 1 has knot span 1 .. 3, not increasing within 0 .. 2",
       [](CurveTableEntry& e) {
         e.pieces[1].spans[1] = {1, 3};
       }},
      {"piece 1 has knot span 0.5 .. 2, not increasing",
       [](CurveTableEntry& e) {
         e.pieces[1].spans[1] = {0.5, 2};
       }},
      {"has its points of region 3 on the host, but 3 regions",
       [](CurveTableEntry& e) {
         e.hostPointRegions = {2, 3};
       }},
      {"descends from 0.75 by a share of 0.5, not within",
       [](CurveTableEntry& e) {
         e.progressFrom = 0.75;
         e.progressShare = 0.5;
       }},
      {"has 3 chosen parameters, not two or more in order within 0 .. 3",
       [](CurveTableEntry& e) {
         e.chosenParameters =
             std::make_shared<const std::vector<double>>(std::vector{0.0, 2.0, 1.0});
       }},
      {"has 1 chosen parameters",
       [](CurveTableEntry& e) {
         e.chosenParameters = std::make_shared<const std::vector<double>>(std::vector{0.0});
       }},
  };
  for (const Case& c : cases) {
    Function function = parsed(circleText);
    CurveTableEntry entry;
    entry.pieces = {{0, 0, 1}, {1, 0, 2, {{0, 1}, {1, 2}}}};
    entry.to = 3;
    entry.amount = 0.5;
    function.curves.push_back(entry);
    EXPECT_THAT(verifyFunction(function), IsEmpty());
    c.spoil(function.curves.back());
    EXPECT_THAT(verifyFunction(function), Contains(HasSubstr(std::string("curve @1 ") + c.problem)))
        << c.problem;
  }
}

// ---------------------------------------------------------------- passes

// Whether every operation reading a lap's parameter sits in that lap.
bool parameterUsesStayInTheirLaps(const Function& function) {
  std::vector<InstructionId> lapOf(function.instructions.size(), ~InstructionId{0});
  auto mark = [&](auto& self, const Region& region, InstructionId lap) -> void {
    for (InstructionId id : region.instructions) {
      lapOf[id] = lap;
      const Instruction& instruction = function.instructions[id];
      for (const Region& nested : instruction.regions) {
        self(self, nested, instruction.opcode == Opcode::CurveLap ? id : lap);
      }
    }
  };
  mark(mark, function.body, ~InstructionId{0});
  for (InstructionId id = 0; id < function.instructions.size(); ++id) {
    for (ValueId operand : function.instructions[id].operands) {
      InstructionId definition = function.definitions[operand.index];
      if (function.instructions[definition].opcode == Opcode::CurveLap && lapOf[id] != definition) {
        return false;
      }
    }
  }
  return true;
}

// The pass keeps the path, the laps and their points, and a valid function.
void expectPassKeepsLaps(bool (*pass)(Function&), std::size_t laps) {
  Function function = passesAroundTwoPieces();
  ASSERT_THAT(verifyFunction(function), IsEmpty());
  ToolPath before = interpret(function);
  ASSERT_EQ(feedMoves(before).size() % 3, 0u);
  pass(function);
  EXPECT_THAT(verifyFunction(function), IsEmpty()) << printFunction(function);
  EXPECT_EQ(countOf(function, Opcode::CurveLap), laps) << printFunction(function);
  EXPECT_EQ(countOf(function, Opcode::CurvePoint), 2 * laps);
  EXPECT_TRUE(parameterUsesStayInTheirLaps(function)) << printFunction(function);
  expectSamePath(before, interpret(function));
}

TEST(IrCurveLapPasses, FoldKeepsWhatDependsOnTheParameter) {
  expectPassKeepsLaps(foldConstants, 1);
  Function function = passesAroundTwoPieces();
  std::size_t multiplies = countOf(function, Opcode::Mul);
  foldConstants(function);
  // Nothing is known of t: t * 0 and t * 2 - t * 2 stay (t is no constant).
  EXPECT_EQ(countOf(function, Opcode::Mul), multiplies);
  EXPECT_EQ(countOf(function, Opcode::Sub), 2u);
}

TEST(IrCurveLapPasses, CseDoesNotReuseASiblingRegionsValue) {
  expectPassKeepsLaps(eliminateCommonSubexpressions, 1);
  Function function = passesAroundTwoPieces();
  std::size_t multiplies = countOf(function, Opcode::Mul);
  eliminateCommonSubexpressions(function);
  // `mul %r, 2` is computed in each region: neither sees the other's.
  EXPECT_EQ(countOf(function, Opcode::Mul), multiplies);
}

TEST(IrCurveLapPasses, LicmHoistsNothingOutOfALap) {
  expectPassKeepsLaps(hoistLoopInvariants, 1);
  Function function = passesAroundTwoPieces();
  hoistLoopInvariants(function);
  const Instruction& lap = onlyLap(function);
  std::size_t inRegions = lap.regions[0].instructions.size() + lap.regions[1].instructions.size();
  Function original = passesAroundTwoPieces();
  const Instruction& originalLap = onlyLap(original);
  EXPECT_EQ(inRegions, originalLap.regions[0].instructions.size() +
                           originalLap.regions[1].instructions.size());
}

TEST(IrCurveLapPasses, DceKeepsTheLapAndItsPoints) {
  expectPassKeepsLaps(eliminateDeadCode, 1);
  Function function = passesAroundTwoPieces();
  eliminateDeadCode(function);
  EXPECT_EQ(countOf(function, Opcode::Sub), 1u); // the unused `twice - twice` went
  // A lap whose regions compute nothing stays too: it moves the machine.
  FunctionBuilder builder("bare");
  CurveTableEntry entry;
  entry.pieces = {{0, 0, 1}};
  entry.amount = 2;
  entry.sampling = CurveSampling::Samples;
  std::uint32_t curve = builder.addCurve(entry);
  ValueId zero = builder.constant(0);
  ValueId t = builder.beginCurveLap(curve, zero, zero, builder.constant(100));
  builder.curvePoint(t, t, t);
  Function bare = builder.finish();
  EXPECT_FALSE(eliminateDeadCode(bare));
  EXPECT_EQ(countOf(bare, Opcode::CurveLap), 1u);
}

TEST(IrCurveLapPasses, UnrollCopiesALapButNeverUnrollsIt) {
  UnrollOptions options;
  options.maximumBodySize = 64;
  Function function = passesAroundTwoPieces();
  ToolPath before = interpret(function);
  EXPECT_TRUE(unrollLoops(function, options));
  EXPECT_THAT(verifyFunction(function), IsEmpty());
  EXPECT_EQ(countOf(function, Opcode::Loop), 0u);
  EXPECT_EQ(countOf(function, Opcode::CurveLap), 3u); // one per pass, each still a lap
  EXPECT_TRUE(parameterUsesStayInTheirLaps(function));
  expectSamePath(before, interpret(function));
  EXPECT_FALSE(unrollLoops(function, options));
}

TEST(IrCurveLapPasses, DefaultPipelineKeepsThePath) {
  Function function = passesAroundTwoPieces();
  ToolPath before = interpret(function);
  for (int round = 0; round < 3; ++round) {
    for (const Pass& pass : allPasses()) {
      if (pass.name != "expand-curve-laps" && pass.exact) {
        pass.run(function);
        ASSERT_THAT(verifyFunction(function), IsEmpty()) << pass.name;
      }
    }
  }
  EXPECT_TRUE(parameterUsesStayInTheirLaps(function));
  expectSamePath(before, interpret(function));
}

} // namespace
} // namespace cncc::ir
