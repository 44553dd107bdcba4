// Laps cut in chords or steps whose entry asks for arcs (arcs=true, --arcs):
// the request is printed and parsed, the verifier keeps it to chords and
// steps within a tolerance, and fit-arcs decides: the fit's arcs where it
// keeps them (in a pass loop too, at the loop's height), else a warning and
// the lap left to its expansion. The interpreter decides the same way, so
// the path before the pass is the path after it.
#include "cncc/ir/curve_lap.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/verifier.h"
#include "curve_lap_fixtures.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>

namespace cncc::ir {
namespace {

using curve_lap_test::countOf;
using curve_lap_test::expectSamePath;
using curve_lap_test::parsed;
using curve_lap_test::replaced;

// The circle of radius r in chords within 0.01 (circleText), asking for
// arcs within 0.004 on the grid 0.001, cut 0 of the function's cut table.
std::string askingCircleText() {
  return replaced(curve_lap_test::circleText, "  }\n  %0 = param r\n",
                  "    asks arcs within 0.004 grid 0.001\n  }\n  cut @0 tolerance 0.01\n"
                  "  cut.begin 0\n  %0 = param r\n");
}

// The same circle in uniform steps (counts the pass measures) at the height
// -k of each pass k = 1 .. 2 of a loop, as a controller runs it.
constexpr std::string_view askingStepsInAPassLoopText = R"(func @circle(r = 5) {
  curve @0 steps 0.004 over 0 .. 6.283185307179586 {
    piece at 0 over 0 .. 6.283185307179586
    counts ?
    asks arcs within 0.004 grid 0.001
  }
  cut @0 tolerance 0.01
  cut.begin 0
  %0 = param r
  %1 = const 500
  %2 = const 1
  %3 = const 0
  %4 = const 2
  %5 = loop %2, %4 {
    %6 = sub %3, %5
    move.rapid %0, %3, %3
    move.feed %0, %3, %6, %1
    %7 = curve.lap @0, %6, %6, %1 {
      %8 = cos %7
      %9 = mul %0, %8
      %10 = sin %7
      %11 = mul %0, %10
      curve.point %9, %11, %3
    }
  }
}
)";

std::size_t arcEvents(const ToolPath& path) {
  std::size_t arcs = 0;
  for (const MachineEvent& event : path.events) {
    arcs += event.kind == MachineEvent::Kind::Arc ? 1 : 0;
  }
  return arcs;
}

TEST(CurveLapAskedArcs, TheRequestPrintsAndParses) {
  Function function = parsed(askingCircleText());
  ASSERT_EQ(function.curves.size(), 1u);
  ASSERT_TRUE(function.curves[0].arcsAsked);
  EXPECT_EQ(function.curves[0].arcsAsked->tolerance, 0.004);
  EXPECT_EQ(function.curves[0].arcsAsked->grid, 0.001);
  EXPECT_EQ(function.curves[0].arcsAsked->largestRadius, std::numeric_limits<double>::infinity());
  EXPECT_EQ(printFunction(function), askingCircleText());
  EXPECT_TRUE(verifyFunction(function).empty());

  std::string bounded = replaced(askingCircleText(), "grid 0.001", "grid 0.001 radius 9999.9999");
  Function radius = parsed(bounded);
  EXPECT_EQ(radius.curves[0].arcsAsked->largestRadius, 9999.9999);
  EXPECT_EQ(printFunction(radius), bounded);
  // Below the circle's radius the fit is lines, still within the tolerance.
  Function small = parsed(replaced(askingCircleText(), "grid 0.001", "grid 0.001 radius 4"));
  ToolPath before = interpret(small);
  ASSERT_TRUE(fitLapArcs(small));
  EXPECT_EQ(countOf(small, Opcode::Arc), 0u);
  EXPECT_GT(countOf(small, Opcode::Feed), 10u);
  expectSamePath(before, interpret(small));
}

TEST(CurveLapAskedArcs, TheVerifierKeepsTheRequestToChordsAndStepsWithinATolerance) {
  Function samples = parsed(replaced(askingCircleText(), "chords 0.01", "samples 50"));
  std::vector<std::string> problems = verifyFunction(samples);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("asks for arcs but is cut by samples"), std::string::npos)
      << problems[0];

  Function none = parsed(replaced(askingCircleText(), "within 0.004", "within 0"));
  problems = verifyFunction(none);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("not a positive tolerance"), std::string::npos) << problems[0];
}

TEST(CurveLapAskedArcs, FitArcsWritesTheArcsTheInterpreterRan) {
  Function function = parsed(askingCircleText());
  ToolPath before = interpret(function);
  EXPECT_GE(arcEvents(before), 2u);
  ASSERT_TRUE(fitLapArcs(function));
  EXPECT_TRUE(verifyFunction(function).empty());
  EXPECT_EQ(countOf(function, Opcode::CurveLap), 0u);
  EXPECT_TRUE(function.warnings.empty());
  EXPECT_EQ(function.cuts.at(0).arcMoves, CutArcs::Fitted);
  expectSamePath(before, interpret(function));
}

TEST(CurveLapAskedArcs, InAPassLoopTheArcsTakeTheLoopsHeight) {
  Function function = parsed(std::string(askingStepsInAPassLoopText));
  ASSERT_TRUE(verifyFunction(function).empty());
  ToolPath before = interpret(function);
  ASSERT_TRUE(fitLapArcs(function));
  EXPECT_EQ(countOf(function, Opcode::CurveLap), 0u);
  EXPECT_EQ(countOf(function, Opcode::Loop), 1u); // the passes stay a loop
  ToolPath after = interpret(function);
  expectSamePath(before, after);
  std::vector<double> heights;
  for (const MachineEvent& event : after.events) {
    if (event.kind == MachineEvent::Kind::Arc && (heights.empty() || heights.back() != event.z)) {
      heights.push_back(event.z);
    }
  }
  EXPECT_EQ(heights, (std::vector<double>{-1, -2}));
}

// A curve that leaves its plane (z follows the parameter): no arcs keep
// it, so the pass warns at the cut, the entry asks no more, and the chords
// the interpreter ran stay for expand-curve-laps.
TEST(CurveLapAskedArcs, WhereNoFitKeepsThemTheLapStaysWithAWarning) {
  Function function =
      parsed(replaced(askingCircleText(), "curve.point %6, %8, %3", "curve.point %6, %8, %4"));
  ToolPath before = interpret(function);
  EXPECT_EQ(arcEvents(before), 0u);
  ASSERT_TRUE(fitLapArcs(function));
  ASSERT_EQ(function.warnings.size(), 1u);
  EXPECT_EQ(function.warnings[0].kind, LegalisationWarning::Kind::ArcsAsChords);
  EXPECT_NE(function.warnings[0].message.find("not arcs: arcs can replace only a curve in a plane"),
            std::string::npos)
      << function.warnings[0].message;
  EXPECT_FALSE(function.curves[0].arcsAsked);
  EXPECT_EQ(function.cuts.at(0).arcMoves, CutArcs::None);
  EXPECT_EQ(countOf(function, Opcode::CurveLap), 1u);
  expectSamePath(before, interpret(function));
  ASSERT_TRUE(expandCurveLaps(function));
  expectSamePath(before, interpret(function));
}

} // namespace
} // namespace cncc::ir
