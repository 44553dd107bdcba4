#include "cncc/backends/program_format.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace cncc::backends {
namespace {

MachineSetup numbered(std::string_view target, int start = 10, int increment = 10,
                      int maximum = 99999) {
  MachineSetup setup = builtinMachineSetup(target);
  setup.lineNumbers = {true, start, increment, maximum};
  return setup;
}

std::vector<std::string> format(const std::vector<std::string>& lines, const MachineSetup& setup,
                                std::vector<std::string>* errors = nullptr) {
  std::vector<std::string> problems;
  std::vector<std::string> result = formatProgram(lines, setup, problems).lines;
  if (errors != nullptr) {
    *errors = problems;
  } else {
    EXPECT_TRUE(problems.empty()) << problems.front();
  }
  return result;
}

TEST(ProgramFormatTest, NumbersBlocksButNotHeadersOrCommentLines) {
  std::vector<std::string> lines = {"%", "O1000 (PART)", "(TOOL 1)", "G21 G17 G90",
                                    "",  "G0 Z5.",       "M30",      "%"};
  EXPECT_EQ(format(lines, numbered("fanuc")),
            (std::vector<std::string>{"%", "O1000 (PART)", "(TOOL 1)", "N10 G21 G17 G90", "",
                                      "N20 G0 Z5.", "N30 M30", "%"}));
}

TEST(ProgramFormatTest, MacroJumpTargetsTakeTheirLineNumbers) {
  std::vector<std::string> lines = {
      "IF [#1 LT 3.] GOTO 2", "G0 X1.", "GOTO 1", "N2", "G0 X2.", "N1", "M30"};
  EXPECT_EQ(format(lines, numbered("m80", 100, 5)),
            (std::vector<std::string>{"N100 IF [#1 LT 3.] GOTO 115", "N105 G0 X1.", "N110 GOTO 125",
                                      "N115", "N120 G0 X2.", "N125", "N130 M30"}));
}

TEST(ProgramFormatTest, AJumpInACommentIsNotRenumbered) {
  std::vector<std::string> lines = {"G0 X1. (GOTO 1)", "N1"};
  EXPECT_EQ(format(lines, numbered("fanuc")),
            (std::vector<std::string>{"N10 G0 X1. (GOTO 1)", "N20"}));
}

TEST(ProgramFormatTest, ANumberTooLongForALabelIsAnOrdinaryBlock) {
  EXPECT_EQ(format({"N1234567890123", "GOTO 98765432109876"}, numbered("fanuc")),
            (std::vector<std::string>{"N10 N1234567890123", "N20 GOTO 98765432109876"}));
}

TEST(ProgramFormatTest, NumbersStartAgainAfterTheMaximum) {
  std::vector<std::string> lines = {"G0 X1.", "G0 X2.", "G0 X3."};
  EXPECT_EQ(format(lines, numbered("gcode", 1, 4, 8)),
            (std::vector<std::string>{"N1 G0 X1.", "N5 G0 X2.", "N1 G0 X3."}));
}

TEST(ProgramFormatTest, WrappedNumbersInAProgramWithJumpsAreAnError) {
  std::vector<std::string> lines = {"GOTO 1", "G0 X1.", "G0 X2.", "N1"};
  std::vector<std::string> errors;
  format(lines, numbered("fanuc", 1, 1, 3), &errors);
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_NE(errors.front().find("after N3"), std::string::npos) << errors.front();
}

TEST(ProgramFormatTest, LinuxcncOWordsAndSinumerikHeadersTakeNoNumber) {
  EXPECT_EQ(format({"o100 while [#1 LT 3]", "#1 = [#1 + 1]", "o100 endwhile", "o<ring> sub"},
                   numbered("linuxcnc")),
            (std::vector<std::string>{"o100 while [#1 LT 3]", "N10 #1 = [#1 + 1]", "o100 endwhile",
                                      "o<ring> sub"}));
  EXPECT_EQ(format({"%_N_RING_SPF", ";$PATH=/_N_SPF_DIR", "PROC RING", "G1 X1", "M17"},
                   numbered("sinumerik", 1, 1)),
            (std::vector<std::string>{"%_N_RING_SPF", ";$PATH=/_N_SPF_DIR", "PROC RING", "N1 G1 X1",
                                      "N2 M17"}));
}

TEST(ProgramFormatTest, CommentsOffKeepOnlyWhatTheControllerActsOn) {
  MachineSetup fanuc = builtinMachineSetup("fanuc");
  fanuc.comments = false;
  EXPECT_EQ(format({"O1000 (PART)", "(TOOL 1)", "T1 M6 (DIAMETER 6.)", "#3000=1 (RADIUS)"}, fanuc),
            (std::vector<std::string>{"O1000", "T1 M6", "#3000=1 (RADIUS)"}));
  MachineSetup linuxcnc = builtinMachineSetup("linuxcnc");
  linuxcnc.comments = false;
  EXPECT_EQ(format({"; ring", "(abort, radius)", "G0 Z5 (up)", "T1 M6 ; tool"}, linuxcnc),
            (std::vector<std::string>{"(abort, radius)", "G0 Z5", "T1 M6"}));
  MachineSetup sinumerik = builtinMachineSetup("sinumerik");
  sinumerik.comments = false;
  EXPECT_EQ(format({";$PATH=/_N_MPF_DIR", "; cut 1", "T=\"T;1\" D1 ; tool 1"}, sinumerik),
            (std::vector<std::string>{";$PATH=/_N_MPF_DIR", "T=\"T;1\" D1"}));
}

TEST(ProgramFormatTest, CommentsInCapitalsOrAsWritten) {
  MachineSetup fanuc = builtinMachineSetup("fanuc");
  EXPECT_EQ(format({"O1000 (ring.cdl - part ring)"}, fanuc),
            std::vector<std::string>{"O1000 (RING.CDL - PART RING)"});
  fanuc.commentCase = CommentCase::AsWritten;
  EXPECT_EQ(format({"O1000 (ring.cdl - part ring)"}, fanuc),
            std::vector<std::string>{"O1000 (ring.cdl - part ring)"});
}

TEST(ProgramFormatTest, KeepsTheLineEachFormattedLineCameFrom) {
  MachineSetup gcode = builtinMachineSetup("gcode");
  gcode.comments = false;
  std::vector<std::string> errors;
  FormattedProgram program = formatProgram({"(A)", "G0 X1.", "(B)", "G0 X2."}, gcode, errors);
  EXPECT_EQ(program.printedLine, (std::vector<std::size_t>{1, 3}));
}

} // namespace
} // namespace cncc::backends
