#include "cncc/geom/segment_tree.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
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

// A 20-turn spiral r = 1 + 2t in `count` chords: a point inside it lies
// within the boxes of many turns outside it.
std::vector<Eigen::Vector3d> spiral(int count) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i <= count; ++i) {
    double t = 40 * std::numbers::pi * i / count;
    points.emplace_back((1 + 2 * t) * std::cos(t), (1 + 2 * t) * std::sin(t), 0.0);
  }
  return points;
}

// The distance from p to segment i, computed as the tree computes it.
double distanceTo(const SegmentTree& tree, const Eigen::Vector3d& p, std::size_t i) {
  LineSegment s = tree.segment(i);
  Eigen::Vector3d d = s.end - s.start;
  double f =
      d.squaredNorm() == 0 ? 0 : std::clamp((p - s.start).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (p - (s.start + f * d)).norm();
}

// The first segment at `from` or later within `radius`, by trying each.
std::optional<std::size_t> firstByEveryone(const SegmentTree& tree, const Eigen::Vector3d& p,
                                           double radius, std::size_t from) {
  for (std::size_t i = from; i < tree.segmentCount(); ++i) {
    if (distanceTo(tree, p, i) <= radius) {
      return i;
    }
  }
  return std::nullopt;
}

// Points about the vertices of `points`, from on them to 10 away.
std::vector<Eigen::Vector3d> pointsAbout(const std::vector<Eigen::Vector3d>& points, int count) {
  std::mt19937 random(11);
  std::uniform_int_distribution<std::size_t> vertex(0, points.size() - 1);
  std::normal_distribution<double> offset(0.0, 1.0);
  std::vector<Eigen::Vector3d> about;
  for (int i = 0; i < count; ++i) {
    double scale = std::pow(10.0, -8 + i % 10);
    Eigen::Vector3d direction(offset(random), offset(random), offset(random));
    about.push_back(points[vertex(random)] + (i % 7 == 0 ? 0.0 : scale) * direction);
  }
  return about;
}

void expectSame(const SegmentTree::Nearest& found, const SegmentTree::Nearest& expected) {
  EXPECT_EQ(found.distance, expected.distance);
  EXPECT_EQ(found.segment, expected.segment);
  EXPECT_EQ(found.fraction, expected.fraction);
  EXPECT_EQ(found.point, expected.point);
}

TEST(SegmentTree, NearestIsTheSmallestDistanceToAnySegment) {
  std::vector<Eigen::Vector3d> points = spiral(4000);
  SegmentTree tree = SegmentTree::throughVertices(points);
  for (const Eigen::Vector3d& p : pointsAbout(points, 400)) {
    double smallest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < tree.segmentCount(); ++i) {
      smallest = std::min(smallest, distanceTo(tree, p, i));
    }
    SegmentTree::Nearest found = tree.nearest(p);
    EXPECT_EQ(found.distance, smallest);
    EXPECT_EQ(distanceTo(tree, p, found.segment), smallest);
  }
}

TEST(SegmentTree, NearestFromAHintIsNearestsToTheBit) {
  std::vector<Eigen::Vector3d> points = spiral(20000);
  SegmentTree tree = SegmentTree::throughVertices(points);
  std::mt19937 random(5);
  std::uniform_int_distribution<std::size_t> segment(0, tree.segmentCount() + 5);
  // From the last point's segment, from anywhere (some past the end), and
  // from the nearest itself; points on a vertex are as near two segments.
  std::size_t last = 0;
  for (const Eigen::Vector3d& p : pointsAbout(points, 5000)) {
    SegmentTree::Nearest expected = tree.nearest(p);
    expectSame(tree.nearest(p, last), expected);
    expectSame(tree.nearest(p, segment(random)), expected);
    expectSame(tree.nearest(p, expected.segment), expected);
    last = expected.segment;
  }
  // A point far from everything, and one not a number.
  Eigen::Vector3d far(1e6, -1e6, 3);
  expectSame(tree.nearest(far, 17), tree.nearest(far));
  Eigen::Vector3d nowhere(std::nan(""), 0, 0);
  EXPECT_EQ(tree.nearest(nowhere, 17).segment, tree.nearest(nowhere).segment);
}

TEST(SegmentTree, SegmentsGivenOneByOneAreSearchedAsVertices) {
  std::vector<Eigen::Vector3d> points = spiral(3000);
  std::vector<LineSegment> segments;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    segments.push_back({points[i], points[i + 1]});
  }
  SegmentTree chain = SegmentTree::throughVertices(points);
  SegmentTree separate(segments);
  ASSERT_EQ(separate.segmentCount(), chain.segmentCount());
  for (const Eigen::Vector3d& p : pointsAbout(points, 1000)) {
    expectSame(separate.nearest(p), chain.nearest(p));
    expectSame(separate.nearest(p, 12), chain.nearest(p));
  }
}

TEST(SegmentTree, KeepsItsVertices) {
  std::vector<Eigen::Vector3d> points = spiral(10);
  SegmentTree tree = SegmentTree::throughVertices(points);
  EXPECT_EQ(tree.points(), points);
  ASSERT_EQ(tree.segmentCount(), 10u);
  EXPECT_EQ(tree.segment(3).start, points[3]);
  EXPECT_EQ(tree.segment(3).end, points[4]);
  // One vertex: one segment that starts and ends there; none: one at the origin.
  Eigen::Vector3d single(1, 2, 3);
  SegmentTree point = SegmentTree::throughVertices({single});
  ASSERT_EQ(point.segmentCount(), 1u);
  EXPECT_EQ(point.nearest({1, 2, 4}).distance, 1.0);
  SegmentTree none = SegmentTree::throughVertices({});
  ASSERT_EQ(none.segmentCount(), 1u);
  EXPECT_EQ(none.nearest({0, 3, 4}).distance, 5.0);
  SegmentTree noSegments(std::vector<LineSegment>{});
  EXPECT_EQ(noSegments.nearest({0, 3, 4}, 0).distance, 5.0);
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
