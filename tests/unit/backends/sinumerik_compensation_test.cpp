// The virtual Sinumerik's tool radius compensation: G41/G42 with the radius
// of the active tool's cutting edge, the approach and retract, corners
// inside (the offsets' crossing) and outside (G450's transition circle),
// arcs offset, and the alarms.
#include "cncc/backends/sinumerik_controller.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace cncc::backends::sinumerik {
namespace {

using Eigen::Vector3d;

SinumerikRunOptions radii(int tool, double radius) {
  SinumerikRunOptions options;
  options.toolRadii[tool] = radius;
  return options;
}

SinumerikRun runOk(const std::string& text, const SinumerikRunOptions& options) {
  SinumerikRun run = runSinumerikProgram(text, options);
  EXPECT_FALSE(run.error) << (run.error ? run.error->what() : "");
  return run;
}

// The index of the first move ending at (x, y) from `from` on, or the move count.
std::size_t moveTo(const SinumerikRun& run, double x, double y, std::size_t from = 0) {
  for (std::size_t i = from; i < run.moves.size(); ++i) {
    if ((run.moves[i].end.head<2>() - Eigen::Vector2d(x, y)).norm() < 1e-9) {
      return i;
    }
  }
  return run.moves.size();
}

// A counterclockwise 10 mm square from (0, 0), approached from (0, -5) and
// left towards (-5, 1), with `code` (G41 or G42) on the approach.
std::string square(const std::string& code) {
  return "T=\"T1\"\nM6\nD1\nG0 X0 Y-5 Z0\nG1 F100\n" + code +
         " X0 Y0\nX10\nY10\nX0\nY1\nG40 X-5\nG0 Z5\nM30\n";
}

TEST(SinumerikCompensation, OutsideCornersGoRoundOnTheToolRadius) {
  // G42 on a counterclockwise square is outside: the offsets lie 2 mm out,
  // joined by quarter circles of radius 2 about the corners (G450).
  SinumerikRun run = runOk(square("G42 G450"), radii(1, 2));
  std::size_t at = 0;
  for (auto [x, y] : {std::pair{0.0, -2.0},
                      {10.0, -2.0},
                      {12.0, 0.0},
                      {12.0, 10.0},
                      {10.0, 12.0},
                      {0.0, 12.0},
                      {-2.0, 10.0},
                      {-2.0, 1.0},
                      {-5.0, 1.0}}) {
    std::size_t found = moveTo(run, x, y, at);
    ASSERT_LT(found, run.moves.size()) << "no move to (" << x << ", " << y << ")";
    at = found;
  }
  // Between (10, -2) and (12, 0) the tool stays 2 mm from the corner.
  std::size_t first = moveTo(run, 10, -2);
  std::size_t last = moveTo(run, 12, 0);
  ASSERT_GT(last, first + 2); // an arc, in chords
  for (std::size_t i = first; i <= last; ++i) {
    EXPECT_NEAR((run.moves[i].end.head<2>() - Eigen::Vector2d(10, 0)).norm(), 2, 1e-9);
    // The side ends on its own block, the corner on the block it leads into.
    EXPECT_EQ(run.moves[i].line, i == first ? 7 : 8);
  }
  EXPECT_EQ(run.moves.back().end, Vector3d(-5, 1, 5));
}

TEST(SinumerikCompensation, InsideCornersMeetWhereTheOffsetsCross) {
  // G41 on the same square is inside: straight from crossing to crossing.
  SinumerikRun run = runOk(square("G41"), radii(1, 2));
  std::vector<Eigen::Vector2d> ends;
  for (const ExecutedSinumerikMove& move : run.moves) {
    ends.push_back(move.end.head<2>());
  }
  // The approach to (0, 2), the sides' crossings, the last side's offset
  // end, the retract from it and the move up.
  std::vector<Eigen::Vector2d> expected{{0, 2}, {8, 2}, {8, 8}, {2, 8}, {2, 1}, {-5, 1}, {-5, 1}};
  ASSERT_EQ(ends.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_LT((ends[i] - expected[i]).norm(), 1e-9) << i;
  }
}

TEST(SinumerikCompensation, ArcsAreOffsetByTheRadiusOfTheToolNamed) {
  // A half circle of radius 5 about (0, 0), counterclockwise, G42 outside:
  // radius 6.5 with tool 7's edges of radius 1.5.
  SinumerikRun run = runOk("T=\"T7\"\nM6\nG0 X5 Y-5 Z-1\nG1 F200\nG42 Y0\n"
                           "G3 X-5 Y0 I-5 J0\nG1 Y-3\nG40 X-8\nM30\n",
                           radii(7, 1.5));
  std::size_t start = moveTo(run, 6.5, 0);
  std::size_t end = moveTo(run, -6.5, 0);
  ASSERT_LT(end, run.moves.size());
  ASSERT_GT(end, start + 10);
  for (std::size_t i = start; i <= end; ++i) {
    EXPECT_NEAR(run.moves[i].end.head<2>().norm(), 6.5, 1e-9) << i;
    EXPECT_GE(run.moves[i].end.y(), -1e-9);
  }
  EXPECT_LT(moveTo(run, -6.5, -3, end), run.moves.size());
}

TEST(SinumerikCompensation, AlarmsNameTheirBlock) {
  auto errorOf = [](const std::string& text, const SinumerikRunOptions& options) {
    SinumerikRun run = runSinumerikProgram(text, options);
    EXPECT_TRUE(run.error);
    return run.error ? std::pair{run.error->line(), std::string(run.error->what())}
                     : std::pair{0, std::string()};
  };
  // No radius known for the tool.
  auto [line, message] = errorOf(square("G42"), radii(2, 2));
  EXPECT_EQ(line, 6);
  EXPECT_NE(message.find("no radius for tool T1"), std::string::npos) << message;
  // Still on at M30.
  std::tie(line, message) =
      errorOf("T=\"T1\"\nM6\nG0 X0 Y-5 Z0\nG1 F100\nG41 X0 Y0\nX10\nY10\nM30\n", radii(1, 2));
  EXPECT_EQ(line, 8);
  EXPECT_NE(message.find("G40"), std::string::npos) << message;
  // An arc smaller than the tool on its inside.
  std::tie(line, message) = errorOf("T=\"T1\"\nM6\nG0 X5 Y-5 Z0\nG1 F100\nG41 Y0\n"
                                    "G3 X-5 Y0 I-5 J0\nG1 Y-5\nG40 X-8\nM30\n",
                                    radii(1, 6));
  EXPECT_EQ(line, 6);
  EXPECT_NE(message.find("smaller than the tool radius"), std::string::npos) << message;
  // G451 is not modelled, nor are splines inside compensation.
  std::tie(line, message) = errorOf(square("G42 G451"), radii(1, 2));
  EXPECT_EQ(line, 6);
  std::tie(line, message) = errorOf("T=\"T1\"\nM6\nG0 X0 Y-5 Z0\nG1 F100\nG41 X0 Y0\n"
                                    "BSPLINE X10 Y0\nX10 Y10\nX0 Y10\nG1 G40 X-5\nM30\n",
                                    radii(1, 2));
  EXPECT_EQ(line, 6);
  // D0: no cutting edge to take the radius of.
  std::tie(line, message) =
      errorOf("T=\"T1\"\nM6\nD0\nG0 X0 Y-5 Z0\nG1 F100\nG41 X0 Y0\nM30\n", radii(1, 2));
  EXPECT_EQ(line, 6);
}

} // namespace
} // namespace cncc::backends::sinumerik
