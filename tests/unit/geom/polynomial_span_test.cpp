#include "cncc/geom/geometry_error.h"
#include "cncc/geom/polynomial_span.h"
#include "test_curves.h"

#include <gtest/gtest.h>

namespace cncc::geom {
namespace {

using testing::parameterGrid;

// Checks every span against de Boor at many parameters (absolute tolerance, mm).
void expectSpansMatchDeBoor(const NurbsCurve& curve, const std::vector<PolynomialSpan>& spans,
                            double tolerance) {
  for (const PolynomialSpan& span : spans) {
    for (int i = 0; i <= 100; ++i) {
      double u = i / 100.0;
      double t = span.t0 + u * (span.t1 - span.t0);
      EXPECT_LT((span.pointAt(u) - curve.point(t)).norm(), tolerance) << t;
    }
  }
}

TEST(PolynomialSpan, OneSpanPerNonEmptyKnotSpan) {
  std::vector<PolynomialSpan> spans = toPowerBasis(testing::unitCircle());
  ASSERT_EQ(spans.size(), 4u);
  EXPECT_EQ(spans[1].t0, 0.25);
  EXPECT_EQ(spans[1].t1, 0.5);
  EXPECT_EQ(spans[1].degree(), 2);
  EXPECT_TRUE(spans[1].isRational());
}

TEST(PolynomialSpan, PowerBasisEvaluatesLikeDeBoor) {
  NurbsCurve sProfile = testing::sProfile();
  NurbsCurve weighted = testing::sProfile({1, 1, 1, 1, 1, 3, 1});
  NurbsCurve circle = testing::unitCircle();
  expectSpansMatchDeBoor(sProfile, toPowerBasis(sProfile), 1e-12);
  expectSpansMatchDeBoor(weighted, toPowerBasis(weighted), 1e-12);
  expectSpansMatchDeBoor(circle, toPowerBasis(circle), 1e-14);
  for (const PolynomialSpan& span : toPowerBasis(circle))
    for (int i = 0; i <= 50; ++i)
      EXPECT_NEAR(span.pointAt(i / 50.0).norm(), 1.0, 1e-12);
}

TEST(PolynomialSpan, PolynomialSpansHaveUnitWeight) {
  for (const PolynomialSpan& span : toPowerBasis(testing::sProfile())) {
    EXPECT_FALSE(span.isRational());
    EXPECT_EQ(span.coefficients[0].w(), 1.0);
    for (std::size_t k = 1; k < span.coefficients.size(); ++k)
      EXPECT_EQ(span.coefficients[k].w(), 0.0);
  }
}

TEST(PolynomialSpan, CoefficientsAreInTheNormalisedParameter) {
  // The quarter circle's only span: W(u) = 1 + (sqrt2 - 2) u + (2 - sqrt2) u^2 and
  // X(u) = 1 + (sqrt2 - 2) u + (1 - sqrt2) u^2 for u in [0, 1].
  PolynomialSpan span = toPowerBasis(testing::quarterCircle()).front();
  double r = std::sqrt(2.0);
  EXPECT_NEAR(span.coefficients[0].w(), 1.0, 1e-15);
  EXPECT_NEAR(span.coefficients[1].w(), r - 2, 1e-15);
  EXPECT_NEAR(span.coefficients[2].w(), 2 - r, 1e-15);
  EXPECT_NEAR(span.coefficients[1].x(), r - 2, 1e-15);
  EXPECT_NEAR(span.coefficients[2].x(), 1 - r, 1e-15);
}

TEST(PolynomialSpan, BezierSpansEvaluateLikeDeBoor) {
  NurbsCurve curve = testing::sProfile({1, 3, 1, 1, 1, 3, 1});
  for (const BezierSpan& span : toBezierSpans(curve))
    for (int i = 0; i <= 100; ++i) {
      double u = i / 100.0;
      double t = span.t0 + u * (span.t1 - span.t0);
      EXPECT_LT((span.pointAt(u) - curve.point(t)).norm(), 1e-12) << t;
    }
}

TEST(PolynomialSpan, BezierOfTheCircleSpanIsItsControlPolygon) {
  // A Bezier curve's own span in Bezier form returns its homogeneous control points.
  BezierSpan bezier = toBezierSpans(testing::quarterCircle()).front();
  double w = std::sqrt(0.5);
  ASSERT_EQ(bezier.controlPoints.size(), 3u);
  EXPECT_LT((bezier.controlPoints[1] - HomogeneousPoint(w, w, 0, w)).norm(), 1e-15);
  EXPECT_LT((bezier.controlPoints[2] - HomogeneousPoint(0, 1, 0, 1)).norm(), 1e-15);
}

TEST(PolynomialSpan, PowerAndBezierFormsConvertBothWays) {
  for (const PolynomialSpan& span : toPowerBasis(testing::sProfile({1, 3, 1, 1, 1, 3, 1}))) {
    PolynomialSpan back = toPowerBasis(toBezier(span));
    ASSERT_EQ(back.coefficients.size(), span.coefficients.size());
    for (std::size_t k = 0; k < span.coefficients.size(); ++k)
      EXPECT_LT((back.coefficients[k] - span.coefficients[k]).norm(),
                1e-12 * (1 + span.coefficients[k].norm()));
  }
}

TEST(PiecewisePolynomialCurve, MatchesTheNurbsAndItsDerivatives) {
  NurbsCurve curve = testing::sProfile({1, 1, 1, 1, 1, 3, 1});
  PiecewisePolynomialCurve spans(toPowerBasis(curve));
  EXPECT_EQ(spans.breakpoints(), curve.breakpoints());
  for (double t : parameterGrid(curve, 400)) {
    CurveDerivatives a = curve.derivatives(t), b = spans.derivatives(t);
    EXPECT_LT((a.point - b.point).norm(), 1e-12) << t;
    EXPECT_LT((a.first - b.first).norm(), 1e-10 * a.first.norm()) << t;
    EXPECT_LT((a.second - b.second).norm(), 1e-9 * (1 + a.second.norm())) << t;
  }
}

TEST(PiecewisePolynomialCurve, RejectsSpansThatDoNotFollowOneAnother) {
  std::vector<PolynomialSpan> spans = toPowerBasis(testing::sProfile());
  spans[2].t0 += 0.01;
  EXPECT_THROW(PiecewisePolynomialCurve{spans}, GeometryError);
  EXPECT_THROW(PiecewisePolynomialCurve{{}}, GeometryError);
}

} // namespace
} // namespace cncc::geom
