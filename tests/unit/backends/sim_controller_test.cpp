// Control flow, macro calls, motion and the limits of the virtual controller.
#include "cncc/backends/controller_profile.h"
#include "cncc/backends/virtual_controller.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace cncc::backends::sim {
namespace {

using ::testing::HasSubstr;

const ControllerProfile& fanuc() {
  return *findControllerProfile("fanuc");
}

// Runs `body` wrapped in `%`, `O1000` and `M30`: the body's first line is
// line 3 of the program.
SimulationResult runBody(const std::string& body, const ControllerProfile& profile = fanuc(),
                         const SimulationOptions& options = {}) {
  return simulateProgram("%\nO1000\n" + body + "M30\n%\n", profile, options);
}

// The value of common variable `variable` after running `body`; fails the
// test when the program has an error or left it vacant.
double commonAfter(const std::string& body, int variable) {
  SimulationResult result = runBody(body);
  if (result.error) {
    ADD_FAILURE() << "line " << result.error->line() << ": " << result.error->what();
    return 0;
  }
  auto found = result.commonVariables.find(variable);
  if (found == result.commonVariables.end() || !found->second) {
    ADD_FAILURE() << "#" << variable << " is vacant";
    return 0;
  }
  return *found->second;
}

// The error running `text` gives; fails the test when there is none.
SimulationError errorOf(const std::string& text, const ControllerProfile& profile = fanuc(),
                        const SimulationOptions& options = {}) {
  SimulationResult result = simulateProgram(text, profile, options);
  if (!result.error) {
    ADD_FAILURE() << "no error for:\n" << text;
    return SimulationError(-1, "", "no error");
  }
  return *result.error;
}

TEST(SimControl, GotoForwardSkipsAndBackwardRepeats) {
  EXPECT_EQ(commonAfter("#100 = 1\nGOTO 20\n#100 = 2\nN20 #101 = 3\n", 100), 1);
  EXPECT_EQ(commonAfter("#100 = 0\nN5 #100 = #100 + 1\nIF [#100 LT 10] GOTO 5\n", 100), 10);
  EXPECT_EQ(commonAfter("#1 = 30\n#100 = 0\nGOTO #1\nN20 #100 = 20\nN30 #101 = 1\n", 100), 0);
}

TEST(SimControl, IfThenRunsItsAssignmentOnlyWhenTrue) {
  EXPECT_EQ(commonAfter("#100 = 1\nIF [#100 EQ 1] THEN #100 = 5\n", 100), 5);
  EXPECT_EQ(commonAfter("#100 = 1\nIF [#100 EQ 2] THEN #100 = 5\n", 100), 1);
}

TEST(SimControl, NestedWhileLoops) {
  // The sum of i * j for i, j in 1..4 is 10 * 10.
  std::string body = "#100 = 0\n"
                     "#1 = 1\n"
                     "WHILE [#1 LE 4] DO1\n"
                     "#2 = 1\n"
                     "WHILE [#2 LE 4] DO2\n"
                     "#100 = #100 + #1 * #2\n"
                     "#2 = #2 + 1\n"
                     "END2\n"
                     "#1 = #1 + 1\n"
                     "END1\n";
  EXPECT_EQ(commonAfter(body, 100), 100);
  // A loop whose condition is false at once runs no block of its body.
  EXPECT_EQ(commonAfter("#100 = 1\nWHILE [#100 GT 5] DO1\n#100 = 9\nEND1\n", 100), 1);
  // GOTO may leave a loop.
  EXPECT_EQ(commonAfter("#100 = 0\nWHILE [1 EQ 1] DO3\n#100 = #100 + 1\n"
                        "IF [#100 EQ 7] GOTO 9\nEND3\nN9 #101 = 0\n",
                        100),
            7);
}

std::string callingProgram(const std::string& call, const std::string& macro) {
  return "%\nO1000\n" + call + "\nM30\nO9001\n" + macro + "M99\n%\n";
}

TEST(SimCall, ArgumentsReachTheirLocalsAndLocalsBelongToTheCall) {
  SimulationResult result =
      simulateProgram(callingProgram("#1 = 11.\nG65 P9001 A2. B3. Z4.\n#101 = #1",
                                     "#100 = #1 * #2 + #26\n#102 = #3\n#1 = 99.\n"),
                      fanuc());
  ASSERT_FALSE(result.error) << result.error->what();
  EXPECT_EQ(*result.commonVariables[100], 10);
  EXPECT_FALSE(result.commonVariables[102]) << "C was not given: #3 stays vacant";
  EXPECT_EQ(*result.commonVariables[101], 11) << "the caller's #1 is its own";
}

TEST(SimCall, RepeatCountAndNestedCalls) {
  SimulationResult repeated =
      simulateProgram(callingProgram("#100 = 0\nG65 P9001 L3 A2.", "#100 = #100 + #1\n"), fanuc());
  ASSERT_FALSE(repeated.error) << repeated.error->what();
  EXPECT_EQ(*repeated.commonVariables[100], 6);

  std::string nested = "%\nO1\n#100 = 0\nG65 P2 A1.\nM30\n"
                       "O2\n#100 = #100 + #1\nIF [#1 GE 4] GOTO 9\nG65 P2 A[#1 + 1]\nN9 M99\n%\n";
  SimulationResult fourLevels = simulateProgram(nested, fanuc());
  ASSERT_FALSE(fourLevels.error) << fourLevels.error->what();
  EXPECT_EQ(*fourLevels.commonVariables[100], 1 + 2 + 3 + 4);

  std::string fiveLevels = nested;
  fiveLevels.replace(fiveLevels.find("GE 4"), 4, "GE 5");
  SimulationError tooDeep = errorOf(fiveLevels);
  EXPECT_EQ(tooDeep.line(), 9);
  EXPECT_THAT(tooDeep.what(), HasSubstr("nested 5 deep"));
}

TEST(SimCall, RunAsAMacroCallWithArguments) {
  SimulationOptions options;
  options.runAsMacroCall = true;
  std::string problem;
  options.arguments.push_back(*parseMacroArgument("A3.", fanuc(), problem));
  options.arguments.push_back(*parseMacroArgument("X-1.5", fanuc(), problem));
  SimulationResult result =
      simulateProgram("%\nO9001\n#100 = #1 + #24\nM99\n%\n", fanuc(), options);
  ASSERT_FALSE(result.error) << result.error->what();
  EXPECT_EQ(*result.commonVariables[100], 1.5);
  EXPECT_FALSE(parseMacroArgument("A3", fanuc(), problem));
  EXPECT_THAT(problem, HasSubstr("decimal point"));
  EXPECT_FALSE(parseMacroArgument("G1.", fanuc(), problem));
  EXPECT_FALSE(parseMacroArgument("Ax.", fanuc(), problem));
}

TEST(SimCall, CallErrors) {
  EXPECT_EQ(errorOf(callingProgram("G65 P9002 A1.", "")).line(), 3);
  EXPECT_THAT(errorOf(callingProgram("G65 P9001 A1", "")).what(), HasSubstr("decimal point"));
  EXPECT_THAT(errorOf(callingProgram("G65 P9001 G01 A1.", "")).what(), HasSubstr("only G"));
  EXPECT_THAT(errorOf("%\nO1\nM99\n%\n").what(), HasSubstr("M99 in the main program"));
  EXPECT_THAT(errorOf("%\nO1\nG65 P2\nM30\nO2\n#1 = 1\n%\n").what(), HasSubstr("without M99"));
}

// The last move, as a copy: callers pass the result of a run that ends with
// the statement.
ExecutedEvent onlyMove(const SimulationResult& result) {
  EXPECT_FALSE(result.error) << (result.error ? result.error->what() : "");
  EXPECT_FALSE(result.path.events.empty());
  return result.path.events.empty() ? ExecutedEvent{} : result.path.events.back();
}

TEST(SimMotion, ArcFromCentreOffsets) {
  SimulationResult result = runBody("G90 G17 G00 X10. Y0\nG03 X0 Y10. I-10. J0 F100.\n");
  const ExecutedEvent& arc = onlyMove(result);
  EXPECT_EQ(arc.kind, ExecutedEvent::Kind::CounterclockwiseArc);
  EXPECT_EQ(arc.start.x, 10);
  EXPECT_EQ(arc.end.y, 10);
  EXPECT_EQ(arc.centre.x, 0);
  EXPECT_EQ(arc.centre.y, 0);
  EXPECT_EQ(arc.feed, 100);

  ir::ToolPath flat = flattenPath(result.path, 1e-4);
  ASSERT_GT(flat.events.size(), 100u);
  double worst = 0;
  for (std::size_t i = 1; i < flat.events.size(); ++i) {
    const ir::MachineEvent& point = flat.events[i];
    worst = std::max(worst, std::abs(std::hypot(point.x, point.y) - 10));
    // The chord's middle is inside the circle by at most the sagitta.
    const ir::MachineEvent& before = flat.events[i - 1];
    double middle = std::hypot((point.x + before.x) / 2, (point.y + before.y) / 2);
    if (i > 1) {
      EXPECT_LE(10 - middle, 1.0001e-4);
    }
  }
  EXPECT_LT(worst, 1e-9);
  EXPECT_EQ(flat.events.back().x, 0);
  EXPECT_EQ(flat.events.back().y, 10);
}

TEST(SimMotion, ArcFromRadiusTakesTheShortOrTheLongWay) {
  const ExecutedEvent& shortArc = onlyMove(runBody("G90 G00 X10. Y0\nG03 X0 Y10. R10. F100.\n"));
  EXPECT_NEAR(shortArc.centre.x, 0, 1e-12);
  EXPECT_NEAR(shortArc.centre.y, 0, 1e-12);
  const ExecutedEvent& longArc = onlyMove(runBody("G90 G00 X10. Y0\nG03 X0 Y10. R-10. F100.\n"));
  EXPECT_NEAR(longArc.centre.x, 10, 1e-12);
  EXPECT_NEAR(longArc.centre.y, 10, 1e-12);
  const ExecutedEvent& clockwise = onlyMove(runBody("G90 G00 X0 Y10.\nG02 X10. Y0 R10. F100.\n"));
  EXPECT_NEAR(clockwise.centre.x, 0, 1e-12);
  EXPECT_NEAR(clockwise.centre.y, 0, 1e-12);
}

TEST(SimMotion, FullCircleAndHelix) {
  SimulationResult result = runBody("G90 G00 X5. Y0 Z0\nG02 I-5. Z-1. F50.\n");
  const ExecutedEvent& circle = onlyMove(result);
  EXPECT_EQ(circle.end.x, 5);
  EXPECT_EQ(circle.end.z, -1);
  ir::ToolPath flat = flattenPath(result.path, 1e-3);
  // A full turn: the half-way point is on the far side, half-way down.
  const ir::MachineEvent& middle = flat.events[1 + (flat.events.size() - 1) / 2];
  EXPECT_NEAR(middle.x, -5, 1e-2);
  EXPECT_NEAR(middle.z, -0.5, 1e-2);
}

TEST(SimMotion, IncrementalModeAndModalMotion) {
  SimulationResult result = runBody("G90 G00 X1. Y1.\nG91 G01 X2. F200.\nY-0.5\n");
  const ExecutedEvent& last = onlyMove(result);
  EXPECT_EQ(last.kind, ExecutedEvent::Kind::Feed);
  EXPECT_NEAR(last.end.x, 3, 1e-12);
  EXPECT_NEAR(last.end.y, 0.5, 1e-12);
  EXPECT_EQ(last.feed, 200);
  EXPECT_EQ(last.line, 5);
}

TEST(SimMotion, ComputedCoordinatesAreRoundedToTheIncrement) {
  const ExecutedEvent& metric = onlyMove(runBody("#1 = 2.00049\n#2 = -1.00051\nG90 G00 X#1 Y#2\n"));
  EXPECT_NEAR(metric.end.x, 2.0, 1e-12);
  EXPECT_NEAR(metric.end.y, -1.001, 1e-12);
  const ExecutedEvent& inch = onlyMove(runBody("G20\n#1 = 2.00049\nG90 G00 X#1\n"));
  EXPECT_NEAR(inch.end.x, 2.0005, 1e-12);
  ControllerProfile fine = fanuc();
  fine.leastInputIncrement = 0.0001;
  fine.coordinateDecimals = 4;
  const ExecutedEvent& isC = onlyMove(runBody("#1 = 2.00049\nG90 G00 X#1\n", fine));
  EXPECT_NEAR(isC.end.x, 2.0005, 1e-12);
}

TEST(SimMotion, ToolsAndSpindleAreRecorded) {
  SimulationResult result = runBody("T3 M06\nS1200 M03\nS1500\nM05\n");
  ASSERT_FALSE(result.error) << result.error->what();
  ir::ToolPath flat = flattenPath(result.path);
  ASSERT_EQ(flat.events.size(), 4u);
  EXPECT_EQ(flat.events[0].kind, ir::MachineEvent::Kind::Tool);
  EXPECT_EQ(flat.events[0].number, 3);
  EXPECT_EQ(flat.events[1].number, 1200);
  EXPECT_EQ(flat.events[2].number, 1500);
  EXPECT_EQ(flat.events[3].number, 0);
}

TEST(SimMotion, AZMoveAfterAToolChangeNeedsTheLengthOffset) {
  auto error = [](const std::string& body) {
    SimulationResult result = runBody(body);
    return result.error ? std::string(result.error->what()) + " at line " +
                              std::to_string(result.error->line())
                        : std::string();
  };
  // G43 H in the block of the first Z move, or before it.
  EXPECT_EQ(error("G54\nT3 M06\nG00 G43 H3 Z5.\nX1. Y1.\nG01 Z-1. F100.\n"), "");
  EXPECT_EQ(error("T3 M06\nG43 H13\nG00 Z5.\n"), "");
  // A move in X and Y alone is no Z move.
  EXPECT_EQ(error("T3 M06\nG00 X1. Y1.\nG43 H3 Z5.\n"), "");
  EXPECT_THAT(error("T3 M06\nG00 Z5.\n"), HasSubstr("G43 H.. must come first at line 4"));
  // G49 cancels it; a new tool needs its own.
  EXPECT_THAT(error("T3 M06\nG00 G43 H3 Z5.\nG49\nZ6.\n"), HasSubstr("line 6"));
  EXPECT_THAT(error("T3 M06\nG00 G43 H3 Z5.\nT4 M06\nZ6.\n"), HasSubstr("tool 4"));
  EXPECT_THAT(error("T3 M06\nG43 Z5.\n"), HasSubstr("G43 without H"));
  // The set-up codes the compiler prints run without changing the path.
  EXPECT_EQ(error("G54.1 P7\nG05.1 Q1\nM08\nM07\nG05.1 Q0\nM09\n"), "");
}

TEST(SimMotion, FeedAndSpindleWithinTheMachinesMaximum) {
  ControllerProfile machine = fanuc();
  machine.maximumFeed = 2000;
  machine.maximumSpindleSpeed = 6000;
  auto error = [&](const std::string& body) {
    SimulationResult result = runBody(body, machine);
    return result.error ? std::string(result.error->what()) : std::string();
  };
  EXPECT_EQ(error("S6000 M03\nG90 G00 X0 Y0\nG01 X1. F2000.\n"), "");
  EXPECT_THAT(error("S6001 M03\n"), HasSubstr("maximum of 6000 rpm"));
  EXPECT_THAT(error("G90 G00 X0 Y0\nG01 X1. F2500.\n"), HasSubstr("maximum of 2000 mm/min"));
  // Inch per minute, against the maximum in millimetres per minute.
  EXPECT_EQ(error("G20\nG90 G00 X0 Y0\nG01 X1. F78.\n"), "");
  EXPECT_THAT(error("G20\nG90 G00 X0 Y0\nG01 X1. F79.\n"), HasSubstr("F79"));
}

TEST(SimMotion, WhatTheControllerWouldRefuse) {
  auto refusal = [](const std::string& body) {
    SimulationResult result = runBody(body);
    EXPECT_TRUE(result.error) << body;
    return result.error ? std::string(result.error->what()) : std::string();
  };
  EXPECT_THAT(refusal("G90 G00 X10\n"), HasSubstr("decimal point"));
  EXPECT_THAT(refusal("G90 G00 X1.0004\n"), HasSubstr("4 decimals"));
  EXPECT_THAT(refusal("G90 X1.\n"), HasSubstr("before any G00"));
  EXPECT_THAT(refusal("G90 G01 X1.\n"), HasSubstr("feed"));
  EXPECT_THAT(refusal("G90 G00 X10. Y0\nG03 X0 Y10.1 I-10. F100.\n"), HasSubstr("from the centre"));
  EXPECT_THAT(refusal("G18\n"), HasSubstr("G18 is not simulated"));
  EXPECT_THAT(refusal("G00 G01 X1.\n"), HasSubstr("same modal group"));
  EXPECT_THAT(refusal("M123\n"), HasSubstr("M123"));
  EXPECT_THAT(refusal("G00 Q1.\n"), HasSubstr("address Q"));
  EXPECT_THAT(refusal("G00 X1. X2.\n"), HasSubstr("twice"));
  EXPECT_THAT(refusal("G00 X[ROUND[1.5]]\n"), HasSubstr("ROUND"));
  EXPECT_THAT(refusal("G00 X100000.\n"), HasSubstr("range"));
  EXPECT_THAT(refusal("G90 G00 X1. Y1.\nG02 X3. Y1. R0.5 F10.\n"), HasSubstr("half the chord"));
  EXPECT_THAT(refusal("#3000 = 1 (TOOL BROKEN)\n"), HasSubstr("alarm 3001"));
}

struct LimitCase {
  const char* name;
  std::string program;
  int line;
  const char* message;
};

void PrintTo(const LimitCase& limit, std::ostream* out) {
  *out << limit.name;
}

class SimLimit : public ::testing::TestWithParam<LimitCase> {};

TEST_P(SimLimit, IsReportedOnItsLine) {
  const LimitCase& limit = GetParam();
  SimulationError error = errorOf(limit.program);
  EXPECT_EQ(error.line(), limit.line) << error.what();
  EXPECT_THAT(error.what(), HasSubstr(limit.message));
  EXPECT_FALSE(error.lineText().empty());
}

INSTANTIATE_TEST_SUITE_P(
    EveryLimit, SimLimit,
    ::testing::Values(
        LimitCase{"BracketDepth", "%\nO1\n#1 = [[[[[[1]]]]]]\nM30\n%\n", 3, "nested 6 deep"},
        LimitCase{"BracketDepthCountsFunctions", "%\nO1\n#1 = [[[[SIN[[1]]]]]]\nM30\n%\n", 3,
                  "nested 6 deep"},
        LimitCase{"BlockLength", "%\nO1\n(" + std::string(130, 'A') + ")\nM30\n%\n", 3,
                  "132 characters"},
        LimitCase{"LoopNesting",
                  "%\nO1\nWHILE [1 EQ 1] DO1\nWHILE [1 EQ 1] DO2\nWHILE [1 EQ 1] DO3\n"
                  "WHILE [1 EQ 1] DO1\nEND1\nEND3\nEND2\nEND1\nM30\n%\n",
                  6, "DO1 inside"},
        LimitCase{"LoopIdentifier", "%\nO1\nWHILE [1 EQ 1] DO4\nEND4\nM30\n%\n", 3, "1 to 3"},
        LimitCase{"CrossingLoops",
                  "%\nO1\nWHILE [1 EQ 1] DO1\nWHILE [1 EQ 1] DO2\nEND1\nEND2\nM30\n%\n", 5,
                  "may not cross"},
        LimitCase{"EndWithoutDo", "%\nO1\nEND2\nM30\n%\n", 3, "without DO2"},
        LimitCase{"DoWithoutEnd", "%\nO1\nWHILE [1 EQ 1] DO2\nM30\n%\n", 3, "without END2"},
        LimitCase{"UndefinedGotoTarget", "%\nO1\n#1 = 1\nGOTO 77\nM30\n%\n", 4, "no block N77"},
        LimitCase{"AmbiguousGotoTarget", "%\nO1\nGOTO 5\nN5 #1 = 1\nN5 #1 = 2\nM30\n%\n", 3,
                  "appears on lines 4 and 5"},
        LimitCase{"GotoIntoALoop", "%\nO1\nGOTO 8\nWHILE [1 EQ 1] DO1\nN8 #1 = 1\nEND1\nM30\n%\n",
                  3, "into the loop"},
        LimitCase{"StepLimit", "%\nO1\nN1 #1 = 1\nGOTO 1\nM30\n%\n", 3, "endless loop"},
        LimitCase{"MissingVariableRange", "%\nO1\n#200 = 1\nM30\n%\n", 3, "#200 does not exist"},
        LimitCase{"AssigningVacant", "%\nO1\n#0 = 1\nM30\n%\n", 3, "#0"},
        LimitCase{"SequenceNumberZero", "%\nO1\nN0 #1 = 1\nM30\n%\n", 3, "N0"},
        LimitCase{"ProgramNumber", "%\nO10000\nM30\n%\n", 2, "1 to 9999"},
        LimitCase{"LowerCase", "%\nO1\ng00 x1.\nM30\n%\n", 3, "lower-case"},
        LimitCase{"Semicolon", "%\nO1\nG00 X1.;\nM30\n%\n", 3, "';'"},
        LimitCase{"ParenthesisInComment", "%\nO1\n(A (B) C)\nM30\n%\n", 3, "'('"},
        LimitCase{"UnknownAddressStart", "%\nO1\n$1\nM30\n%\n", 3, "address letter"},
        LimitCase{"NoProgramEnd", "%\nO1\n#1 = 1\n%\n", 4, "without M30"},
        LimitCase{"DivisionByZero", "%\nO1\nG00 X[1/0]\nM30\n%\n", 3, "division by zero"}),
    [](const ::testing::TestParamInfo<LimitCase>& info) { return info.param.name; });

TEST(SimLimit, StepLimitIsAnOption) {
  SimulationOptions options;
  options.stepLimit = 50;
  SimulationError error = errorOf(
      "%\nO1\n#1 = 0\nWHILE [#1 LT 100] DO1\n#1 = #1 + 1\nEND1\nM30\n%\n", fanuc(), options);
  EXPECT_THAT(error.what(), HasSubstr("more than 50 blocks"));
}

TEST(SimLimit, TheSmallVariableOptionHasFewerCommons) {
  const ControllerProfile& small = *findControllerProfile("fanuc-0i-small");
  EXPECT_FALSE(simulateProgram("%\nO1\n#150 = 1\nM30\n%\n", fanuc()).error);
  SimulationError error = errorOf("%\nO1\n#150 = 1\nM30\n%\n", small);
  EXPECT_THAT(error.what(), HasSubstr("#150 does not exist on fanuc-0i-small"));
}

TEST(SimReader, ProgramFormat) {
  SimulationResult result = simulateProgram(
      "%\r\nO0001 (MAIN)\r\nN10 G21 G17 G90 (MM)\r\n/N20 G00 X1. Y2.\r\n\r\nN30 M30\r\n%\r\n"
      "anything after the end of record is not read\n",
      fanuc());
  ASSERT_FALSE(result.error) << result.error->what();
  EXPECT_EQ(result.path.events.size(), 1u);
  EXPECT_EQ(result.blocksExecuted, 4u);
}

} // namespace
} // namespace cncc::backends::sim
