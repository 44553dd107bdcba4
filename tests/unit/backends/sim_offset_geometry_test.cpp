// The offset geometry of cutter radius compensation: lines and arcs offset
// to the left (positive) or right, and the joins at corners.
#include "cncc/backends/sim_offset_geometry.h"

#include <gtest/gtest.h>

#include <cmath>

#include <optional>
#include <vector>

namespace cncc::backends::sim {
namespace {

PlaneElement line(Vector2 start, Vector2 end) {
  return {false, false, start, end, {}};
}

PlaneElement arc(Vector2 start, Vector2 end, Vector2 centre, bool clockwise) {
  return {true, clockwise, start, end, centre};
}

void expectPoint(Vector2 actual, Vector2 expected) {
  EXPECT_NEAR(actual.x, expected.x, 1e-9);
  EXPECT_NEAR(actual.y, expected.y, 1e-9);
}

std::vector<Vector2> cornerOf(const PlaneElement& before, const PlaneElement& after,
                              double offset) {
  std::optional<std::vector<Vector2>> corner = offsetCorner(before, after, offset);
  if (!corner) {
    ADD_FAILURE() << "no corner";
    return {};
  }
  return *corner;
}

TEST(OffsetGeometry, TangentsOfLinesAndArcs) {
  expectPoint(startTangent(line({0, 0}, {3, 4})), {0.6, 0.8});
  // Counterclockwise around the origin from (10, 0): up; clockwise: down.
  expectPoint(startTangent(arc({10, 0}, {0, 10}, {0, 0}, false)), {0, 1});
  expectPoint(startTangent(arc({10, 0}, {0, -10}, {0, 0}, true)), {0, -1});
  expectPoint(endTangent(arc({10, 0}, {0, 10}, {0, 0}, false)), {-1, 0});
}

TEST(OffsetGeometry, TheLeftOfACounterclockwiseArcIsItsInside) {
  PlaneElement counterclockwise = arc({10, 0}, {0, 10}, {0, 0}, false);
  EXPECT_DOUBLE_EQ(offsetArcRadius(counterclockwise, 2), 8);   // G41
  EXPECT_DOUBLE_EQ(offsetArcRadius(counterclockwise, -2), 12); // G42
  PlaneElement clockwise = arc({10, 0}, {0, -10}, {0, 0}, true);
  EXPECT_DOUBLE_EQ(offsetArcRadius(clockwise, 2), 12);
}

TEST(OffsetGeometry, InnerCornerOfLinesMeetsAtTheIntersection) {
  // Along +X then +Y (a left turn) with the tool on the left: inside.
  std::vector<Vector2> corner = cornerOf(line({0, 0}, {20, 0}), line({20, 0}, {20, 20}), 2);
  ASSERT_EQ(corner.size(), 1u);
  expectPoint(corner[0], {18, 2});
  // An acute inner corner: back along the diagonal.
  corner = cornerOf(line({0, 0}, {20, 0}), line({20, 0}, {0, 20}), 2);
  ASSERT_EQ(corner.size(), 1u);
  // y = 2 meets the line x + y = 20 moved 2 inwards: x + y = 20 - 2 * sqrt(2).
  expectPoint(corner[0], {18 - 2 * std::sqrt(2.0), 2});
}

TEST(OffsetGeometry, RightAngleOuterCornerMeetsAtTheIntersection) {
  // Along +Y then +X (a right turn) with the tool on the left: outside.
  std::vector<Vector2> corner = cornerOf(line({0, 0}, {0, 20}), line({0, 20}, {20, 20}), 2);
  ASSERT_EQ(corner.size(), 1u);
  expectPoint(corner[0], {-2, 22});
}

TEST(OffsetGeometry, SharpOuterCornerGoesRoundTwoPoints) {
  // Along +X then back down-left at 135 degrees, tool on the right (G42).
  PlaneElement before = line({0, 0}, {10, 0});
  PlaneElement after = line({10, 0}, {0, 10});
  // A left turn with the tool on the right: outside, sharper than 90 degrees.
  std::vector<Vector2> corner = cornerOf(before, after, -1);
  ASSERT_EQ(corner.size(), 2u);
  // 1 beyond the corner along the first block's offset (y = -1) ...
  expectPoint(corner[0], {11, -1});
  // ... and 1 before the second block's offset start, along its direction.
  double s = std::sqrt(0.5);
  Vector2 startOfAfter = Vector2{10, 0} + -1.0 * Vector2{-s, -s};
  expectPoint(corner[1], startOfAfter - Vector2{-s, s});
}

TEST(OffsetGeometry, SharpCornerAfterAnArcAddsItsOffsetEnd) {
  // A counterclockwise quarter circle ending at (0, 10) heading -X, then a
  // line straight back along +X: a reversal, outside for a tool on the right.
  PlaneElement before = arc({10, 0}, {0, 10}, {0, 0}, false);
  PlaneElement after = line({0, 10}, {10, 10});
  std::vector<Vector2> corner = cornerOf(before, after, -2);
  ASSERT_EQ(corner.size(), 3u);
  expectPoint(corner[0], {0, 12}); // the offset arc's end, radius 12
  expectPoint(corner[1], {-2, 12});
  expectPoint(corner[2], {-2, 8});
}

TEST(OffsetGeometry, TangentLineIntoArcKeepsTheOffsetPoint) {
  PlaneElement before = line({0, 0}, {10, 0});
  PlaneElement after = arc({10, 0}, {20, 10}, {10, 10}, false);
  std::vector<Vector2> corner = cornerOf(before, after, 2);
  ASSERT_EQ(corner.size(), 1u);
  expectPoint(corner[0], {10, 2});
}

TEST(OffsetGeometry, LineIntoArcInsideMeetsTheOffsetCircle) {
  // Along +Y into a counterclockwise arc around (-10, 10) that starts at
  // (0, 10) heading +Y: tangent. Move the line so it enters at an angle:
  // from (5, 0) to (0, 10), then the same arc; the tool on the left (inside).
  PlaneElement before = line({5, 0}, {0, 10});
  PlaneElement after = arc({0, 10}, {-10, 20}, {-10, 10}, false);
  std::vector<Vector2> corner = cornerOf(before, after, 1);
  ASSERT_EQ(corner.size(), 1u);
  // The point is on the offset circle (radius 9) and on the offset line.
  EXPECT_NEAR(length(corner[0] - Vector2{-10, 10}), 9, 1e-9);
  Vector2 direction = startTangent(before);
  Vector2 offsetStart = Vector2{5, 0} + leftNormal(direction);
  EXPECT_NEAR(cross(direction, corner[0] - offsetStart), 0, 1e-9);
  EXPECT_LT(length(corner[0] - Vector2{0, 10}), 2);
}

TEST(OffsetGeometry, ArcsMeetAtTheNearestIntersection) {
  // A clockwise arc arriving at the origin heading +X, then a clockwise arc
  // leaving at 45 degrees: a left turn, inside for a tool on the left, where
  // both offset circles are larger by the radius.
  PlaneElement before = arc({-10, -10}, {0, 0}, {0, -10}, true);
  PlaneElement after = arc({0, 0}, {20, 0}, {10, -10}, true);
  std::vector<Vector2> corner = cornerOf(before, after, 1);
  ASSERT_EQ(corner.size(), 1u);
  EXPECT_NEAR(length(corner[0] - Vector2{0, -10}), 11, 1e-9);
  EXPECT_NEAR(length(corner[0] - Vector2{10, -10}), 10 * std::sqrt(2.0) + 1, 1e-9);
  EXPECT_LT(length(corner[0]), 2);
  EXPECT_GT(corner[0].y, 0);
}

TEST(OffsetGeometry, CirclesTooSmallForTheToolDoNotMeet) {
  // Inside two small counterclockwise arcs at an inner corner: the offset
  // circles (radii 0.1 and 0.51) are 1 apart.
  PlaneElement before = arc({-1, -1}, {0, 0}, {0, -1}, false);
  PlaneElement after = arc({0, 0}, {2, 0}, {1, -1}, false);
  EXPECT_FALSE(offsetCorner(before, after, 0.9));
  EXPECT_TRUE(offsetCorner(before, after, 0.2));
}

TEST(OffsetGeometry, ArcSweepInTheArcsDirection) {
  EXPECT_NEAR(arcSweep({10, 0}, {0, 10}, {0, 0}, false), 90, 1e-9);
  EXPECT_NEAR(arcSweep({10, 0}, {0, 10}, {0, 0}, true), 270, 1e-9);
  EXPECT_NEAR(arcSweep({10, 0}, {10, 0}, {0, 0}, true), 0, 1e-9);
}

} // namespace
} // namespace cncc::backends::sim
