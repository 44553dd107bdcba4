#include "cncc/backends/gcode_writer.h"
#include "cncc/backends/tool_path_csv.h"

#include <gtest/gtest.h>

namespace cncc::backends {
namespace {

TEST(GcodeNumber, AlwaysHasAPointAndNoUselessZeros) {
  EXPECT_EQ(formatGcodeNumber(10, 4), "10.");
  EXPECT_EQ(formatGcodeNumber(0.5, 4), "0.5");
  EXPECT_EQ(formatGcodeNumber(-1.25, 4), "-1.25");
  EXPECT_EQ(formatGcodeNumber(1.23456, 4), "1.2346");
  EXPECT_EQ(formatGcodeNumber(1.23456, 3), "1.235");
  EXPECT_EQ(formatGcodeNumber(-0.00001, 4), "0.");
  EXPECT_EQ(formatGcodeNumber(0, 4), "0.");
}

TEST(CsvNumber, SixDecimalsTrimmed) {
  EXPECT_EQ(formatCsvNumber(25), "25");
  EXPECT_EQ(formatCsvNumber(0.5), "0.5");
  EXPECT_EQ(formatCsvNumber(1.0000004), "1");
  EXPECT_EQ(formatCsvNumber(-1e-9), "0");
  EXPECT_EQ(formatCsvNumber(-2.1234567), "-2.123457");
}

TEST(ProgramNumber, ComesFromAnOFileName) {
  EXPECT_EQ(programNumberFromFileName("O1234"), 1234);
  EXPECT_EQ(programNumberFromFileName("out/O1000.nc"), 1000);
  EXPECT_EQ(programNumberFromFileName("part.nc"), std::nullopt);
  EXPECT_EQ(programNumberFromFileName("-"), std::nullopt);
  EXPECT_EQ(programNumberFromFileName("O12a"), std::nullopt);
}

TEST(CommentText, PrintableWithoutParentheses) {
  // The case is the machine's (program_format.h): capitals by default.
  EXPECT_EQ(gcodeCommentText("part (a)\tb"), "part a b");
}

ir::MachineEvent move(ir::MachineEvent::Kind kind, double x, double y, double z, double f = 0) {
  ir::MachineEvent event;
  event.kind = kind;
  event.x = x;
  event.y = y;
  event.z = z;
  event.feed = f;
  return event;
}

TEST(Gcode, CoordinatesAndFeedAreModal) {
  using Kind = ir::MachineEvent::Kind;
  ir::ToolPath path;
  ir::MachineEvent tool;
  tool.kind = Kind::Tool;
  tool.number = 1;
  tool.diameter = 10;
  path.events.push_back(tool);
  ir::MachineEvent spindle;
  spindle.kind = Kind::Spindle;
  spindle.number = 3000;
  path.events.push_back(spindle);
  path.events.push_back(move(Kind::Rapid, 1, 2, 5));
  path.events.push_back(move(Kind::Feed, 1, 2, -1, 300));
  path.events.push_back(move(Kind::Feed, 3, 2, -1, 300));
  path.events.push_back(move(Kind::Feed, 3, 2, -1, 300));
  path.events.push_back(move(Kind::Feed, 3, 4.5, -1, 150));
  path.events.push_back(move(Kind::Rapid, 3, 4.5, 5));
  GcodeOptions options;
  options.programNumber = 1000;
  options.sourceName = "s_profile.cdl";
  options.partName = "s_profile";
  EXPECT_EQ(writeGcode(path, options), "%\n"
                                       "O1000\n"
                                       "(S_PROFILE.CDL - PART S_PROFILE)\n"
                                       "G21\n"
                                       "G17 G90\n"
                                       "G40 G49 G80\n"
                                       "T1 M06 (DIAMETER 10.)\n"
                                       "S3000 M03\n"
                                       "G00 G43 H1 Z5.\n"
                                       "G00 X1. Y2.\n"
                                       "G01 Z-1. F300.\n"
                                       "G01 X3.\n"
                                       "G01 Y4.5 F150.\n"
                                       "G00 Z5.\n"
                                       "M05\n"
                                       "M30\n"
                                       "%\n");
  EXPECT_EQ(writeToolPathCsv(path), "x,y,z,feed,rapid\n"
                                    "1,2,5,0,1\n"
                                    "1,2,-1,300,0\n"
                                    "3,2,-1,300,0\n"
                                    "3,2,-1,300,0\n"
                                    "3,4.5,-1,150,0\n"
                                    "3,4.5,5,0,1\n");
}

// The tool path's rows leave out a rapid to where the tool already is (a
// sweep's rapid over its start before the pass loop, then the first pass's);
// a feed is a row even where it does not move.
TEST(ToolPathCsv, LeavesOutARapidToWhereTheToolIs) {
  using Kind = ir::MachineEvent::Kind;
  ir::ToolPath path;
  path.events.push_back(move(Kind::Rapid, 1, 2, 5));
  path.events.push_back(move(Kind::Rapid, 1, 2, 5));
  path.events.push_back(move(Kind::Feed, 1, 2, -1, 300));
  path.events.push_back(move(Kind::Feed, 1, 2, -1, 300));
  path.events.push_back(move(Kind::Rapid, 1, 2, -1));
  path.events.push_back(move(Kind::Rapid, 1, 2, 5));
  EXPECT_EQ(writeToolPathCsv(path), "x,y,z,feed,rapid\n"
                                    "1,2,5,0,1\n"
                                    "1,2,-1,300,0\n"
                                    "1,2,-1,300,0\n"
                                    "1,2,5,0,1\n");
}

} // namespace
} // namespace cncc::backends
