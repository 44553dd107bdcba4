// The Sinumerik C spline and A spline models.

#include "cncc/geom/arc_length.h"
#include "cncc/geom/curve_deviation.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/geom/interpolating_splines.h"
#include "test_curves.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>

namespace cncc::geom {
namespace {

using Vector = Eigen::Vector3d;

// Points on the planar cubic x = s, y = s^3 / 10 - s, at uneven steps.
std::vector<Vector> cubicPoints() {
  std::vector<Vector> points;
  for (double s : {-2.0, -1.6, -0.9, -0.5, 0.0, 0.4, 1.1, 1.5, 2.0, 2.6, 3.0})
    points.emplace_back(s, 0.1 * s * s * s - s, 0.0);
  return points;
}

SplineTransitions bothEnds(SplineEndCondition condition) {
  SplineTransitions transitions;
  transitions.start = condition;
  transitions.end = condition;
  return transitions;
}

double distanceToLine(const Vector& p, const Vector& a, const Vector& b) {
  return (p - a).cross((b - a).normalized()).norm();
}

TEST(InterpolatingSplines, ChordLengthParameters) {
  std::vector<double> t = chordLengthParameters({{0, 0, 0}, {3, 4, 0}, {3, 4, 2}});
  ASSERT_EQ(t.size(), 3u);
  EXPECT_DOUBLE_EQ(t[1], 5.0);
  EXPECT_DOUBLE_EQ(t[2], 7.0);
}

TEST(InterpolatingSplines, BothPassThroughTheirPoints) {
  std::vector<Vector> points = cubicPoints();
  std::vector<double> t = chordLengthParameters(points);
  for (const PiecewisePolynomialCurve& spline : {cSpline(points), aSpline(points)}) {
    ASSERT_EQ(spline.spans().size(), points.size() - 1);
    for (std::size_t i = 0; i < points.size(); ++i)
      EXPECT_LT((spline.point(t[i]) - points[i]).norm(), 1e-12) << i;
  }
}

TEST(InterpolatingSplines, CSplineIsCurvatureContinuousWhenGlobal) {
  std::vector<Vector> points = cubicPoints();
  std::vector<double> t = chordLengthParameters(points);
  PiecewisePolynomialCurve spline = cSpline(points, {}, {.windowBlocks = 0});
  for (std::size_t i = 1; i + 1 < points.size(); ++i) {
    const PolynomialSpan& before = spline.spans()[i - 1];
    const PolynomialSpan& after = spline.spans()[i];
    CurveDerivatives left = before.derivativesAt(1.0);
    CurveDerivatives right = after.derivativesAt(0.0);
    double hb = before.t1 - before.t0, ha = after.t1 - after.t0;
    EXPECT_LT((left.first / hb - right.first / ha).norm(), 1e-12) << i;
    EXPECT_LT((left.second / (hb * hb) - right.second / (ha * ha)).norm(), 1e-10) << i;
  }
}

TEST(InterpolatingSplines, NaturalEndsHaveZeroSecondDerivative) {
  std::vector<Vector> points = cubicPoints();
  SplineTransitions natural = bothEnds(SplineEndCondition::Natural);
  for (const PiecewisePolynomialCurve& spline :
       {cSpline(points, natural), aSpline(points, natural)}) {
    EXPECT_LT(spline.spans().front().derivativesAt(0.0).second.norm(), 1e-12);
    EXPECT_LT(spline.spans().back().derivativesAt(1.0).second.norm(), 1e-12);
  }
}

TEST(InterpolatingSplines, TangentEndsFollowTheGivenDirections) {
  std::vector<Vector> points = cubicPoints();
  SplineTransitions tangent;
  tangent.startDirection = Vector(0, 2, 0);
  tangent.endDirection = Vector(1, 1, 0);
  for (const PiecewisePolynomialCurve& spline :
       {cSpline(points, tangent), aSpline(points, tangent)}) {
    ParameterRange range = spline.domain();
    EXPECT_LT((spline.derivative(range.t0) - Vector(0, 1, 0)).norm(), 1e-12);
    EXPECT_LT((spline.derivative(range.t1) - Vector(1, 1, 0).normalized()).norm(), 1e-12);
  }
  // Without a direction the adjacent chord is the tangent.
  PiecewisePolynomialCurve chordTangent = cSpline(points);
  Vector firstChord = (points[1] - points[0]).normalized();
  EXPECT_LT((chordTangent.derivative(0.0) - firstChord).norm(), 1e-12);
}

TEST(InterpolatingSplines, BothReproduceUnevenlySpacedPointsOnALine) {
  // In the chord length parameter, points on a line are a polynomial of degree 1, so
  // every cubic model with consistent ends reproduces it exactly and at unit speed.
  std::vector<Vector> line;
  for (double s : {0.0, 0.3, 1.0, 1.2, 2.0, 3.5, 3.6, 5.0})
    line.emplace_back(1.0 + 2.0 * s, -s, 0.5 * s);
  SplineTransitions natural = bothEnds(SplineEndCondition::Natural);
  SplineTransitions automatic = bothEnds(SplineEndCondition::Auto);
  for (const PiecewisePolynomialCurve& spline :
       {cSpline(line), cSpline(line, natural), cSpline(line, automatic), aSpline(line),
        aSpline(line, natural), aSpline(line, automatic)}) {
    for (double t = spline.domain().t0; t <= spline.domain().t1; t += 0.01)
      EXPECT_LT(distanceToLine(spline.point(t), line.front(), line.back()), 1e-12);
    EXPECT_NEAR(spline.derivative(0.77).norm(), 1.0, 1e-12);
  }
}

// Largest |y - f(x)| over the spline through points of y = f(x) at spacing h in x.
double cubicInterpolationError(double h) {
  auto f = [](double x) { return 0.02 * x * x * x - 0.1 * x * x; };
  auto slope = [](double x) { return 0.06 * x * x - 0.2 * x; };
  std::vector<Vector> points;
  for (int i = 0; i * h <= 5.0 + 1e-12; ++i)
    points.emplace_back(i * h, f(i * h), 0.0);
  SplineTransitions ends{SplineEndCondition::Tangent, SplineEndCondition::Tangent,
                         Vector(1, slope(0.0), 0), Vector(1, slope(5.0), 0)};
  PiecewisePolynomialCurve spline = cSpline(points, ends, {.windowBlocks = 0});
  double worst = 0.0;
  for (double t = 0.0; t <= spline.domain().t1; t += 0.001) {
    Vector p = spline.point(t);
    worst = std::max(worst, std::fabs(p.y() - f(p.x())));
  }
  return worst;
}

TEST(InterpolatingSplines, CSplineOfACubicConvergesAtFourthOrder) {
  // A cubic curve is not a cubic in chord length, so it is reproduced only to
  // O(h^4): halving the spacing divides the error by about 16.
  double coarse = cubicInterpolationError(0.5);
  double fine = cubicInterpolationError(0.25);
  EXPECT_LT(coarse, 1e-4);
  EXPECT_GT(coarse / fine, 10.0);
}

TEST(InterpolatingSplines, WindowedCSplineIsCloseToTheGlobalOne) {
  std::vector<Vector> points;
  for (int i = 0; i <= 40; ++i)
    points.emplace_back(std::cos(0.15 * i) * (10 + i), std::sin(0.15 * i) * (10 + i), 0.0);
  PiecewisePolynomialCurve global = cSpline(points, {}, {.windowBlocks = 0});
  PiecewisePolynomialCurve windowed = cSpline(points);
  PiecewisePolynomialCurve wide = cSpline(points, {}, {.windowBlocks = 100});
  double difference = 0.0, wideDifference = 0.0;
  for (double t = 0.0; t <= global.domain().t1; t += 0.05) {
    difference = std::max(difference, (global.point(t) - windowed.point(t)).norm());
    wideDifference = std::max(wideDifference, (global.point(t) - wide.point(t)).norm());
  }
  EXPECT_GT(difference, 0.0); // the window is a different model
  EXPECT_LT(difference, 1e-4);
  EXPECT_LT(wideDifference, 1e-11); // a window over all points is the global spline
  // Tangent-continuous at every point, windowed or not.
  for (std::size_t i = 1; i + 1 < points.size(); ++i) {
    const PolynomialSpan& before = windowed.spans()[i - 1];
    const PolynomialSpan& after = windowed.spans()[i];
    Vector left = before.derivativesAt(1.0).first / (before.t1 - before.t0);
    Vector right = after.derivativesAt(0.0).first / (after.t1 - after.t0);
    EXPECT_LT((left - right).norm(), 1e-12);
  }
}

TEST(InterpolatingSplines, AkimaChangeMovesAtMostSixSegments) {
  std::vector<Vector> points;
  for (int i = 0; i <= 20; ++i)
    points.emplace_back(i, std::sin(0.7 * i), 0.0);
  std::vector<Vector> moved = points;
  moved[10].y() += 0.5;
  // Same chord lengths away from the change, so compare span by span.
  PiecewisePolynomialCurve before = aSpline(points);
  PiecewisePolynomialCurve after = aSpline(moved);
  int changed = 0;
  for (std::size_t span = 0; span < before.spans().size(); ++span) {
    bool differs = false;
    for (double u = 0.0; u <= 1.0; u += 0.125)
      differs |= (before.spans()[span].pointAt(u) - after.spans()[span].pointAt(u)).norm() > 1e-12;
    changed += differs;
    if (differs) {
      EXPECT_GE(span, 7u);
      EXPECT_LE(span, 12u);
    }
  }
  EXPECT_EQ(changed, 6);
}

TEST(InterpolatingSplines, PolarContourThroughEqualArcKnots) {
  // shared/REFERENCE-CASES.md, case 3: deviation of a periodic cubic spline and of an
  // Akima spline through 357 / 177 knots equally spaced in arc length: 4.45e-5 /
  // 1.15e-3 mm (cubic) and 4.60e-4 / 3.85e-3 mm (Akima). The models here have tangent
  // ends (with the curve's own tangents) instead of periodic ones and chord length
  // parameters, so agreement within 10% is what to expect (measured: 4.50e-5 /
  // 1.21e-3 and 4.46e-4 / 3.90e-3).
  PolarCurve contour = testing::polarContour();
  SplineTransitions ends;
  ends.startDirection = contour.derivative(contour.domain().t0);
  ends.endDirection = contour.derivative(contour.domain().t1);
  struct Case {
    int knots;
    double cubic;
    double akima;
  };
  for (Case c : {Case{357, 4.45e-5, 4.60e-4}, Case{177, 1.15e-3, 3.85e-3}}) {
    std::vector<Vector> points;
    for (double t : equalArcLengthParameters(contour, std::size_t(c.knots) + 1))
      points.push_back(contour.point(t));
    double cubic = measureCurveDeviation(cSpline(points, ends), contour, {1e-6}).maxDeviation();
    double akima = measureCurveDeviation(aSpline(points, ends), contour, {1e-6}).maxDeviation();
    EXPECT_NEAR(cubic, c.cubic, 0.1 * c.cubic) << c.knots;
    EXPECT_NEAR(akima, c.akima, 0.1 * c.akima) << c.knots;
  }
}

TEST(InterpolatingSplines, BadPointsAreReported) {
  EXPECT_TRUE(findSplinePointsProblem({{0, 0, 0}}));
  EXPECT_TRUE(findSplinePointsProblem({{0, 0, 0}, {0, 0, 0}}));
  EXPECT_TRUE(findSplinePointsProblem({{0, 0, 0}, {NAN, 0, 0}}));
  EXPECT_FALSE(findSplinePointsProblem({{0, 0, 0}, {1, 0, 0}}));
  EXPECT_THROW(cSpline({{0, 0, 0}}), GeometryError);
  EXPECT_THROW(aSpline({{1, 2, 3}, {1, 2, 3}, {4, 5, 6}}), GeometryError);
  // Two points: a straight segment for every transition.
  PiecewisePolynomialCurve two =
      cSpline({{0, 0, 0}, {2, 0, 0}}, bothEnds(SplineEndCondition::Auto));
  EXPECT_LT((two.point(1.0) - Vector(1, 0, 0)).norm(), 1e-12);
}

} // namespace
} // namespace cncc::geom
