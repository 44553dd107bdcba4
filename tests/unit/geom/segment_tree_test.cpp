#include "cncc/geom/segment_tree.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <random>
#include <vector>

namespace cncc::geom {
namespace {

// A circle of radius 5 traced twice in 400 chords, climbing 1 per turn:
// in plan view every place is passed twice.
std::vector<Eigen::Vector3d> twoTurns() {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i <= 400; ++i) {
    double angle = 2 * std::numbers::pi * i / 200.0;
    points.emplace_back(5 * std::cos(angle), 5 * std::sin(angle), i / 200.0);
  }
  return points;
}

// The first segment at `from` or later within `radius`, by trying each.
std::optional<std::size_t> firstByEveryone(const SegmentTree& tree, const Eigen::Vector3d& p,
                                           double radius, std::size_t from) {
  for (std::size_t i = from; i < tree.segmentCount(); ++i) {
    const LineSegment& s = tree.segment(i);
    Eigen::Vector3d d = s.end - s.start;
    double f =
        d.squaredNorm() == 0 ? 0 : std::clamp((p - s.start).dot(d) / d.squaredNorm(), 0.0, 1.0);
    if ((p - (s.start + f * d)).norm() <= radius) {
      return i;
    }
  }
  return std::nullopt;
}

TEST(SegmentTree, NearestDistanceFromAHintIsNearestsToTheBit) {
  SegmentTree tree = SegmentTree::throughVertices(twoTurns());
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-7.0, 7.0);
  std::uniform_int_distribution<std::size_t> segment(0, tree.segmentCount() + 5);
  // Random points from random hints (some past the end), and points along a
  // line, each from the last one's segment as a walk along a path asks.
  for (int i = 0; i < 2000; ++i) {
    Eigen::Vector3d p(coordinate(random), coordinate(random), coordinate(random) / 7.0);
    std::size_t hint = segment(random);
    double distance = tree.nearestDistance(p, hint);
    SegmentTree::Nearest expected = tree.nearest(p);
    EXPECT_EQ(distance, expected.distance) << i;
    // The hint left is a nearest segment.
    ASSERT_LT(hint, tree.segmentCount());
    std::size_t again = hint;
    EXPECT_EQ(tree.nearestDistance(p, again), expected.distance) << i;
    EXPECT_EQ(again, hint);
  }
  std::size_t hint = 0;
  for (int i = 0; i <= 1000; ++i) {
    Eigen::Vector3d p(-6.0 + 0.012 * i, 0.3 * std::sin(0.05 * i), 0.5);
    EXPECT_EQ(tree.nearestDistance(p, hint), tree.nearest(p).distance) << i;
  }
}

TEST(SegmentTree, FirstWithinFindsTheFirstPassAtOrAfterAnIndex) {
  SegmentTree tree = SegmentTree::throughVertices(twoTurns());
  // (5, 0, 0.5) is 0.5 from both passes by (5, 0); the chords next to them
  // are farther than 0.51.
  Eigen::Vector3d between(5, 0, 0.5);
  std::optional<SegmentTree::Nearest> first = tree.firstWithin(between, 0.51, 0);
  ASSERT_TRUE(first);
  EXPECT_EQ(first->segment, 0u);
  EXPECT_NEAR(first->distance, 0.5, 1e-3);
  std::optional<SegmentTree::Nearest> second = tree.firstWithin(between, 0.51, 1);
  ASSERT_TRUE(second);
  EXPECT_EQ(second->segment, 199u); // the chord that ends the first turn at (5, 0, 1)
  EXPECT_NEAR(second->distance, 0.5, 1e-3);
  EXPECT_FALSE(tree.firstWithin(between, 0.4, 0));
  EXPECT_FALSE(tree.firstWithin(between, 0.51, 400));
}

TEST(SegmentTree, FirstWithinAgreesWithTryingEverySegment) {
  SegmentTree tree = SegmentTree::throughVertices(twoTurns());
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-6, 6);
  std::uniform_real_distribution<double> height(-0.5, 2.5);
  std::uniform_real_distribution<double> radius(0, 2);
  std::uniform_int_distribution<std::size_t> from(0, 400);
  for (int trial = 0; trial < 2000; ++trial) {
    Eigen::Vector3d p(coordinate(random), coordinate(random), height(random));
    double r = radius(random);
    std::size_t start = from(random);
    std::optional<SegmentTree::Nearest> found = tree.firstWithin(p, r, start);
    std::optional<std::size_t> expected = firstByEveryone(tree, p, r, start);
    ASSERT_EQ(found.has_value(), expected.has_value()) << trial;
    if (found) {
      EXPECT_EQ(found->segment, *expected) << trial;
      EXPECT_LE(found->distance, r);
    }
  }
}

} // namespace
} // namespace cncc::geom
