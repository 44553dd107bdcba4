// curve.lap in the IR core: its text and the curve table's, the verifier's
// rules, the passes treating a lap like a loop over unknown parameters, the
// curve its regions compute, and the interpreter running it.
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

namespace cncc::ir {
namespace {

using ::testing::Contains;
using ::testing::HasSubstr;
using ::testing::IsEmpty;

constexpr double pi = std::numbers::pi;

// A circle of radius r (a parameter) about the origin, one lap at z = -1.
constexpr std::string_view circleText = R"(func @circle(r = 5) {
  curve @0 chords 0.01 over 0 .. 6.283185307179586 {
    piece at 0 over 0 .. 6.283185307179586
  }
  %0 = param r
  %1 = const 500
  %2 = const -1
  %3 = const 0
  move.rapid %0, %3, %3
  %4 = curve.lap @0, %2, %2, %1 {
    %5 = cos %4
    %6 = mul %0, %5
    %7 = sin %4
    %8 = mul %0, %7
    curve.point %6, %8, %3
  }
}
)";

// A line along x from 0 to 13: a piece over 0 .. 10, then a NURBS-like
// piece of three knot spans, each its own region at u in [0, 1]; a ramp
// lap from z = 0 down to z = -1 by eight points at equal parameter steps.
constexpr std::string_view pathText = R"(func @path() {
  table @0 = [0.5, 1.5]
  curve @0 samples 8 over 0 .. 13 {
    piece at 0 over 0 .. 10
    piece at 10 over 0 .. 3 spans 0 .. 1, 1 .. 2, 2 .. 3
    host 1, 3
  }
  curve @1 spacing 0.25 over -1 .. 1e+300 {
    piece at 0 over -1 .. 1e+300
    progress 0.25 share 0.5
    chosen -1, 0.1, 1e+300
  }
  %0 = const 0
  %1 = const -1
  %2 = const 100
  %3 = curve.lap @0, %0, %1, %2 {
    curve.point %3, %0, %0
  } piece {
    %4 = const 10
    %5 = add %4, %3
    curve.point %5, %0, %0
  } piece {
    %6 = const 11
    %7 = add %6, %3
    curve.point %7, %0, %0
  } piece {
    %8 = const 12
    %9 = add %8, %3
    curve.point %9, %0, %0
  }
}
)";

Function parsed(std::string_view text) {
  ParseError error;
  std::optional<Function> function = parseFunction(text, error);
  EXPECT_TRUE(function) << error.line << ": " << error.message;
  return function ? std::move(*function) : Function{};
}

// The parser's complaint, as "line: message".
std::string parseComplaint(std::string_view text) {
  ParseError error;
  if (parseFunction(text, error)) {
    return "parsed";
  }
  return std::to_string(error.line) + ": " + error.message;
}

const Instruction& onlyLap(const Function& function) {
  for (const Instruction& instruction : function.instructions) {
    if (instruction.opcode == Opcode::CurveLap) {
      return instruction;
    }
  }
  ADD_FAILURE() << "no curve.lap";
  return function.instructions.front();
}

std::size_t countOf(const Function& function, Opcode opcode) {
  std::size_t count = 0;
  for (const Instruction& instruction : function.instructions) {
    count += instruction.opcode == opcode ? 1 : 0;
  }
  return count;
}

std::vector<MachineEvent> feedMoves(const ToolPath& path) {
  std::vector<MachineEvent> moves;
  for (const MachineEvent& event : path.events) {
    if (event.kind == MachineEvent::Kind::Feed) {
      moves.push_back(event);
    }
  }
  return moves;
}

void expectSamePath(const ToolPath& expected, const ToolPath& actual) {
  ASSERT_EQ(expected.events.size(), actual.events.size());
  for (std::size_t k = 0; k < expected.events.size(); ++k) {
    const MachineEvent& a = expected.events[k];
    const MachineEvent& b = actual.events[k];
    EXPECT_EQ(a.kind, b.kind) << k;
    EXPECT_EQ(a.x, b.x) << k;
    EXPECT_EQ(a.y, b.y) << k;
    EXPECT_EQ(a.z, b.z) << k;
    EXPECT_EQ(a.feed, b.feed) << k;
  }
}

// ---------------------------------------------------------------- text

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
  EXPECT_EQ(onlyLap(function).regions.size(), 4u);
  EXPECT_THAT(verifyFunction(function), IsEmpty());
}

