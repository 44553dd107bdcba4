#include "cncc/geom/geometry_error.h"
#include "cncc/geom/nurbs_curve.h"
#include "test_curves.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace cncc::geom {
namespace {

using ::testing::HasSubstr;
using testing::parameterGrid;

TEST(NurbsCurve, QuarterCircleHasRadiusOneEverywhere) {
  NurbsCurve arc = testing::quarterCircle();
  for (double t : parameterGrid(arc, 1000)) {
    EXPECT_NEAR(arc.point(t).norm(), 1.0, 1e-12) << t;
    EXPECT_NEAR(arc.curvature(t), 1.0, 1e-12) << t;
  }
  EXPECT_LT((arc.point(0.0) - Eigen::Vector3d(1, 0, 0)).norm(), 1e-15);
  EXPECT_LT((arc.point(1.0) - Eigen::Vector3d(0, 1, 0)).norm(), 1e-15);
  EXPECT_TRUE(arc.isRational());
}

TEST(NurbsCurve, FullCircleFromNineControlPointsHasRadiusOne) {
  NurbsCurve circle = testing::unitCircle();
  for (double t : parameterGrid(circle, 4000)) {
    Eigen::Vector3d p = circle.point(t);
    EXPECT_NEAR(p.norm(), 1.0, 1e-12) << t;
    EXPECT_NEAR(circle.curvature(t), 1.0, 1e-12) << t;
    // The tangent is perpendicular to the radius.
    EXPECT_NEAR(circle.derivative(t).normalized().dot(p), 0.0, 1e-12) << t;
  }
  EXPECT_LT((circle.point(0.625) - Eigen::Vector3d(-1, -1, 0).normalized()).norm(), 1e-15);
}

TEST(NurbsCurve, DeBoorPointEqualsBasisFunctionPoint) {
  NurbsCurve curve = testing::sProfile({1, 3, 1, 1, 1, 3, 1});
  for (double t : parameterGrid(curve, 200))
    EXPECT_LT((curve.point(t) - curve.derivatives(t).point).norm(), 1e-12) << t;
}

TEST(NurbsCurve, DerivativesMatchFiniteDifferences) {
  for (const NurbsCurve& curve :
       {testing::sProfile({1, 3, 1, 1, 1, 3, 1}), testing::unitCircle()}) {
    const double h = 1e-5;
    for (double t : parameterGrid(curve, 97)) {
      t = curve.domain().clamp(t);
      if (t - h < curve.domain().t0 || t + h > curve.domain().t1)
        continue;
      CurveDerivatives d = curve.derivatives(t);
      Eigen::Vector3d first = (curve.point(t + h) - curve.point(t - h)) / (2 * h);
      Eigen::Vector3d second =
          (curve.point(t + h) - 2 * curve.point(t) + curve.point(t - h)) / (h * h);
      EXPECT_LT((d.first - first).norm(), 1e-6 * (1 + d.first.norm())) << t;
      EXPECT_LT((d.second - second).norm(), 1e-3 * (1 + d.second.norm())) << t;
      EXPECT_LT((curve.derivative(t) - d.first).norm(), 1e-15 * (1 + d.first.norm()));
      EXPECT_LT((curve.secondDerivative(t) - d.second).norm(), 1e-15 * (1 + d.second.norm()));
    }
  }
}

TEST(NurbsCurve, ClampedBSplineInterpolatesItsEndPoints) {
  NurbsCurve curve =
      NurbsCurve::bspline(3, {{0, 0, 0}, {1, 2, 0}, {3, 2, 1}, {4, 0, 0}, {6, 1, 0}});
  EXPECT_LT((curve.point(0.0) - Eigen::Vector3d(0, 0, 0)).norm(), 1e-15);
  EXPECT_LT((curve.point(1.0) - Eigen::Vector3d(6, 1, 0)).norm(), 1e-15);
  // End tangent of a clamped spline: p / (u_{p+1} - u_1) (P1 - P0).
  EXPECT_LT((curve.derivative(0.0) - 3.0 / 0.5 * Eigen::Vector3d(1, 2, 0)).norm(), 1e-12);
  EXPECT_FALSE(curve.isRational());
}

TEST(NurbsCurve, BezierMatchesBernsteinFormula) {
  std::vector<Eigen::Vector3d> p{{0, 0, 0}, {1, 3, 0}, {4, 3, 2}, {5, 0, 1}};
  NurbsCurve bezier = NurbsCurve::bezier(p);
  for (double t : {0.0, 0.2, 0.5, 0.9, 1.0}) {
    double s = 1 - t;
    Eigen::Vector3d expected =
        s * s * s * p[0] + 3 * t * s * s * p[1] + 3 * t * t * s * p[2] + t * t * t * p[3];
    EXPECT_LT((bezier.point(t) - expected).norm(), 1e-14) << t;
  }
}

TEST(NurbsCurve, RationalBezierQuarterCircle) {
  NurbsCurve arc = NurbsCurve::bezier({{1, 0, 0}, {1, 1, 0}, {0, 1, 0}}, {1, std::sqrt(0.5), 1});
  for (double t : parameterGrid(arc, 100))
    EXPECT_NEAR(arc.point(t).norm(), 1.0, 1e-14);
}

TEST(NurbsCurve, EqualWeightsAreNotRational) {
  NurbsCurve scaled(KnotVector::clampedUniform(2, 4), {{0, 0, 0}, {1, 1, 0}, {2, 0, 0}, {3, 1, 0}},
                    {2, 2, 2, 2});
  NurbsCurve plain = NurbsCurve::bspline(2, {{0, 0, 0}, {1, 1, 0}, {2, 0, 0}, {3, 1, 0}});
  EXPECT_FALSE(scaled.isRational());
  for (double t : {0.1, 0.4, 0.8})
    EXPECT_LT((scaled.point(t) - plain.point(t)).norm(), 1e-15);
}

TEST(NurbsCurve, ValidationNamesTheProblem) {
  KnotVector knots = KnotVector::clampedUniform(2, 4);
  std::vector<Eigen::Vector3d> four{{0, 0, 0}, {1, 1, 0}, {2, 0, 0}, {3, 1, 0}};
  EXPECT_THAT(NurbsCurve::findProblem(knots.values(), 2, {{0, 0, 0}}, {1}).value_or(""),
              HasSubstr("need 4 control points, got 1"));
  EXPECT_THAT(NurbsCurve::findProblem(knots.values(), 2, four, {1, 1}).value_or(""),
              HasSubstr("as many weights"));
  EXPECT_THAT(NurbsCurve::findProblem(knots.values(), 2, four, {1, 0, 1, 1}).value_or(""),
              HasSubstr("weight 1 must be positive"));
  std::vector<Eigen::Vector3d> bad = four;
  bad[2].y() = INFINITY;
  EXPECT_THAT(NurbsCurve::findProblem(knots.values(), 2, bad, {1, 1, 1, 1}).value_or(""),
              HasSubstr("control point 2"));
  EXPECT_FALSE(NurbsCurve::findProblem(knots.values(), 2, four, {1, 1, 1, 1}).has_value());
  EXPECT_THROW(NurbsCurve(knots, four, {1, -1, 1, 1}), GeometryError);
  EXPECT_THROW(NurbsCurve::bezier({{0, 0, 0}}), GeometryError);
}

TEST(NurbsCurve, ParametersOutsideTheDomainAreClamped) {
  NurbsCurve arc = testing::quarterCircle();
  EXPECT_LT((arc.point(-1.0) - arc.point(0.0)).norm(), 1e-15);
  EXPECT_LT((arc.point(2.0) - arc.point(1.0)).norm(), 1e-15);
}

TEST(NurbsCurve, BreakpointsAreTheDistinctKnots) {
  EXPECT_EQ(testing::unitCircle().breakpoints(), (std::vector<double>{0, 0.25, 0.5, 0.75, 1}));
}

} // namespace
} // namespace cncc::geom
