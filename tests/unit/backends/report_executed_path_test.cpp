// The executed path of a host run and of a G-code program, with the cut of
// every feed move.
#include "report_test_paths.h"

#include "cncc/backends/executed_path.h"
#include "cncc/backends/gcode_writer.h"

#include <gtest/gtest.h>

namespace cncc {
namespace {

using backends::ExecutedMove;
using backends::ExecutedPath;
using namespace report_test;

std::size_t feedMovesOfCut(const ExecutedPath& path, std::size_t cut) {
  std::size_t count = 0;
  for (const ExecutedMove& move : path.moves) {
    count += !move.rapid && move.cut == cut ? 1 : 0;
  }
  return count;
}

TEST(ReportExecutedPath, HostRunStartsAtTheFirstTargetAndKeepsTheCuts) {
  ExecutedPath path = backends::executedPathOfToolPath(twoCutPath());
  EXPECT_EQ(path.start, Eigen::Vector3d(10, 0, 5));
  ASSERT_EQ(path.moves.size(), 11u); // 8 feed moves and 3 rapids after the first
  EXPECT_FALSE(path.moves[0].rapid);
  EXPECT_EQ(path.moves[0].cut, 0u);
  EXPECT_EQ(path.moves[0].feed, 100);
  EXPECT_EQ(path.moves[1].feed, 200);
  EXPECT_TRUE(path.moves[3].rapid);
  EXPECT_FALSE(path.moves[3].cut.has_value());
  EXPECT_EQ(feedMovesOfCut(path, 0), 3u);
  EXPECT_EQ(feedMovesOfCut(path, 1), 5u);
  EXPECT_EQ(path.startOf(1), Eigen::Vector3d(10, 0, -1));
}

TEST(ReportExecutedPath, GcodeRoundsToThePrintedDecimalsAndSplitsRapids) {
  ir::ToolPath toolPath;
  toolPath.events = {rapid(0, 0, 5),
                     cutBegin(0),
                     feed(0, 0, -1, 100),
                     feed(1.23456, 2.000049, -1, 100),
                     feed(1.23456, 2.000049, -1, 100),
                     rapid(1.23456, 2.000049, 5),
                     rapid(7, 8, 3)};
  backends::GcodeOptions options;
  std::string program = backends::writeGcode(toolPath, options);
  ExecutedPath path = backends::executeGcode(program, toolPath, options.decimals);
  EXPECT_EQ(path.start, Eigen::Vector3d(0, 0, 5));
  // The repeated feed move prints nothing; the last rapid goes across, then down.
  ASSERT_EQ(path.moves.size(), 5u);
  EXPECT_EQ(path.moves[1].end, Eigen::Vector3d(1.2346, 2.0, -1));
  EXPECT_EQ(path.moves[1].cut, 0u);
  EXPECT_EQ(path.moves[1].feed, 100);
  EXPECT_TRUE(path.moves[2].rapid);
  EXPECT_EQ(path.moves[3].end, Eigen::Vector3d(7, 8, 5));
  EXPECT_EQ(path.moves[4].end, Eigen::Vector3d(7, 8, 3));
  EXPECT_FALSE(path.moves[4].cut.has_value());
}

TEST(ReportExecutedPath, GcodeOfTwoCutsKeepsEachCutsMoves) {
  ir::ToolPath toolPath = twoCutPath();
  std::string program = backends::writeGcode(toolPath, {});
  ExecutedPath path = backends::executeGcode(program, toolPath, 4);
  EXPECT_EQ(feedMovesOfCut(path, 0), 3u);
  EXPECT_EQ(feedMovesOfCut(path, 1), 5u);
  EXPECT_NEAR(path.moves.back().end.y(), 10.0, 1e-12);
}

TEST(ReportExecutedPath, GcodeThatDoesNotMatchItsToolPathIsAMismatch) {
  ir::ToolPath toolPath = twoCutPath();
  std::string program = backends::writeGcode(toolPath, {});
  std::size_t feedBlock = program.find("G01 X");
  ASSERT_NE(feedBlock, std::string::npos);
  std::string altered = program;
  altered.replace(feedBlock, 5, "G01 X1");
  EXPECT_THROW(backends::executeGcode(altered, toolPath, 4), backends::ExecutionMismatch);
  EXPECT_THROW(backends::executeGcode(program + "G01 X99.\n", toolPath, 4),
               backends::ExecutionMismatch);
  EXPECT_THROW(backends::executeGcode("G02 X1. Y1. I1. J0.\n", toolPath, 4),
               backends::ExecutionMismatch);
  EXPECT_THROW(backends::executeGcode("G01 X1..2\n", toolPath, 4), backends::ExecutionMismatch);
}

// The end retract and a tool change's return to the reference point move in
// machine coordinates: no move of the tool path.
TEST(ReportExecutedPath, RetractsInMachineCoordinatesAreNotToolPathMoves) {
  ir::ToolPath toolPath;
  ir::MachineEvent home;
  home.kind = ir::MachineEvent::Kind::Home;
  toolPath.events = {rapid(1, 2, 3), cutBegin(0), feed(4, 2, 3, 50), home};
  std::string program = "G00 X1. Y2. Z3.\nG01 X4. F50.\nG91 G28 Z0.\nG90\nG53 G00 Z0.\nM30\n";
  ExecutedPath path = backends::executeGcode(program, toolPath, 4);
  ASSERT_EQ(path.moves.size(), 1u);
  EXPECT_EQ(path.moves[0].end, Eigen::Vector3d(4, 2, 3));
}

TEST(ReportExecutedPath, GcodeReaderIgnoresCommentsAndOtherWords) {
  ir::ToolPath toolPath;
  toolPath.events = {rapid(1, 2, 3), cutBegin(0), feed(4, 2, 3, 50)};
  std::string program = "%\nO1 (A COMMENT WITH X9 Y9)\nN10 G21 G17 G90\nG00 X1. Y2. Z3. ; X8\n"
                        "S1000 M03\nN20 G01 X4. F50.\nM30\n%\n";
  ExecutedPath path = backends::executeGcode(program, toolPath, 4);
  ASSERT_EQ(path.moves.size(), 1u);
  EXPECT_EQ(path.start, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(path.moves[0].end, Eigen::Vector3d(4, 2, 3));
  EXPECT_EQ(path.moves[0].feed, 50);
  EXPECT_EQ(path.moves[0].cut, 0u);
}

TEST(ReportExecutedPath, BlocksAreLinesOtherThanTapeMarksAndEmptyLines) {
  EXPECT_EQ(backends::countProgramBlocks("%\nO1\nG21\n\nG00 X1.\nM30\n%\n"), 4u);
  EXPECT_EQ(backends::countProgramBlocks(""), 0u);
  EXPECT_EQ(backends::countProgramBlocks("x,y\n1,2"), 2u);
}

} // namespace
} // namespace cncc
