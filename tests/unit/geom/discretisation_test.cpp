#include "cncc/geom/arc_length.h"
#include "cncc/geom/deviation.h"
#include "cncc/geom/discretisation.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/geom/line_arc_curves.h"
#include "test_curves.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace cncc::geom {
namespace {

using std::numbers::pi;

TEST(ChordDeviation, OfACircleChordIsTheSagitta) {
  NurbsCurve circle = testing::unitCircle();
  ArcLengthTable table(circle);
  // A chord over 0.8 rad of the unit circle: half-angle 0.4, sagitta 1 - cos 0.4.
  double ta = table.parameterAt(1.0), tb = table.parameterAt(1.8);
  EXPECT_NEAR(chordDeviation(circle, ta, tb), 1 - std::cos(0.4), 1e-10);
  ArcCurve arc({0, 0}, 7.0, 0.3, 1.0);
  EXPECT_NEAR(chordDeviation(arc, 0.0, arc.length()), 7 * (1 - std::cos(0.5)), 1e-14);
  EXPECT_EQ(chordDeviation(arc, 1.0, 1.0), 0.0);
}

TEST(ChordDeviation, FindsTheHigherOfTwoHumps) {
  // y = sin x + 0.3 sin 5x over [0, 2 pi] against its chord y = 0: the humps differ in
  // height and width; compare with brute force.
  FunctionCurve wave = FunctionCurve::fromCoordinates(
      {0.0, 2 * pi}, [](double x) { return x; },
      [](double x) { return std::sin(x) + 0.3 * std::sin(5 * x); });
  double brute = 0.0;
  for (int i = 0; i <= 1000000; ++i) {
    double x = 2 * pi * i / 1000000;
    brute = std::max(brute, std::fabs(std::sin(x) + 0.3 * std::sin(5 * x)));
  }
  double deviation = chordDeviation(wave, 0.0, 2 * pi);
  EXPECT_GE(deviation, brute - 1e-14);
  EXPECT_LE(deviation, brute + 1e-10);
}

// Circle discretisations have a closed form: each full chord spans 2 acos(1 - tol / R).
TEST(ChordDiscretisation, OfACircleHasTheClosedFormCount) {
  for (double tolerance : {0.01, 0.001}) {
    int expected = static_cast<int>(std::ceil(pi / std::acos(1 - tolerance)));
    CurveSamples nurbs = discretiseByChordTolerance(testing::unitCircle(), tolerance);
    ArcCurve arc({0, 0}, 1.0, 0.0, 2 * pi);
    CurveSamples exact = discretiseByChordTolerance(arc, tolerance);
    EXPECT_EQ(static_cast<int>(nurbs.chordCount()), expected) << tolerance;
    EXPECT_EQ(static_cast<int>(exact.chordCount()), expected) << tolerance;
    // Every chord but the last is as long as the tolerance allows.
    for (std::size_t i = 0; i + 2 < exact.points.size(); ++i) {
      double sagitta = chordDeviation(arc, exact.parameters[i], exact.parameters[i + 1]);
      EXPECT_NEAR(sagitta, tolerance, 1e-12);
    }
  }
}

TEST(ChordDiscretisation, VerticesAreOnTheCurveFromStartToEnd) {
  NurbsCurve curve = testing::sProfile();
  CurveSamples samples = discretiseByChordTolerance(curve, 0.05);
  ASSERT_EQ(samples.parameters.size(), samples.points.size());
  EXPECT_EQ(samples.parameters.front(), 0.0);
  EXPECT_EQ(samples.parameters.back(), 1.0);
  for (std::size_t i = 0; i < samples.points.size(); ++i) {
    EXPECT_EQ(samples.points[i], curve.point(samples.parameters[i]));
    if (i > 0) {
      EXPECT_GT(samples.parameters[i], samples.parameters[i - 1]);
    }
  }
}

TEST(ChordDiscretisation, EveryChordReachesAsFarAsPossible) {
  // Farthest reach: moving any chord's end (but the last) a little further breaks the
  // tolerance, as measured independently on the sub-curve.
  PolarCurve contour = testing::polarContour();
  const double tolerance = 0.01;
  CurveSamples samples = discretiseByChordTolerance(contour, tolerance);
  for (std::size_t i = 0; i + 2 < samples.parameters.size(); i += 7) {
    double a = samples.parameters[i], b = samples.parameters[i + 1] + 1e-4;
    FunctionCurve longer = testing::restrictTo(contour, a, b);
    DeviationReport report = measureDeviation({contour.point(a), contour.point(b)}, longer);
    EXPECT_GT(report.maxDeviation(), tolerance) << i;
  }
}

TEST(ChordDiscretisation, AStraightCurveIsOneChord) {
  EXPECT_EQ(discretiseByChordTolerance(LineCurve({0, 0, 0}, {5, 1, 2}), 1e-6).chordCount(), 1u);
}

TEST(ChordDiscretisation, RejectsANonPositiveTolerance) {
  EXPECT_THROW(discretiseByChordTolerance(testing::unitCircle(), 0.0), GeometryError);
  EXPECT_THROW(discretiseByChordTolerance(testing::unitCircle(), -1.0), GeometryError);
}

TEST(UniformParameterSampling, TakesEqualParameterSteps) {
  CurveSamples samples = sampleUniformParameter(testing::sProfile(), 5);
  ASSERT_EQ(samples.points.size(), 5u);
  EXPECT_EQ(samples.parameters, (std::vector<double>{0, 0.25, 0.5, 0.75, 1}));
  EXPECT_LT((samples.points.back() - Eigen::Vector3d(175, 150, 0)).norm(), 1e-12);
  EXPECT_THROW(sampleUniformParameter(testing::sProfile(), 1), GeometryError);
}

TEST(EqualArcLengthSampling, StepsAreEqualAndTheLastEndsAtTheEnd) {
  NurbsCurve circle = testing::unitCircle();
  CurveSamples samples = sampleEqualArcLength(circle, 1.0);
  ASSERT_EQ(samples.points.size(), 8u); // s = 0..6, then 2 pi
  EXPECT_EQ(samples.parameters.back(), 1.0);
  for (std::size_t i = 0; i + 1 < samples.points.size(); ++i) {
    double step = arcLength(circle, samples.parameters[i], samples.parameters[i + 1]);
    EXPECT_NEAR(step, i + 2 < samples.points.size() ? 1.0 : 2 * pi - 6, 1e-10);
  }
  // An exact multiple leaves no sliver at the end.
  EXPECT_EQ(sampleEqualArcLength(circle, 2 * pi / 4).points.size(), 5u);
  EXPECT_THROW(sampleEqualArcLength(circle, 0.0), GeometryError);
}

} // namespace
} // namespace cncc::geom
