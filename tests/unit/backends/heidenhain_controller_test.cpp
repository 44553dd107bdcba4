// The virtual TNC on programs written here: formula precedence, FN
// arithmetic, jumps, repeats and subprograms, arcs and helices, and the
// errors it names by line.
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
      {{"L X+1 RL F100"}, 2, "RL/RR"},
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

} // namespace
} // namespace cncc::backends::heidenhain