TEST(IrCurveLapText, ShortestRoundTripNumbers) {
  Function function = parsed(circleText);
  function.curves[0].amount = 0.1 + 0.2; // 0.30000000000000004
  function.curves[0].pieces[0].start = -0.0;
  Function again = parsed(printFunction(function));
  EXPECT_EQ(again.curves[0].amount, 0.1 + 0.2);
  EXPECT_TRUE(std::signbit(again.curves[0].pieces[0].start));
}

std::string replaced(std::string_view text, std::string_view from, std::string_view to) {
  std::string result(text);
  std::size_t at = result.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) {
    result.replace(at, from.size(), to);
  }
  return result;
}

TEST(IrCurveLapText, ParserRefusesLapsThatDoNotFitTheirCurve) {
  EXPECT_EQ(parseComplaint(replaced(circleText, "curve.lap @0", "curve.lap @3")),
            "10: curve @3 is not in the curve table");
  EXPECT_EQ(parseComplaint(replaced(pathText, "  } piece {\n    %8", "    %8")),
            "26: 'curve.point' ends a curve.lap region: expected '} piece {' or '}'");
  EXPECT_EQ(parseComplaint(replaced(circleText, "    curve.point %6, %8, %3\n", "")),
            "15: a curve.lap region must end with 'curve.point'");
  EXPECT_EQ(parseComplaint(replaced(circleText, "    curve.point %6, %8, %3\n",
                                    "    curve.point %6, %8, %3\n  } piece {\n")),
            "16: this curve.lap has more regions than the 1 its curve needs");
  std::string threeRegions = replaced(pathText,
                                      "  } piece {\n    %8 = const 12\n    %9 = add %8, %3\n    "
                                      "curve.point %9, %0, %0\n",
                                      "");
  EXPECT_EQ(parseComplaint(threeRegions), "26: this curve.lap has 3 regions, its curve needs 4");
  EXPECT_EQ(parseComplaint(replaced(circleText, "chords", "steps")),
            "2: a curve's points are chosen by 'chords', 'samples' or 'spacing'");
  EXPECT_EQ(parseComplaint(replaced(pathText, "    host 1, 3\n", "    host 1, x\n")),
            "6: expected a whole number, found 'x'");
  EXPECT_EQ(parseComplaint(replaced(pathText, "spans 0 .. 1,", "spans 0 1,")),
            "5: expected a knot span 'from .. to'");
  EXPECT_EQ(parseComplaint(replaced(circleText, "  }\n  %0", "  }}\n  %0")),
            "4: expected 'piece at start over from .. to', 'progress', 'host', 'chosen' or '}'");
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

// A loop over three passes, each a lap around the circle at z = -pass.
// Each region computes what a pass could mishandle: `mul %t, %two` (the
// lap's parameter: nothing leaves the lap), `mul %r, %two` in both regions
// (equal expressions in sibling regions), an unused value.
Function passesAroundTwoPieces() {
  FunctionBuilder builder("passes");
  ValueId r = builder.parameter(builder.addParameter("r", 5));
  CurveTableEntry entry;
  entry.pieces = {{0, 0, 1}, {1, 0, pi}};
  entry.to = 1 + pi;
  entry.amount = 0.01;
  std::uint32_t curve = builder.addCurve(entry);
  ValueId zero = builder.constant(0);
  ValueId one = builder.constant(1);
  ValueId two = builder.constant(2);
  ValueId feed = builder.constant(300);
  ValueId pass = builder.beginLoop(one, builder.constant(3));
  ValueId depth = builder.unary(Opcode::Neg, pass);
  ValueId t = builder.beginCurveLap(curve, depth, depth, feed);
  ValueId diameter = builder.binary(Opcode::Mul, r, two);
  ValueId twice = builder.binary(Opcode::Mul, t, two);
  builder.binary(Opcode::Sub, twice, twice); // unused
  builder.curvePoint(builder.binary(Opcode::Mul, twice, diameter), zero, zero);
  diameter = builder.binary(Opcode::Mul, r, two);
  ValueId x = builder.binary(Opcode::Add, builder.binary(Opcode::Mul, two, diameter),
                             builder.binary(Opcode::Mul, r, builder.unary(Opcode::Sin, t)));
  ValueId y =
      builder.binary(Opcode::Sub, r, builder.binary(Opcode::Mul, r, builder.unary(Opcode::Cos, t)));
  builder.curvePoint(x, y, builder.binary(Opcode::Mul, t, zero));
  builder.endLoop();
  return builder.finish();
}

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
      if (pass.name != "expand-curve-laps") {
        pass.run(function);
        ASSERT_THAT(verifyFunction(function), IsEmpty()) << pass.name;
      }
    }
  }
  EXPECT_TRUE(parameterUsesStayInTheirLaps(function));
  expectSamePath(before, interpret(function));
}

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
