// Exact tool-radius offsets (offset_curve.h) and their clearance checks
// (offset_clearance.h) against closed forms and reference case 3.
#include "cncc/geom/composite_curve.h"
#include "cncc/geom/line_arc_curves.h"
#include "cncc/geom/offset_clearance.h"
#include "cncc/geom/offset_curve.h"

#include "test_curves.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

namespace cncc::geom {
namespace {

using testing::kTwoPi;
constexpr double kPi = std::numbers::pi;

std::shared_ptr<const Curve> shared(const NurbsCurve& curve) {
  return std::make_shared<NurbsCurve>(curve);
}

TEST(OffsetCurve, CircleAsNurbsOffsetsToConcentricCircles) {
  auto circle = shared(testing::unitCircle()); // counter-clockwise: left is inside
  OffsetCurve inside(circle, 0.25);
  OffsetCurve outside(circle, -0.5);
  for (double t : testing::parameterGrid(inside, 200)) {
    EXPECT_NEAR(inside.point(t).head<2>().norm(), 0.75, 1e-12) << t;
    EXPECT_NEAR(outside.point(t).head<2>().norm(), 1.5, 1e-12) << t;
    // The offset's tangent is the base's, scaled by 1 - d k (k = 1 here).
    Eigen::Vector3d base = circle->derivative(t);
    EXPECT_NEAR((inside.derivative(t) - 0.75 * base).norm(), 0.0, 1e-12) << t;
    EXPECT_NEAR((outside.derivative(t) - 1.5 * base).norm(), 0.0, 1e-12) << t;
  }
}

TEST(OffsetCurve, EllipseMatchesTheClosedForm) {
  const double a = 20, b = 12, d = 1.5;
  auto ellipse = std::make_shared<FunctionCurve>(FunctionCurve::fromCoordinates(
      {0, kTwoPi}, [=](double t) { return a * std::cos(t); },
      [=](double t) { return b * std::sin(t); }));
  OffsetCurve offset(ellipse, d);
  auto exact = [=](double t) {
    double w = std::hypot(a * std::sin(t), b * std::cos(t));
    return Eigen::Vector3d(a * std::cos(t) - d * b * std::cos(t) / w,
                           b * std::sin(t) - d * a * std::sin(t) / w, 0.0);
  };
  for (double t : testing::parameterGrid(offset, 97)) {
    EXPECT_NEAR((offset.point(t) - exact(t)).norm(), 0.0, 1e-8) << t;
    // The derivative against central differences of the closed form.
    double h = 1e-5;
    if (t > h && t < kTwoPi - h) {
      Eigen::Vector3d difference = (exact(t + h) - exact(t - h)) / (2 * h);
      EXPECT_NEAR((offset.derivative(t) - difference).norm(), 0.0, 1e-5) << t;
      Eigen::Vector3d second = (exact(t + h) - 2 * exact(t) + exact(t - h)) / (h * h);
      EXPECT_NEAR((offset.secondDerivative(t) - second).norm(), 0.0, 2e-3) << t;
    }
  }
}

TEST(OffsetCurve, ArcStaysAnArcAndALineALine) {
  auto ccw = std::make_shared<ArcCurve>(Eigen::Vector2d(1, 2), 10.0, 0.0, kPi);
  auto cw = std::make_shared<ArcCurve>(Eigen::Vector2d(1, 2), 10.0, 0.0, -kPi);
  auto left = std::dynamic_pointer_cast<const ArcCurve>(offsetOfPieces({ccw}, 2.0));
  auto right = std::dynamic_pointer_cast<const ArcCurve>(offsetOfPieces({cw}, 2.0));
  ASSERT_TRUE(left && right);
  EXPECT_DOUBLE_EQ(left->radius(), 8.0);
  EXPECT_DOUBLE_EQ(right->radius(), 12.0);
  EXPECT_DOUBLE_EQ(left->sweep(), kPi);
  auto line = std::make_shared<LineCurve>(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(10, 0, 0));
  auto moved = std::dynamic_pointer_cast<const LineCurve>(offsetOfPieces({line}, -3.0));
  ASSERT_TRUE(moved);
  EXPECT_NEAR((moved->point(0) - Eigen::Vector3d(0, -3, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((moved->point(10) - Eigen::Vector3d(10, -3, 0)).norm(), 0.0, 1e-15);
  // The tool inside an arc no larger than itself cannot follow it.
  EXPECT_THROW(offsetOfPieces({ccw}, 10.0), OffsetError);
}

// A square counter-clockwise: outside (right) its corners are convex and get
// quarter circles of the tool's radius, the closing corner included; inside
// they are concave and the sides are cut back to where their offsets cross.
TEST(OffsetCurve, ConvexCornersGetArcsConcaveOnesAreTrimmed) {
  std::vector<Eigen::Vector3d> corners = {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}};
  std::vector<std::shared_ptr<const Curve>> sides;
  for (std::size_t i = 0; i < 4; ++i) {
    sides.push_back(std::make_shared<LineCurve>(corners[i], corners[(i + 1) % 4]));
  }
  auto outside = std::dynamic_pointer_cast<const CompositeCurve>(offsetOfPieces(sides, -2.0));
  ASSERT_TRUE(outside);
  EXPECT_EQ(outside->pieceCount(), 8u); // four sides, four corners
  auto arc = dynamic_cast<const ArcCurve*>(&outside->piece(1));
  ASSERT_NE(arc, nullptr);
  EXPECT_DOUBLE_EQ(arc->radius(), 2.0);
  EXPECT_NEAR(arc->sweep(), kPi / 2, 1e-12);
  EXPECT_NEAR((arc->point(arc->domain().t1) - Eigen::Vector3d(12, 0, 0)).norm(), 0.0, 1e-12);
  ParameterRange whole = outside->domain();
  EXPECT_NEAR((outside->point(whole.t0) - outside->point(whole.t1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(whole.length(), 40 + 2 * kPi * 2, 1e-9);

  auto inside = std::dynamic_pointer_cast<const CompositeCurve>(offsetOfPieces(sides, 2.0));
  ASSERT_TRUE(inside);
  ASSERT_EQ(inside->pieceCount(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    const Curve& side = inside->piece(i);
    ASSERT_NE(dynamic_cast<const LineCurve*>(&side), nullptr);
    EXPECT_NEAR(side.domain().length(), 6.0, 1e-12) << i;
  }
  EXPECT_NEAR((inside->point(0) - Eigen::Vector3d(2, 2, 0)).norm(), 0.0, 1e-12);
  EXPECT_NEAR((inside->point(inside->domain().t1) - Eigen::Vector3d(2, 2, 0)).norm(), 0.0, 1e-12);
}

// Each part of the offset says which drawn piece it lies beside; a convex
// corner's arc follows the piece ending there, the arc where a closed path
// closes comes last, and a concave corner adds no part.
TEST(OffsetCurve, EachPartNamesThePieceItLiesBeside) {
  using Origins = std::vector<std::optional<std::size_t>>;
  std::vector<Eigen::Vector3d> corners = {{0, 0, 0}, {10, 0, 0}, {10, 10, 0}, {0, 10, 0}};
  std::vector<std::shared_ptr<const Curve>> sides;
  for (std::size_t i = 0; i < 4; ++i) {
    sides.push_back(std::make_shared<LineCurve>(corners[i], corners[(i + 1) % 4]));
  }
  PiecesOffset outside = offsetOfPiecesWithOrigins(sides, -2.0);
  EXPECT_EQ(outside.partOrigins,
            (Origins{0, std::nullopt, 1, std::nullopt, 2, std::nullopt, 3, std::nullopt}));
  ASSERT_EQ(piecesOf(*outside.curve).size(), outside.partOrigins.size());
  EXPECT_NE(dynamic_cast<const ArcCurve*>(piecesOf(*outside.curve)[7]), nullptr);
  EXPECT_EQ(offsetOfPiecesWithOrigins(sides, 2.0).partOrigins, (Origins{0, 1, 2, 3}));

  // Open: a right turn then a left turn, the tool on the left (convex at the
  // first corner, concave at the second); one piece alone is its own part.
  std::vector<std::shared_ptr<const Curve>> steps = {
      std::make_shared<LineCurve>(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(10, 0, 0)),
      std::make_shared<LineCurve>(Eigen::Vector3d(10, 0, 0), Eigen::Vector3d(10, -10, 0)),
      std::make_shared<LineCurve>(Eigen::Vector3d(10, -10, 0), Eigen::Vector3d(20, -10, 0))};
  PiecesOffset open = offsetOfPiecesWithOrigins(steps, 1.0);
  EXPECT_EQ(open.partOrigins, (Origins{0, std::nullopt, 1, 2}));
  EXPECT_EQ(piecesOf(*open.curve).size(), 4u);
  EXPECT_EQ(offsetOfPiecesWithOrigins({steps[0]}, 1.0).partOrigins, (Origins{0}));
}

// A concave corner next to a piece shorter than the tool's radius: the
// offsets do not cross within the pieces.
TEST(OffsetCurve, ConcaveCornerOfAShortPieceIsRefused) {
  std::vector<std::shared_ptr<const Curve>> pieces = {
      std::make_shared<LineCurve>(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(10, 0, 0)),
      std::make_shared<LineCurve>(Eigen::Vector3d(10, 0, 0), Eigen::Vector3d(10, 1, 0))};
  try {
    offsetOfPieces(pieces, 2.0);
    FAIL() << "the offsets were joined";
  } catch (const OffsetError& error) {
    EXPECT_NEAR((error.place - Eigen::Vector3d(10, 0, 0)).norm(), 0.0, 1e-12);
    EXPECT_EQ(error.radius, 0.0);
  }
}

// A line into an arc turning to the tool's side: the trimmed offsets stay a line
// and an arc, and meet.
TEST(OffsetCurve, ConcaveCornerOfALineAndAnArcIsTrimmedExactly) {
  // A line from the origin into an arc counter-clockwise about (10, 5) from
  // below its centre: a left turn where they join.
  auto arc = std::make_shared<ArcCurve>(Eigen::Vector2d(10, 5), 5.0, -kPi / 2 + 0.5, 2.0);
  auto start =
      Eigen::Vector3d(10 + 5 * std::cos(-kPi / 2 + 0.5), 5 + 5 * std::sin(-kPi / 2 + 0.5), 0);
  auto lead = std::make_shared<LineCurve>(Eigen::Vector3d(0, 0, 0), start);
  auto offset = std::dynamic_pointer_cast<const CompositeCurve>(offsetOfPieces({lead, arc}, 1.0));
  ASSERT_TRUE(offset);
  ASSERT_EQ(offset->pieceCount(), 2u);
  const auto* trimmedLine = dynamic_cast<const LineCurve*>(&offset->piece(0));
  const auto* trimmedArc = dynamic_cast<const ArcCurve*>(&offset->piece(1));
  ASSERT_TRUE(trimmedLine != nullptr && trimmedArc != nullptr);
  EXPECT_DOUBLE_EQ(trimmedArc->radius(), 4.0);
  Eigen::Vector3d meeting = trimmedLine->point(trimmedLine->domain().t1);
  EXPECT_NEAR((meeting - trimmedArc->point(0)).norm(), 0.0, 1e-10);
  EXPECT_NEAR((meeting.head<2>() - Eigen::Vector2d(10, 5)).norm(), 4.0, 1e-10);
}

// Pieces half a micrometre apart that turn by 3e-8 rad where they meet (as a
// path's pieces may, within its join tolerance): on either side the offsets
// join as the pieces do, without a corner arc or a crossing to search for.
TEST(OffsetCurve, TangentPiecesWithASmallGapJoinAsTheyAre) {
  std::vector<std::shared_ptr<const Curve>> pieces = {
      std::make_shared<LineCurve>(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(10, 0, 0)),
      std::make_shared<LineCurve>(Eigen::Vector3d(10, 5e-7, 0), Eigen::Vector3d(20, 8e-7, 0))};
  for (double distance : {3.0, -3.0}) {
    auto offset = std::dynamic_pointer_cast<const CompositeCurve>(offsetOfPieces(pieces, distance));
    ASSERT_TRUE(offset);
    ASSERT_EQ(offset->pieceCount(), 2u) << "distance " << distance;
    EXPECT_NEAR(offset->point(offset->domain().t1).y(), distance + 8e-7, 1e-9);
  }
}

// REFERENCE-CASES.md case 3 (counter-clockwise): outside (right) its tightest
// concave radius is 2.3314 mm, its tightest convex 2.659 mm at t = 0; inside
// the two swap.
TEST(OffsetClearance, PolarContourOfReferenceCase3) {
  PolarCurve contour = testing::polarContour();
  OffsetClearance outside = offsetClearance(contour, -2.0);
  EXPECT_NEAR(outside.concave.radius, 2.3314, 5e-5);
  EXPECT_NEAR(outside.convex.radius, 2.659, 5e-4);
  // t = 0 and t = 2 pi are the same place.
  EXPECT_NEAR(std::sin(outside.convex.t), 0.0, 1e-6);
  EXPECT_NEAR((outside.convex.point - Eigen::Vector3d(22, 0, 0)).norm(), 0.0, 1e-6);
  OffsetClearance inside = offsetClearance(contour, 2.0);
  EXPECT_NEAR(inside.concave.radius, outside.convex.radius, 1e-9);
  EXPECT_NEAR(inside.convex.radius, outside.concave.radius, 1e-9);
  EXPECT_NEAR(outside.concave.radius, 1.0 / contour.curvature(outside.concave.t), 1e-9);
}

TEST(OffsetClearance, CircleBendsOneWayOnly) {
  NurbsCurve circle = testing::unitCircle();
  OffsetClearance inside = offsetClearance(circle, 0.5);
  EXPECT_NEAR(inside.concave.radius, 1.0, 1e-9);
  EXPECT_TRUE(std::isinf(inside.convex.radius));
}

// r = 10 + 6 cos 2t is a peanut whose waist is 8 mm across: a tool of radius
// 4.5 inside it meets itself there, one of radius 1 does not.
TEST(OffsetSelfCrossing, NarrowWaistIsFound) {
  auto peanut = std::make_shared<PolarCurve>(ParameterRange{0, kTwoPi},
                                             [](double t) { return 10 + 6 * std::cos(2 * t); });
  EXPECT_FALSE(offsetSelfCrossing(OffsetCurve(peanut, 1.0)).has_value());
  std::optional<Eigen::Vector3d> crossing = offsetSelfCrossing(OffsetCurve(peanut, 4.5));
  ASSERT_TRUE(crossing.has_value());
  // The offsets of the waist's two sides meet on the x axis (its symmetry), near it.
  EXPECT_NEAR(crossing->y(), 0.0, 0.05);
  EXPECT_LT(std::fabs(crossing->x()), 4.0);
  // Outside, the waist bends with a radius of 0.8 mm: 0.5 follows it, 3 loops.
  EXPECT_FALSE(offsetSelfCrossing(OffsetCurve(peanut, -0.5)).has_value());
  EXPECT_TRUE(offsetSelfCrossing(OffsetCurve(peanut, -3.0)).has_value());
}

// Two windings of a peanut: its offset runs over itself, every chord of the
// second lap near one of the first. The grid finds a crossing all the same,
// and one on the first lap's waist (the first along the curve).
TEST(OffsetSelfCrossing, FirstCrossingAlongTheCurve) {
  auto peanut = std::make_shared<PolarCurve>(ParameterRange{0, kTwoPi},
                                             [](double t) { return 10 + 6 * std::cos(2 * t); });
  std::optional<Eigen::Vector3d> crossing = offsetSelfCrossing(OffsetCurve(peanut, 4.5), 4096);
  ASSERT_TRUE(crossing.has_value());
  // Along the curve (counter-clockwise from t = 0) the waist at +x comes first.
  EXPECT_GT(crossing->x(), 0.0);
  EXPECT_NEAR(crossing->y(), 0.0, 0.01);
}

// An open path whose last line ends on its first (a rectangle drawn from
// (-5, 0), closed at (0, 0)): beside it on the outside no offset crosses
// another, but the tool at the last line's end stands on the first line.
TEST(OffsetClearanceViolation, OpenEndRunIntoTheStart) {
  std::vector<std::shared_ptr<const Curve>> pieces{
      std::make_shared<LineCurve>(Eigen::Vector3d(-5, 0, 0), Eigen::Vector3d(40, 0, 0)),
      std::make_shared<LineCurve>(Eigen::Vector3d(40, 0, 0), Eigen::Vector3d(40, 20, 0)),
      std::make_shared<LineCurve>(Eigen::Vector3d(40, 20, 0), Eigen::Vector3d(0, 20, 0)),
      std::make_shared<LineCurve>(Eigen::Vector3d(0, 20, 0), Eigen::Vector3d(0, 0, 0))};
  CompositeCurve drawn(pieces);
  std::shared_ptr<const Curve> outside = offsetOfPieces(pieces, -2.0);
  EXPECT_FALSE(offsetSelfCrossing(*outside).has_value());
  std::optional<ClearanceViolation> violation =
      offsetClearanceViolation(*outside, drawn, 2.0, 1e-3);
  ASSERT_TRUE(violation.has_value());
  EXPECT_NEAR((violation->centre - Eigen::Vector3d(-2, 0, 0)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(violation->distance, 0.0, 1e-9);
  // The same path ending at (-5, 20) and on to (-5, 0) is a closed rectangle:
  // the tool runs round it at its radius everywhere.
  std::vector<std::shared_ptr<const Curve>> closed{
      std::make_shared<LineCurve>(Eigen::Vector3d(-5, 0, 0), Eigen::Vector3d(40, 0, 0)),
      std::make_shared<LineCurve>(Eigen::Vector3d(40, 0, 0), Eigen::Vector3d(40, 20, 0)),
      std::make_shared<LineCurve>(Eigen::Vector3d(40, 20, 0), Eigen::Vector3d(-5, 20, 0)),
      std::make_shared<LineCurve>(Eigen::Vector3d(-5, 20, 0), Eigen::Vector3d(-5, 0, 0))};
  EXPECT_FALSE(
      offsetClearanceViolation(*offsetOfPieces(closed, -2.0), CompositeCurve(closed), 2.0, 1e-3)
          .has_value());
}

// A polar curve with its tool outside: as many centres as the check takes,
// each a tree query, none nearer than the radius.
TEST(OffsetClearanceViolation, SmoothContourKeepsItsDistance) {
  PolarCurve contour = testing::polarContour();
  auto base = std::make_shared<PolarCurve>(contour);
  EXPECT_FALSE(offsetClearanceViolation(OffsetCurve(base, -2.0), contour, 2.0, 1e-3).has_value());
}

} // namespace
} // namespace cncc::geom
