#include "cncc/geom/curvature.h"
#include "cncc/geom/line_arc_curves.h"
#include "test_curves.h"

#include <gtest/gtest.h>

#include <numbers>

namespace cncc::geom {
namespace {

TEST(MinimumRadius, OfAnEllipseIsAtTheEndOfTheMajorAxis) {
  // x = a cos t, y = b sin t: smallest radius b^2 / a at t = 0 and pi; a window that
  // puts the peak between samples, not at an end.
  const double a = 5.0, b = 2.0;
  FunctionCurve ellipse(
      {0.3, 4.0}, [=](double t) { return Eigen::Vector3d(a * std::cos(t), b * std::sin(t), 0); },
      [=](double t) { return Eigen::Vector3d(-a * std::sin(t), b * std::cos(t), 0); },
      [=](double t) { return Eigen::Vector3d(-a * std::cos(t), -b * std::sin(t), 0); });
  CurvatureExtreme m = minimumRadiusOfCurvature(ellipse);
  EXPECT_NEAR(m.radius, b * b / a, 1e-12);
  EXPECT_NEAR(m.parameter, std::numbers::pi, 1e-6);
}

TEST(MinimumRadius, OfTheSpiralIsAtItsStart) {
  CurvatureExtreme m = minimumRadiusOfCurvature(testing::archimedeanSpiral());
  EXPECT_NEAR(m.radius, std::pow(5.0, 1.5) / 9.0, 1e-12);
  EXPECT_EQ(m.parameter, 0.0);
}

TEST(MinimumRadius, OfCirclesAndLines) {
  EXPECT_NEAR(minimumRadiusOfCurvature(testing::unitCircle()).radius, 1.0, 1e-12);
  EXPECT_NEAR(minimumRadiusOfCurvature(ArcCurve({0, 0}, 3.0, 0, 1)).radius, 3.0, 1e-12);
  CurvatureExtreme straight = minimumRadiusOfCurvature(LineCurve({0, 0, 0}, {1, 1, 0}));
  EXPECT_EQ(straight.curvature, 0.0);
  EXPECT_TRUE(std::isinf(straight.radius));
}

TEST(MinimumRadius, FindsANarrowPeakBetweenSamples) {
  // y = 1e-3 / (1e-6 + (x - 0.4123)^2) has a curvature spike about 1e-3 wide; the
  // largest curvature 2 / y''... is found by refinement: at the peak y' = 0 and
  // k = |y''| = 2e-3 / 1e-12 = 2e9.
  const double c = 0.4123, w = 1e-6;
  FunctionCurve bump(
      {0.0, 1.0}, [=](double x) { return Eigen::Vector3d(x, 1e-3 / (w + (x - c) * (x - c)), 0); },
      [=](double x) {
        double q = w + (x - c) * (x - c);
        return Eigen::Vector3d(1, -2e-3 * (x - c) / (q * q), 0);
      },
      [=](double x) {
        double q = w + (x - c) * (x - c);
        return Eigen::Vector3d(0, -2e-3 / (q * q) + 8e-3 * (x - c) * (x - c) / (q * q * q), 0);
      });
  CurvatureExtreme m = minimumRadiusOfCurvature(bump);
  EXPECT_NEAR(m.parameter, c, 1e-9);
  EXPECT_NEAR(m.curvature, 2e9, 2e9 * 1e-8);
}

} // namespace
} // namespace cncc::geom
