// --stats figures of hand-made paths whose deviation, length and time are
// known in closed form.
#include "report_test_paths.h"

#include "cncc/backends/gcode_writer.h"
#include "cncc/backends/path_statistics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace cncc {
namespace {

using backends::ExecutedProgram;
using backends::PathStatistics;
using namespace report_test;

constexpr double pi = std::numbers::pi;

std::vector<ir::CutGeometry> twoCuts() {
  return {quarterCircle(0.5), quarterCircle(0.2)};
}

ExecutedProgram hostProgram() {
  return {"abc\n", 1, backends::executedPathOfToolPath(twoCutPath())};
}

TEST(ReportStatistics, DeviationOfEachCutIsTheSagittaOfItsChords) {
  PathStatistics statistics = backends::measureProgram(hostProgram(), twoCuts(), {});
  ASSERT_EQ(statistics.cuts.size(), 2u);
  EXPECT_NEAR(statistics.cuts[0].maxDeviation, sagitta(pi / 4), 1e-9); // 0.7612 mm
  EXPECT_NEAR(statistics.cuts[1].maxDeviation, sagitta(pi / 8), 1e-9); // 0.1921 mm
  EXPECT_FALSE(statistics.cuts[0].withinTolerance());
  EXPECT_TRUE(statistics.cuts[1].withinTolerance());
  EXPECT_EQ(statistics.cuts[0].feedMoves, 3u);
  EXPECT_EQ(statistics.cuts[1].feedMoves, 5u);
  EXPECT_NEAR(statistics.maxDeviation(), sagitta(pi / 4), 1e-9);
  // The worst place of the first cut is the middle of a chord: at 22.5 or 67.5 degrees.
  double angle = std::atan2(statistics.cuts[0].where.y(), statistics.cuts[0].where.x());
  EXPECT_NEAR(std::min(std::abs(angle - pi / 8), std::abs(angle - 3 * pi / 8)), 0.0, 1e-6);
}

// A helix descending 3 mm in a turn, cut by chords of 22.5 degrees that
// follow it down: measured in XY, its deviation is the chords' sagitta, not
// the 3 mm between the path's depth and z = 0.
TEST(ReportStatistics, MeasuresACurveThatDescendsInPlanView) {
  ir::CutGeometry helix;
  helix.curve =
      std::make_shared<geom::ArcCurve>(Eigen::Vector2d(0, 0), 10.0, 0.0, 2 * pi, 0.0, -3.0);
  helix.tolerance = 0.5;
  ir::ToolPath path;
  path.events.push_back(rapid(10, 0, 5));
  path.events.push_back(cutBegin(0));
  path.events.push_back(feed(10, 0, 0, 100));
  for (int step = 1; step <= 16; ++step) {
    double angle = step * pi / 8;
    path.events.push_back(feed(10 * std::cos(angle), 10 * std::sin(angle), -3.0 * step / 16, 100));
  }
  ExecutedProgram program{"", 0, backends::executedPathOfToolPath(path)};
  std::vector<ir::CutGeometry> cuts{helix};
  PathStatistics statistics = backends::measureProgram(program, cuts, {});
  ASSERT_EQ(statistics.cuts.size(), 1u);
  EXPECT_NEAR(statistics.cuts[0].maxDeviation, sagitta(pi / 8), 1e-6);
  EXPECT_TRUE(statistics.cuts[0].withinTolerance());
}

TEST(ReportStatistics, LengthsAndTimesAtTheProgrammedFeeds) {
  backends::StatisticsOptions options;
  options.rapidRate = 5000;
  PathStatistics statistics = backends::measureProgram(hostProgram(), twoCuts(), options);
  double chord45 = 20 * std::sin(pi / 8), chord22 = 20 * std::sin(pi / 16);
  EXPECT_EQ(statistics.feedMoves, 8u);
  EXPECT_EQ(statistics.rapidMoves, 3u);
  EXPECT_NEAR(statistics.feedLength, 12 + 2 * chord45 + 4 * chord22, 1e-12);
  EXPECT_NEAR(statistics.rapidLength, 6 + std::sqrt(200.0) + 6, 1e-12);
  EXPECT_NEAR(statistics.feedMinutes, 2 * 6 / 100.0 + 2 * chord45 / 200 + 4 * chord22 / 400, 1e-12);
  EXPECT_NEAR(statistics.rapidMinutes, (12 + std::sqrt(200.0)) / 5000, 1e-12);
  EXPECT_EQ(statistics.blocks, 1u);
  EXPECT_EQ(statistics.bytes, 4u);
}

TEST(ReportStatistics, GcodeRoundingIsPartOfTheMeasuredDeviation) {
  // Two chords of the quarter circle printed with one decimal: the measured
  // deviation is that of the printed points, not of the tool path.
  ir::ToolPath toolPath;
  double c = 10 * std::cos(pi / 4);
  toolPath.events = {rapid(10, 0, 1), cutBegin(0), feed(10, 0, 0, 100), feed(c, c, 0, 100),
                     feed(0, 10, 0, 100)};
  backends::GcodeOptions gcode;
  gcode.decimals = 1;
  std::string text = backends::writeGcode(toolPath, gcode);
  ExecutedProgram program{text, backends::countProgramBlocks(text),
                          backends::executeGcode(text, toolPath, 1)};
  std::vector<ir::CutGeometry> cuts = {quarterCircle(0.1)};
  PathStatistics rounded = backends::measureProgram(program, cuts, {});
  PathStatistics exact =
      backends::measureProgram({text, 0, backends::executedPathOfToolPath(toolPath)}, cuts, {});
  EXPECT_NEAR(exact.cuts[0].maxDeviation, sagitta(pi / 4), 1e-9);
  // The middle point is printed as (7.1, 7.1), off the circle: the chord from
  // (10, 0) to it passes 71 / |(-2.9, 7.1)| from the centre.
  EXPECT_NEAR(rounded.cuts[0].maxDeviation, 10 - 71 / std::hypot(2.9, 7.1), 1e-9);
  EXPECT_GT(std::abs(rounded.cuts[0].maxDeviation - exact.cuts[0].maxDeviation), 0.01);
  EXPECT_EQ(rounded.blocks, 11u);
}

TEST(ReportStatistics, CutWithoutFeedMovesOrToleranceIsReportedAsSuch) {
  std::vector<ir::CutGeometry> cuts = twoCuts();
  cuts.push_back(quarterCircle(std::nan("")));
  PathStatistics statistics = backends::measureProgram(hostProgram(), cuts, {});
  ASSERT_EQ(statistics.cuts.size(), 3u);
  EXPECT_TRUE(std::isnan(statistics.cuts[2].maxDeviation));
  std::string text = backends::formatStatistics(statistics, {});
  EXPECT_NE(text.find("cut 3: no feed moves"), std::string::npos) << text;
}

TEST(ReportStatistics, MoveOfAnUnknownCutIsAMismatch) {
  std::vector<ir::CutGeometry> oneCut = {quarterCircle(0.5)};
  EXPECT_THROW(backends::measureProgram(hostProgram(), oneCut, {}), backends::ExecutionMismatch);
}

TEST(ReportStatistics, TextGivesFiguresTolerancesAndTheRapidRate) {
  backends::StatisticsOptions options;
  options.cutNames = {"part.cdl:3"};
  PathStatistics statistics = backends::measureProgram(hostProgram(), twoCuts(), options);
  std::string text = backends::formatStatistics(statistics, options);
  EXPECT_NE(text.find("program: 1 blocks, 4 bytes\n"), std::string::npos) << text;
  EXPECT_NE(text.find("path: feed moves 42.915 mm (8 moves), rapids 26.142 mm (3 moves)\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("time: 14.3 s (feed moves 14.1 s, rapids 0.2 s), at the programmed feeds "
                      "and rapids at 10000 mm/min"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("part.cdl:3: max deviation 0.76120 mm"), std::string::npos) << text;
  EXPECT_NE(text.find("tolerance 0.5 mm, EXCEEDED"), std::string::npos) << text;
  EXPECT_NE(text.find("cut 2: max deviation 0.19215 mm"), std::string::npos) << text;
  EXPECT_NE(text.find("tolerance 0.2 mm, within"), std::string::npos) << text;
  EXPECT_NE(text.find("overall: max deviation 0.76120 mm; 1 of 2 cuts EXCEED"), std::string::npos)
      << text;
}

} // namespace
} // namespace cncc
