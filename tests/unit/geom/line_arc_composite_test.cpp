#include "cncc/geom/arc_length.h"
#include "cncc/geom/composite_curve.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/geom/line_arc_curves.h"
#include "test_curves.h"

#include <gtest/gtest.h>

#include <numbers>

namespace cncc::geom {
namespace {

using std::numbers::pi;

TEST(LineCurve, IsParametrisedByArcLength) {
  LineCurve line({1, 2, 3}, {4, 6, 3});
  EXPECT_EQ(line.domain().t1, 5.0);
  EXPECT_LT((line.point(2.5) - Eigen::Vector3d(2.5, 4, 3)).norm(), 1e-15);
  EXPECT_NEAR(line.derivative(1.0).norm(), 1.0, 1e-15);
  EXPECT_EQ(line.curvature(1.0), 0.0);
  EXPECT_THROW(LineCurve({1, 1, 1}, {1, 1, 1}), GeometryError);
}

TEST(ArcCurve, PointsCurvatureAndLength) {
  ArcCurve arc({1, 1}, 2.0, 0.0, pi / 2);
  EXPECT_NEAR(arc.length(), pi, 1e-15);
  EXPECT_LT((arc.point(0.0) - Eigen::Vector3d(3, 1, 0)).norm(), 1e-15);
  EXPECT_LT((arc.point(arc.length()) - Eigen::Vector3d(1, 3, 0)).norm(), 1e-15);
  EXPECT_NEAR(arc.curvature(0.7), 0.5, 1e-15);
  EXPECT_NEAR(arc.derivative(0.7).norm(), 1.0, 1e-15);
  EXPECT_NEAR(arcLength(arc), pi, 1e-12);
}

TEST(ArcCurve, FromCentreTakesTheCuttingDirection) {
  Eigen::Vector3d start(1, 0, 0), end(0, 1, 0);
  ArcCurve ccw = ArcCurve::fromCentre(start, end, {0, 0}, ArcDirection::CounterClockwise);
  ArcCurve cw = ArcCurve::fromCentre(start, end, {0, 0}, ArcDirection::Clockwise);
  EXPECT_NEAR(ccw.sweep(), pi / 2, 1e-15);
  EXPECT_NEAR(cw.sweep(), -3 * pi / 2, 1e-15);
  // Clockwise from (1, 0) passes through (0, -1).
  EXPECT_LT((cw.point(cw.length() / 3) - Eigen::Vector3d(0, -1, 0)).norm(), 1e-15);
  ArcCurve full = ArcCurve::fromCentre(start, start, {0, 0}, ArcDirection::Clockwise);
  EXPECT_NEAR(full.sweep(), -2 * pi, 1e-15);
}

TEST(ArcCurve, HelicalArcRisesLinearly) {
  // One turn of radius 2 rising 6 mm: length sqrt((4 pi)^2 + 36), curvature
  // r / (r^2 + c^2) with c = 6 / (2 pi) per radian.
  ArcCurve helix({0, 0}, 2.0, 0.0, 2 * pi, -1.0, 6.0);
  EXPECT_NEAR(helix.length(), std::hypot(4 * pi, 6.0), 1e-14);
  EXPECT_NEAR(helix.point(helix.length()).z(), 5.0, 1e-14);
  double c = 6.0 / (2 * pi);
  EXPECT_NEAR(helix.curvature(1.0), 2.0 / (4.0 + c * c), 1e-14);
  EXPECT_NEAR(arcLength(helix), helix.length(), 1e-11);
}

std::shared_ptr<const Curve> line(Eigen::Vector3d a, Eigen::Vector3d b) {
  return std::make_shared<LineCurve>(a, b);
}

TEST(CompositeCurve, JoinsPiecesOnAGlobalParameter) {
  auto arc = std::make_shared<ArcCurve>(Eigen::Vector2d(1, 1), 1.0, -pi / 2, pi / 2);
  CompositeCurve path({line({0, 0, 0}, {1, 0, 0}), arc, line({2, 1, 0}, {2, 3, 0})});
  EXPECT_EQ(path.pieceCount(), 3u);
  EXPECT_NEAR(path.domain().t1, 1 + pi / 2 + 2, 1e-15);
  EXPECT_LT((path.point(0.5) - Eigen::Vector3d(0.5, 0, 0)).norm(), 1e-15);
  EXPECT_LT((path.point(1 + pi / 2) - Eigen::Vector3d(2, 1, 0)).norm(), 1e-15);
  EXPECT_LT((path.point(path.domain().t1) - Eigen::Vector3d(2, 3, 0)).norm(), 1e-15);
  EXPECT_NEAR(path.curvature(1 + pi / 4), 1.0, 1e-15);
  EXPECT_EQ(path.curvature(1 + pi / 2 + 0.5), 0.0);
  auto [piece, local] = path.locate(1.0);
  EXPECT_EQ(piece, 1u); // a join belongs to the later piece
  EXPECT_EQ(local, 0.0);
  EXPECT_NEAR(arcLength(path), 3 + pi / 2, 1e-12);
  std::vector<double> breaks = path.breakpoints();
  ASSERT_EQ(breaks.size(), 4u);
  EXPECT_NEAR(breaks[2], 1 + pi / 2, 1e-15);
}

TEST(CompositeCurve, RejectsGapsBetweenPieces) {
  EXPECT_THROW(CompositeCurve({line({0, 0, 0}, {1, 0, 0}), line({1, 0.1, 0}, {2, 0, 0})}),
               GeometryError);
  EXPECT_THROW(CompositeCurve({}), GeometryError);
}

TEST(CompositeCurve, NamesAGapTooSmallForSixDecimals) {
  try {
    CompositeCurve({line({0, 0, 0}, {1, 0, 0}), line({1, 5e-7, 0}, {2, 0, 0})});
    FAIL() << "a gap of 5e-7 past the default 1e-9 is refused";
  } catch (const GeometryError& error) {
    EXPECT_STREQ(error.what(), "path piece 1 starts 5e-07 mm away from where piece 0 ends");
  }
  // Within the tolerance asked for, the same pieces join.
  EXPECT_NO_THROW(
      CompositeCurve({line({0, 0, 0}, {1, 0, 0}), line({1, 5e-7, 0}, {2, 0, 0})}, 1e-6));
}

} // namespace
} // namespace cncc::geom
