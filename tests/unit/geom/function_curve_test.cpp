#include "cncc/geom/function_curve.h"
#include "cncc/geom/geometry_error.h"
#include "test_curves.h"

#include <gtest/gtest.h>

#include <cmath>

namespace cncc::geom {
namespace {

using testing::kTwoPi;
using testing::parameterGrid;

double contourRadius(double t) {
  return 18.0 + 4.0 * std::cos(2 * t) * std::cos(6 * t);
}

// The polar contour as parametric x(t), y(t), derivatives left to finite differences.
FunctionCurve contourByCoordinates() {
  return FunctionCurve::fromCoordinates(
      {0.0, kTwoPi}, [](double t) { return contourRadius(t) * std::cos(t); },
      [](double t) { return contourRadius(t) * std::sin(t); });
}

TEST(FunctionCurve, FiniteDifferencesMatchExactDerivatives) {
  FunctionCurve byDifferences = contourByCoordinates();
  PolarCurve exact = testing::polarContour();
  EXPECT_FALSE(byDifferences.hasExactDerivative());
  for (double t : parameterGrid(exact, 500)) {
    CurveDerivatives e = exact.derivatives(t);
    EXPECT_LT((byDifferences.point(t) - e.point).norm(), 1e-14 * e.point.norm());
    // Relative to the magnitudes involved (|C'| ~ 20..60, |C''| ~ 20..1300).
    EXPECT_LT((byDifferences.derivative(t) - e.first).norm(), 1e-8 * e.first.norm()) << t;
    EXPECT_LT((byDifferences.secondDerivative(t) - e.second).norm(), 1e-5 * e.second.norm()) << t;
  }
}

TEST(FunctionCurve, APolarCurvesDerivativeIsItsDerivativesFirstWithoutTheSecond) {
  // r by differences: derivative(t) asks r at 5 parameters (6 near an end,
  // where the stencil is one-sided), derivatives(t) at 5 more.
  int calls = 0;
  PolarCurve spiral({0.0, 40 * M_PI}, [&](double t) {
    ++calls;
    return 1.0 + 2.0 * t;
  });
  for (double t : {0.0, 1e-4, 3.3, 40 * M_PI - 1e-4, 40 * M_PI}) {
    calls = 0;
    Eigen::Vector3d first = spiral.derivative(t);
    int firstCalls = calls;
    EXPECT_LE(firstCalls, 6);
    calls = 0;
    Eigen::Vector3d expected = spiral.derivatives(t).first;
    EXPECT_EQ(calls, firstCalls + 5);
    // The same arithmetic: equal to the bit.
    EXPECT_EQ(first.x(), expected.x()) << t;
    EXPECT_EQ(first.y(), expected.y()) << t;
    EXPECT_EQ(first.z(), 0.0);
  }
}

TEST(FunctionCurve, NeverCallsThePositionOutsideTheDomain) {
  double lowest = INFINITY, highest = -INFINITY;
  FunctionCurve curve({0.0, 1.0}, [&](double t) {
    lowest = std::min(lowest, t);
    highest = std::max(highest, t);
    return Eigen::Vector3d(std::sqrt(t), t * t, 0.0); // sqrt is undefined below 0
  });
  for (double t : {0.0, 1e-4, 0.5, 1.0 - 1e-4, 1.0}) {
    (void)curve.derivative(t);
    (void)curve.secondDerivative(t);
  }
  EXPECT_GE(lowest, 0.0);
  EXPECT_LE(highest, 1.0);
  // One-sided differences at the ends are still accurate for a smooth function.
  EXPECT_NEAR(curve.derivative(1.0).x(), 0.5, 1e-8);
  EXPECT_NEAR(curve.secondDerivative(1.0).x(), -0.25, 1e-5);
  EXPECT_NEAR(curve.derivative(1.0).y(), 2.0, 1e-9);
}

TEST(FunctionCurve, UsesGivenDerivativeCallbacks) {
  FunctionCurve helix(
      {0.0, 10.0}, [](double t) { return Eigen::Vector3d(std::cos(t), std::sin(t), 0.1 * t); },
      [](double t) { return Eigen::Vector3d(-std::sin(t), std::cos(t), 0.1); },
      [](double t) { return Eigen::Vector3d(-std::cos(t), -std::sin(t), 0.0); });
  EXPECT_TRUE(helix.hasExactSecondDerivative());
  // Helix curvature r / (r^2 + c^2) with r = 1, c = 0.1.
  EXPECT_NEAR(helix.curvature(3.0), 1.0 / 1.01, 1e-15);
}

TEST(PolarCurve, ExactDerivativesOfTheSpiral) {
  PolarCurve spiral = testing::archimedeanSpiral();
  // At t = 0: r = 1, r' = 2, so C' = (r', r) = (2, 1) and C'' = (-r, 2 r') = (-1, 4).
  CurveDerivatives d = spiral.derivatives(0.0);
  EXPECT_LT((d.point - Eigen::Vector3d(1, 0, 0)).norm(), 1e-15);
  EXPECT_LT((d.first - Eigen::Vector3d(2, 1, 0)).norm(), 1e-15);
  EXPECT_LT((d.second - Eigen::Vector3d(-1, 4, 0)).norm(), 1e-15);
  // Polar curvature (r^2 + 2 r'^2 - r r'') / (r^2 + r'^2)^(3/2) = 9 / 5^(3/2).
  EXPECT_NEAR(spiral.curvature(0.0), 9.0 / std::pow(5.0, 1.5), 1e-15);
}

TEST(PolarCurve, DifferencesOfRadiusMatchExactDerivatives) {
  PolarCurve exact = testing::polarContour();
  PolarCurve byDifferences({0.0, kTwoPi}, contourRadius);
  for (double t : parameterGrid(exact, 300)) {
    CurveDerivatives e = exact.derivatives(t), d = byDifferences.derivatives(t);
    EXPECT_LT((d.first - e.first).norm(), 1e-8 * e.first.norm()) << t;
    EXPECT_LT((d.second - e.second).norm(), 1e-5 * e.second.norm()) << t;
  }
}

TEST(FunctionCurve, RejectsBadRangesAndMissingFunctions) {
  EXPECT_THROW(FunctionCurve({1.0, 1.0}, [](double) { return Eigen::Vector3d::Zero(); }),
               GeometryError);
  EXPECT_THROW(FunctionCurve({0.0, 1.0}, PointFunction{}), GeometryError);
  EXPECT_THROW(PolarCurve({0.0, NAN}, [](double) { return 1.0; }), GeometryError);
}

} // namespace
} // namespace cncc::geom
