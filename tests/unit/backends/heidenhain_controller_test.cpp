// The virtual TNC on programs written here: formula precedence, FN
// arithmetic, jumps, repeats and subprograms, arcs and helices, radius
// compensation RL/RR, and the errors it names by line.
#include "cncc/backends/heidenhain_controller.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

namespace cncc::backends::heidenhain {
namespace {

using ::testing::HasSubstr;

// The program `body` between BEGIN PGM and END PGM, numbered.
std::string program(const std::vector<std::string>& body) {
  std::string text = "0 BEGIN PGM T MM\n";
  int number = 1;
  for (const std::string& block : body) {
    text += std::to_string(number++) + " " + block + "\n";
  }
  return text + std::to_string(number) + " END PGM T MM\n";
}

// The X of the feed moves of a run.
std::vector<double> feedXs(const TncRun& run) {
  std::vector<double> xs;
  for (const ir::MachineEvent& event : run.path.events) {
    if (event.kind == ir::MachineEvent::Kind::Feed) {
      xs.push_back(event.x);
    }
  }
  return xs;
}

// Runs `X = formula` and gives the X the feed move reached.
double formulaValue(const std::string& formula) {
  TncRun run =
      runTncProgram(program({"L X+0 Y+0 Z+0 R0 FMAX", "QL1 = " + formula, "L X+QL1 F100"}));
  EXPECT_FALSE(run.error) << formula << ": " << run.error->message;
  std::vector<double> xs = feedXs(run);
  return xs.empty() ? 0 : xs.front();
}

TEST(TncController, ReadsFormulasWithTheControlsPrecedence) {
  EXPECT_DOUBLE_EQ(formulaValue("2 + 3 * 4 ^ 2"), 50);
  EXPECT_DOUBLE_EQ(formulaValue("SQ 3 - 1"), 8);
  EXPECT_DOUBLE_EQ(formulaValue("SIN ( 15 * 2 ) * 4"), 2);
  EXPECT_DOUBLE_EQ(formulaValue("INT -2.5 + FRAC 2.25"), -1.75);
  EXPECT_DOUBLE_EQ(formulaValue("( -3 ) * ( 1 - 2 ) / 2"), 1.5);
  EXPECT_DOUBLE_EQ(formulaValue("NEG ( 7 % 4 ) + ABS -1 + SGN -3"), -3);
  EXPECT_NEAR(formulaValue("ATAN 1 + ACOS 0 + PI"), 135 + 3.14159265358979, 1e-12);
}

TEST(TncController, RunsFnArithmeticJumpsAndRepeats) {
  TncRun run = runTncProgram(program({
      "L X+0 Y+0 Z+0 R0 FMAX",
      "FN 0: Q1 = +1",
      "FN 0: Q2 = +3",
      "LBL 1",
      "FN 11: IF +Q1 GT +Q2 GOTO LBL 2",
      "L X+Q1 F200",
      "FN 1: Q1 = +Q1 + +1",
      "FN 9: IF +0 EQU +0 GOTO LBL 1",
      "LBL 2",
      "FN 3: Q3 = +Q2 * -2",
      "FN 4: Q3 = +Q3 DIV +4",
      "L X+Q3",
      "LBL 5",
      "L X-Q3",
      "CALL LBL 5 REP 2",
      "CALL LBL 7",
      "L X+99",
      "FN 9: IF +0 EQU +0 GOTO LBL 8",
      "LBL 7",
      "L X+42",
      "LBL 0",
      "LBL 8",
  }));
  ASSERT_FALSE(run.error) << run.error->line << ": " << run.error->message;
  EXPECT_EQ(feedXs(run), (std::vector<double>{1, 2, 3, -1.5, 1.5, 1.5, 1.5, 42, 99}));
  EXPECT_GT(run.loopOperations.feedMoves, 0u);
  EXPECT_GT(run.loopOperations.operations.comparisons, 0u);
  EXPECT_EQ(run.parametersNamed, 3u);
}

TEST(TncController, RunsArcsAndHelicesAboutTheCentre) {
  TncRun run = runTncProgram(program(
      {"L X+10 Y+0 Z+0 R0 FMAX", "CC IX-10 IY+0", "C X+0 Y+10 DR+ F300", "C X+0 Y+10 IZ-2 DR-"}));
  ASSERT_FALSE(run.error) << run.error->message;
  ASSERT_EQ(run.path.events.size(), 3u);
  const ir::MachineEvent& quarter = run.path.events[1];
  EXPECT_EQ(quarter.kind, ir::MachineEvent::Kind::Arc);
  EXPECT_FALSE(quarter.clockwise);
  EXPECT_EQ(quarter.centreX, 0);
  const ir::MachineEvent& helix = run.path.events[2];
  EXPECT_TRUE(helix.clockwise);
  EXPECT_EQ(helix.z, -2);
  EXPECT_NEAR(ir::arcSweep(0, 10, helix), 2 * 3.14159265358979, 1e-9);
}

// SPL: per axis K3 t^3 + K2 t^2 + K1 t + the end, t from 1 to 0; an
// exponent word scales the coefficient before it; an axis without a
// coordinate stays where it is.
TEST(TncController, RunsSplineBlocks) {
  TncRun run = runTncProgram(program({
      "L X+20 Y+0 Z-1 R0 FMAX",
      "SPL X+0 Y+0 K3X+0 K2X+0 K1X+2 E+1 K3Y+1 K2Y-1 K1Y+0 F250",
  }));
  ASSERT_FALSE(run.error) << run.error->message;
  ASSERT_GT(run.path.events.size(), 3u);
  for (const ir::MachineEvent& event : run.path.events) {
    double t = event.x / 20; // x(t) = 20 t
    EXPECT_NEAR(event.y, t * t * t - t * t, 1e-12);
    EXPECT_EQ(event.z, -1);
  }
  const ir::MachineEvent& last = run.path.events.back();
  EXPECT_EQ(last.x, 0);
  EXPECT_EQ(last.feed, 250);
}

TEST(TncController, EditsTheBlockThatSetsAParameter) {
  std::string text = program({"FN 0: Q1 = +3", "FN 0: QL2 = +4", "L X+Q1 Y+QL2 Z+0 R0 FMAX"});
  std::optional<std::string> edited = withEditedParameter(text, 1, -2.5);
  ASSERT_TRUE(edited);
  EXPECT_THAT(*edited, HasSubstr("1 FN 0: Q1 = -2.5\n"));
  EXPECT_THAT(*edited, HasSubstr("2 FN 0: QL2 = +4\n"));
  EXPECT_FALSE(withEditedParameter(text, 7, 1));
}

struct BadProgram {
  std::vector<std::string> body;
  int line;
  std::string message;
};

TEST(TncController, NamesTheLineOfWhatItCannotRun) {
  const BadProgram cases[] = {
      {{"L X+QL4 F100"}, 2, "QL4 is read before any block sets it"},
      {{"FN 9: IF +0 EQU +0 GOTO LBL 3"}, 2, "there is no LBL 3"},
      {{"LBL 1", "LBL 1"}, 3, "LBL 1 is defined twice"},
      {{"FN 14: ERROR = 7"}, 2, "FN 14: ERROR = 7"},
      {{"FN 6: Q1 = SIN +30"}, 2, "FN 6 is not modelled"},
      {{"L X+0 Y+0 Z+0 R0 FMAX", "CC X+5 Y+0", "C X+5 Y+6 DR+ F100"}, 4, "from the circle"},
      {{"L X+0 Y+0 Z+0 R0 FMAX", "L X+4"}, 3, "before any feed rate"},
      {{"Q1 = 2 * ( 3 + 4"}, 2, "without its ')'"},
      {{"Q1 = 1 / 0"}, 2, "division by zero"},
      {{"L X+1 RL F100"}, 2, "RL/RR from an unknown position"},
      {{"LBL 1", "FN 9: IF +0 EQU +0 GOTO LBL 1"}, 3, "more than"},
      {{"FN 0: Q1 = +1e12"}, 2, "beyond the control's"},
      {{"L X+1 Y+0 Z+0 R0 FMAX", "SPL X+0 Y+0 Z+0 K3X+0 K2X+0 K1X+1 F100"}, 3, "K3Y K2Y K1Y"},
      {{"L X+1 Y+0 Z+0 R0 FMAX", "SPL X+0 Y+0 Z+0 K3X+0 K2X+0 K1X+1.01 K3Y+0 K2Y+0 K1Y+0 K3Z+0 "
                                 "K2Z+0 K1Z+0 F100"},
       3,
       "from where the machine is"},
      {{"L X+1 Y+0 Z+0 R0 FMAX", "SPL X+0 K3X+0 K2X+0 K1X+1 E+256 F100"}, 3, "no exponent"},
  };
  for (const BadProgram& bad : cases) {
    TncRunOptions options;
    options.stepLimit = 1000;
    TncRun run = runTncProgram(program(bad.body), options);
    ASSERT_TRUE(run.error) << bad.message;
    EXPECT_EQ(run.error->line, bad.line) << bad.message;
    EXPECT_THAT(run.error->message, HasSubstr(bad.message));
  }
  TncRun unnumbered = runTncProgram("0 BEGIN PGM T MM\n2 L X+1\n3 END PGM T MM\n");
  ASSERT_TRUE(unnumbered.error);
  EXPECT_EQ(unnumbered.error->line, 2);
  EXPECT_THAT(unnumbered.error->message, HasSubstr("expected block number 1"));
  TncRun unended = runTncProgram("0 BEGIN PGM T MM\n1 L X+1\n");
  ASSERT_TRUE(unended.error);
  EXPECT_THAT(unended.error->message, HasSubstr("END PGM"));
}

// ---- radius compensation RL/RR/R0 -------------------------------------------

// Tool 1 down at (-10, -10), `body` with the tool table's R of tool 1 at 2,
// up again.
TncRun compensated(const std::vector<std::string>& body, double radius = 2) {
  std::vector<std::string> blocks = {"TOOL CALL 1 Z S1000", "L X-10 Y-10 Z+5 R0 FMAX",
                                     "L Z-1 F100"};
  blocks.insert(blocks.end(), body.begin(), body.end());
  blocks.push_back("L Z+5 R0 FMAX");
  TncRunOptions options;
  options.toolRadii[1] = radius;
  return runTncProgram(program(blocks), options);
}

struct Move {
  ir::MachineEvent::Kind kind;
  double x, y;
};

// The moves after the plunge, up to the retract.
void expectMoves(const TncRun& run, const std::vector<Move>& expected) {
  ASSERT_FALSE(run.error) << run.error->line << ": " << run.error->message;
  std::vector<ir::MachineEvent> moves(run.path.events.begin() + 2, run.path.events.end() - 1);
  ASSERT_EQ(moves.size(), expected.size());
  for (std::size_t index = 0; index < expected.size(); ++index) {
    EXPECT_EQ(moves[index].kind, expected[index].kind) << "move " << index;
    EXPECT_NEAR(moves[index].x, expected[index].x, 1e-9) << "move " << index;
    EXPECT_NEAR(moves[index].y, expected[index].y, 1e-9) << "move " << index;
    EXPECT_DOUBLE_EQ(moves[index].z, -1) << "move " << index;
  }
}

constexpr auto Line = ir::MachineEvent::Kind::Feed;
constexpr auto Arc = ir::MachineEvent::Kind::Arc;

TEST(TncCompensation, GoesRoundTheOutsideCornersOfASquareOnArcs) {
  // Clockwise round the square (0,0)-(20,20): RL is outside. The TNC
  // inserts an arc of the tool radius about each outside corner, where a
  // Fanuc's type A meets at the intersection.
  TncRun run =
      compensated({"L X+0 Y+0 RL", "L Y+20", "L X+20", "L Y+0", "L X+0", "L X-10 Y-10 R0"});
  expectMoves(run, {{Line, -2, 0}, // start-up: normal to the first side at its start
                    {Line, -2, 20},
                    {Arc, 0, 22}, // about the corner (0, 20)
                    {Line, 20, 22},
                    {Arc, 22, 20},
                    {Line, 22, 0},
                    {Arc, 20, -2},
                    {Line, 0, -2},      // the last side ends normal to itself
                    {Line, -10, -10}}); // R0: back to the programmed point
  const ir::MachineEvent& corner = run.path.events[4];
  EXPECT_TRUE(corner.clockwise);
  EXPECT_DOUBLE_EQ(corner.centreX, 0);
  EXPECT_DOUBLE_EQ(corner.centreY, 20);
  EXPECT_EQ(corner.feed, 100);
}

TEST(TncCompensation, MeetsAtTheIntersectionInsideTheSquareWithRR) {
  TncRun run =
      compensated({"L X+0 Y+0 RR", "L Y+20", "L X+20", "L Y+0", "L X+0", "L X-10 Y-10 R0"});
  expectMoves(
      run,
      {{Line, 2, 0}, {Line, 2, 18}, {Line, 18, 18}, {Line, 18, 2}, {Line, 0, 2}, {Line, -10, -10}});
}

TEST(TncCompensation, OffsetsAFullCircleBetweenTangentLines) {
  // Up to the circle of radius 10 about (10, 0), once round it clockwise
  // with RL (outside: radius 10 + 3), away on a tangent line.
  TncRun run = compensated(
      {"L X+0 Y-10 RL", "L Y+0", "CC X+10 Y+0", "C X+0 Y+0 DR-", "L Y+10", "L X-10 Y-10 R0"}, 3);
  expectMoves(run, {{Line, -3, -10},
                    {Line, -3, 0},
                    {Arc, -3, 0}, // a full turn at radius 13
                    {Line, -3, 10},
                    {Line, -10, -10}});
  const ir::MachineEvent& circle = run.path.events[4];
  EXPECT_TRUE(circle.clockwise);
  EXPECT_DOUBLE_EQ(circle.centreX, 10);
  EXPECT_DOUBLE_EQ(circle.centreY, 0);
}

TEST(TncCompensation, NamesTheLineOfWhatItCannotRun) {
  struct Case {
    std::vector<std::string> body; // from line 5
    int line;
    std::string message;
  };
  const Case bad[] = {
      {{"CC X-10 Y+0", "C X-10 Y+10 DR+ RL"}, 6, "RL/RR on a C block"},
      {{"L Z-2 RL"}, 5, "on a block without an X or Y move"},
      {{"L X+0 Y+0 RL", "L Y+20", "CC X+0 Y+30", "C X+0 Y+40 DR- R0"}, 8, "R0 on a C block"},
      {{"L X+0 Y+0 RL", "L Y+20", "L X+5 RR"}, 7, "RR while RL is on"},
      {{"L X+0 Y+0 RL", "L Y+20"}, 7, "R0 on a block without an X or Y move"},
      // A hole of radius 1 for a tool of radius 2, counterclockwise with
      // RL: the offset circle does not exist (the line of the C block).
      {{"L X+0 Y+0 R0", "L X+1 RL", "CC X+0 Y+0", "C X+1 Y+0 DR+", "L X+0 R0"},
       8,
       "smaller than the tool radius"},
      {{"TOOL CALL 2 Z", "L X+0 Y+0 RL", "L Y+20", "L X-10 R0"}, 6, "--tool-radius 2=R"},
  };
  for (const Case& one : bad) {
    TncRun run = compensated(one.body);
    ASSERT_TRUE(run.error) << one.message;
    EXPECT_EQ(run.error->line, one.line) << one.message << ": " << run.error->message;
    EXPECT_THAT(run.error->message, HasSubstr(one.message));
  }
  TncRunOptions options;
  options.toolRadii[1] = 2;
  TncRun unended = runTncProgram(
      program({"TOOL CALL 1 Z", "L X+0 Y+0 Z+0 R0 FMAX", "L X+5 RL F100", "L Y+5"}), options);
  ASSERT_TRUE(unended.error);
  EXPECT_EQ(unended.error->line, 6);
  EXPECT_THAT(unended.error->message, HasSubstr("cancel it with R0"));
}

} // namespace
} // namespace cncc::backends::heidenhain
