// Reading rs274's canonical calls back into an executed path.
#include "cncc/backends/linuxcnc_canon.h"

#include <gtest/gtest.h>

#include <cmath>

namespace cncc::backends {
namespace {

TEST(LinuxcncCanon, ReadsTraversesFeedsAndFeedRates) {
  ExecutedPath path = readLinuxcncCanon(
      "    1 N..... USE_LENGTH_UNITS(CANON_UNITS_MM)\n"
      "   20 N..... STRAIGHT_TRAVERSE(0.0000, 0.0000, 5.0000, 0.0000, 0.0000, 0.0000)\n"
      "   21 N..... SET_FEED_RATE(300.0000)\n"
      "   22 N..... STRAIGHT_FEED(3.0000, 135.0000, -1.0000, 0.0000, 0.0000, 0.0000)\n"
      "   23 N..... COMMENT(\"interpreter: motion mode set to none\")\n");
  EXPECT_EQ(path.start, Eigen::Vector3d::Zero());
  ASSERT_EQ(path.moves.size(), 2u);
  EXPECT_TRUE(path.moves[0].rapid);
  EXPECT_EQ(path.moves[0].end, Eigen::Vector3d(0, 0, 5));
  EXPECT_FALSE(path.moves[1].rapid);
  EXPECT_EQ(path.moves[1].end, Eigen::Vector3d(3, 135, -1));
  EXPECT_EQ(path.moves[1].feed, 300);
}

TEST(LinuxcncCanon, ArcsBecomeChordsOnTheCircle) {
  // From (1, 0) clockwise around the origin to (-1, 0), descending to z -1.
  ExecutedPath path = readLinuxcncCanon(
      "STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
      "ARC_FEED(-1.0000, 0.0000, 0.0000, 0.0000, -1, -1.0000, 0.0000, 0.0000, 0.0000)\n",
      1e-4);
  ASSERT_GT(path.moves.size(), 20u);
  for (std::size_t i = 1; i < path.moves.size(); ++i) {
    const Eigen::Vector3d& point = path.moves[i].end;
    EXPECT_NEAR(point.head<2>().norm(), 1, 1e-12);
    EXPECT_LE(point.y(), 1e-12) << "clockwise from (1, 0) passes below the origin";
  }
  EXPECT_EQ(path.moves.back().end, Eigen::Vector3d(-1, 0, -1));
  // A full counterclockwise turn where the arc ends where it starts.
  ExecutedPath circle = readLinuxcncCanon(
      "STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
      "ARC_FEED(1.0000, 0.0000, 0.0000, 0.0000, 1, 0.0000, 0.0000, 0.0000, 0.0000)\n",
      1e-4);
  double highest = 0;
  for (const ExecutedMove& move : circle.moves) {
    highest = std::max(highest, move.end.y());
  }
  EXPECT_NEAR(highest, 1, 1e-3);
}

TEST(LinuxcncCanon, RefusesNurbsAndMalformedMoves) {
  EXPECT_THROW(readLinuxcncCanon("NURBS_FEED(5, ...)\n"), ExecutionMismatch);
  EXPECT_THROW(readLinuxcncCanon("STRAIGHT_FEED(1.0000)\n"), ExecutionMismatch);
  EXPECT_THROW(readLinuxcncCanon("STRAIGHT_FEED(1.0000, x, 2.0000)\n"), ExecutionMismatch);
}

TEST(LinuxcncCanon, StopsBeforeThePathPassesItsLimit) {
  // A helix of 1000 turns (P1000) of radius 1: 1000 times the chords of one
  // turn (about 222 within 1e-4), refused before they are made.
  const char* helix = "STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
                      "ARC_FEED(1.0000, 0.0000, 0.0000, 0.0000, 1000, -9.0000, 0.0000, 0.0000, "
                      "0.0000)\n";
  std::size_t oneTurn =
      readLinuxcncCanon("STRAIGHT_TRAVERSE(1.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
                        "ARC_FEED(1.0000, 0.0000, 0.0000, 0.0000, 1, 0.0000, 0.0000, 0.0000, "
                        "0.0000)\n",
                        1e-4)
          .moves.size();
  EXPECT_NEAR(static_cast<double>(readLinuxcncCanon(helix, 1e-4, 1001.0 * oneTurn).moves.size()),
              1000.0 * static_cast<double>(oneTurn), 0.01 * 1000.0 * static_cast<double>(oneTurn));
  try {
    readLinuxcncCanon(helix, 1e-4, 100'000);
    FAIL() << "expected the limit";
  } catch (const PathTooLargeToMeasure& error) {
    EXPECT_NE(std::string(error.what()).find("more than 100000 points"), std::string::npos)
        << error.what();
  }
  // Straight moves count too.
  EXPECT_THROW(readLinuxcncCanon("STRAIGHT_FEED(1.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n"
                                 "STRAIGHT_FEED(2.0000, 0.0000, 0.0000, 0.0000, 0.0000, 0.0000)\n",
                                 1e-4, 1),
               PathTooLargeToMeasure);
}

} // namespace
} // namespace cncc::backends
