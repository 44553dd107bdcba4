#include "cncc/geom/arc_length.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/geom/line_arc_curves.h"
#include "test_curves.h"

#include <gtest/gtest.h>

#include <numbers>

namespace cncc::geom {
namespace {

using std::numbers::pi;

TEST(ArcLength, OfNurbsCircles) {
  EXPECT_NEAR(arcLength(testing::quarterCircle()), pi / 2, 1e-12);
  EXPECT_NEAR(arcLength(testing::unitCircle()), 2 * pi, 1e-12);
  EXPECT_NEAR(arcLength(testing::unitCircle(), 0.25, 0.5), pi / 2, 1e-12);
}

TEST(ArcLength, OfTheSpiralInClosedForm) {
  // r = a + b t: s = [ (r sqrt(r^2 + b^2) + b^2 asinh(r / b)) / (2 b) ] from r(0) to r(2 pi).
  auto primitive = [](double r) {
    const double b = 2.0;
    return (r * std::sqrt(r * r + b * b) + b * b * std::asinh(r / b)) / (2 * b);
  };
  double exact = primitive(1 + 4 * pi) - primitive(1.0);
  EXPECT_NEAR(arcLength(testing::archimedeanSpiral()), exact, 1e-10);
  EXPECT_NEAR(arcLength(testing::archimedeanSpiral(), 1e-6), exact, 1e-6);
}

TEST(ArcLength, IsSignedByDirection) {
  NurbsCurve circle = testing::unitCircle();
  EXPECT_NEAR(arcLength(circle, 0.5, 0.25), -pi / 2, 1e-12);
  EXPECT_EQ(arcLength(circle, 0.3, 0.3), 0.0);
  EXPECT_THROW(arcLength(circle, 0.0), GeometryError);
}

TEST(ArcLengthTable, ParameterAtInvertsLengthAt) {
  NurbsCurve curve = testing::sProfile({1, 1, 1, 1, 1, 3, 1});
  ArcLengthTable table(curve);
  EXPECT_NEAR(table.totalLength(), arcLength(curve), 1e-10);
  for (double t : testing::parameterGrid(curve, 37)) {
    double s = table.lengthAt(t);
    EXPECT_NEAR(table.parameterAt(s), t, 1e-12) << t;
    EXPECT_NEAR(s, arcLength(curve, 0.0, t), 1e-9);
  }
  EXPECT_EQ(table.parameterAt(-1.0), 0.0);
  EXPECT_EQ(table.parameterAt(1e9), 1.0);
}

TEST(ArcLengthTable, OnTheCircleTheParameterFollowsTheAngle) {
  NurbsCurve circle = testing::unitCircle();
  ArcLengthTable table(circle);
  for (double angle : {0.1, 1.0, 2.5, 4.0, 6.2}) {
    Eigen::Vector3d p = circle.point(table.parameterAt(angle));
    EXPECT_LT((p - Eigen::Vector3d(std::cos(angle), std::sin(angle), 0)).norm(), 1e-10);
  }
}

TEST(EqualArcLength, ParametersAreEquallySpacedInLength) {
  PolarCurve contour = testing::polarContour();
  std::vector<double> t = equalArcLengthParameters(contour, 25);
  ASSERT_EQ(t.size(), 25u);
  EXPECT_EQ(t.front(), 0.0);
  EXPECT_EQ(t.back(), testing::kTwoPi);
  double step = arcLength(contour) / 24;
  for (std::size_t i = 0; i + 1 < t.size(); ++i)
    EXPECT_NEAR(arcLength(contour, t[i], t[i + 1]), step, 1e-9);
}

} // namespace
} // namespace cncc::geom
