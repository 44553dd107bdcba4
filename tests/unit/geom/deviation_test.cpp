#include "cncc/geom/composite_curve.h"
#include "cncc/geom/deviation.h"
#include "cncc/geom/discretisation.h"
#include "cncc/geom/function_curve.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/geom/line_arc_curves.h"
#include "test_curves.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace cncc::geom {
namespace {

using std::numbers::pi;

TEST(Deviation, OfACircleChordIsTheSagittaBothWays) {
  // Arc of radius R over half-angle a each side of +x; its chord deviates R (1 - cos a).
  for (double a : {0.01, 0.3, 1.0}) {
    const double radius = 5.0;
    ArcCurve arc({0, 0}, radius, -a, 2 * a);
    std::vector<Eigen::Vector3d> chord{arc.point(0.0), arc.point(arc.length())};
    DeviationReport report = measureDeviation(chord, arc);
    double sagitta = radius * (1 - std::cos(a));
    EXPECT_NEAR(report.polylineToCurve.distance, sagitta, 1e-12) << a;
    EXPECT_NEAR(report.curveToPolyline.distance, sagitta, 1e-12) << a;
    EXPECT_NEAR(report.maxDeviation(), sagitta, 1e-12) << a;
    // Where: the arc's middle and the chord's middle.
    EXPECT_LT((report.curveToPolyline.curvePoint - Eigen::Vector3d(radius, 0, 0)).norm(), 1e-5);
    EXPECT_LT(
        (report.polylineToCurve.polylinePoint - Eigen::Vector3d(radius * std::cos(a), 0, 0)).norm(),
        1e-5);
  }
}

TEST(Deviation, OfAnOffsetPath) {
  LineCurve line({0, 0, 0}, {10, 0, 0});
  DeviationReport report = measureDeviation({{0, 0.2, 0}, {4, 0.2, 0}, {10, 0.2, 0}}, line);
  EXPECT_NEAR(report.polylineToCurve.distance, 0.2, 1e-14);
  EXPECT_NEAR(report.curveToPolyline.distance, 0.2, 1e-14);
}

TEST(Deviation, APathThatStopsShortIsCaughtFromTheCurveSide) {
  LineCurve line({0, 0, 0}, {10, 0, 0});
  DeviationReport shortPath = measureDeviation({{0, 0, 0}, {8, 0, 0}}, line);
  EXPECT_NEAR(shortPath.polylineToCurve.distance, 0.0, 1e-14);
  EXPECT_NEAR(shortPath.curveToPolyline.distance, 2.0, 1e-14);
  EXPECT_NEAR(shortPath.curveToPolyline.curveParameter, 10.0, 1e-14);
  DeviationReport longPath = measureDeviation({{0, 0, 0}, {12, 0, 0}}, line);
  EXPECT_NEAR(longPath.polylineToCurve.distance, 2.0, 1e-14);
  EXPECT_NEAR(longPath.curveToPolyline.distance, 0.0, 1e-14);
  EXPECT_EQ(&longPath.worst(), &longPath.polylineToCurve);
}

TEST(Deviation, OfAPathCuttingACorner) {
  auto first = std::make_shared<LineCurve>(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0));
  auto second = std::make_shared<LineCurve>(Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(1, 1, 0));
  CompositeCurve corner({first, second});
  DeviationReport report = measureDeviation({{0, 0, 0}, {1, 1, 0}}, corner);
  // The corner (1, 0) is 1/sqrt 2 from the diagonal; the diagonal's middle is 1/2 from
  // both legs.
  EXPECT_NEAR(report.curveToPolyline.distance, std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(report.curveToPolyline.curveParameter, 1.0, 1e-6);
  EXPECT_NEAR(report.polylineToCurve.distance, 0.5, 1e-12);
}

TEST(Deviation, OfASinglePoint) {
  DeviationReport report = measureDeviation({{0, 0, 0}}, testing::unitCircle(), {1e-5});
  EXPECT_NEAR(report.polylineToCurve.distance, 1.0, 1e-14);
  EXPECT_NEAR(report.curveToPolyline.distance, 1.0, 1e-14);
  EXPECT_THROW(measureDeviation({}, testing::unitCircle()), GeometryError);
}

TEST(Deviation, OfHelixChordsIsTheirTolerance) {
  ArcCurve helix({0, 0}, 3.0, 0.0, 4 * pi, 0.0, 10.0);
  const double tolerance = 0.002;
  CurveSamples chords = discretiseByChordTolerance(helix, tolerance);
  DeviationReport report = measureDeviation(chords.points, helix, {1e-6});
  EXPECT_LE(report.maxDeviation(), tolerance);
  EXPECT_GT(report.maxDeviation(), 0.999 * tolerance);
}

// An astroid's four cusps bend it without limit; uniform steps of its
// parameter (as a controller runs them) are measured with the bend near each
// chord, not the cusps' everywhere: within a work the curve's tightest radius
// for every chord would pass many times over, and to the accuracy of a
// measurement on dense chords.
TEST(Deviation, OfUniformStepsAlongACurveWithCuspsTakesTheBendNearEachChord) {
  FunctionCurve astroid({0.0, 2 * pi}, [](double t) {
    return Eigen::Vector3d(20 * std::pow(std::cos(t), 3), 20 * std::pow(std::sin(t), 3), 0.0);
  });
  std::vector<Eigen::Vector3d> steps;
  for (int k = 0; k <= 300; ++k) {
    steps.push_back(astroid.point(2 * pi * k / 300));
  }
  DeviationOptions bounded;
  bounded.accuracy = 1e-6;
  bounded.maximumWork = 5e6;
  DeviationReport report = measureDeviation(steps, astroid, bounded);
  // The chords' own sagitta, from many points on each.
  double sagitta = 0;
  for (std::size_t k = 0; k + 1 < steps.size(); ++k) {
    for (int i = 1; i < 200; ++i) {
      double t = 2 * pi * (double(k) + i / 200.0) / 300;
      Eigen::Vector3d a = steps[k];
      Eigen::Vector3d b = steps[k + 1];
      Eigen::Vector3d c = astroid.point(t);
      double along = std::clamp((c - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
      sagitta = std::max(sagitta, (a + along * (b - a) - c).norm());
    }
  }
  EXPECT_NEAR(report.maxDeviation(), sagitta, 1e-5);
}

TEST(CurveProximity, SmallestRadiusBetweenSampleSegmentsIsTheBendThere) {
  // A stadium: two half circles of radius 1 and 4 joined by lines.
  CompositeCurve stadium(
      {std::make_shared<ArcCurve>(Eigen::Vector2d{0, 0}, 1.0, pi / 2, pi),
       std::make_shared<LineCurve>(Eigen::Vector3d{0, -1, 0}, Eigen::Vector3d{10, -1, 0}),
       std::make_shared<ArcCurve>(Eigen::Vector2d{10, 3}, 4.0, -pi / 2, pi)});
  CurveProximity proximity(stadium, 1e-6);
  std::size_t last = proximity.samplePoints().size() - 2;
  EXPECT_NEAR(proximity.smallestRadiusBetween(0, last), 1.0, 1e-9);
  EXPECT_NEAR(proximity.smallestRadiusBetween(last, last), 4.0, 1e-9);
  std::size_t hint = 0;
  proximity.sampledDistance({5, -1, 0}, hint); // the line's middle
  EXPECT_TRUE(std::isinf(proximity.smallestRadiusBetween(hint, hint)));
}

TEST(CurveProximity, ClosestPointOnACircle) {
  NurbsCurve circle = testing::unitCircle();
  CurveProximity proximity(circle, 1e-6);
  CurveProximity::ClosestPoint c = proximity.closestPoint({2, 2, 0.5});
  EXPECT_NEAR(c.distance, std::hypot(2 * std::sqrt(2.0) - 1, 0.5), 1e-14);
  EXPECT_LT((c.point - Eigen::Vector3d(1, 1, 0).normalized()).norm(), 1e-8);
  EXPECT_NEAR(c.parameter, 0.125, 1e-8);
  EXPECT_NEAR(proximity.smallestSampledRadius(), 1.0, 1e-12);
  EXPECT_THROW(CurveProximity(circle, 0.0), GeometryError);
}

TEST(CurveProximity, ClosestPointFromAHintIsClosestPointsToTheBit) {
  // Three turns of a spiral: points beside a turn lie in the boxes of the
  // turns outside it.
  FunctionCurve spiral({0.0, 6 * std::numbers::pi}, [](double t) {
    return Eigen::Vector3d((1 + t) * std::cos(t), (1 + t) * std::sin(t), 0.0);
  });
  CurveProximity proximity(spiral, 1e-6);
  std::size_t hint = 0;
  for (int i = 0; i <= 2000; ++i) {
    double t = 6 * std::numbers::pi * i / 2000;
    // Inside, outside and on the curve, the hint the last point's segment.
    Eigen::Vector3d p = spiral.point(t) * (1 + 0.05 * std::sin(7.0 * i));
    CurveProximity::ClosestPoint expected = proximity.closestPoint(p);
    CurveProximity::ClosestPoint found = proximity.closestPoint(p, hint);
    EXPECT_EQ(found.distance, expected.distance) << i;
    EXPECT_EQ(found.parameter, expected.parameter) << i;
    EXPECT_EQ(found.point, expected.point) << i;
    ASSERT_LT(hint + 1, proximity.samplePoints().size());
  }
  // A hint past the end is the last segment.
  hint = 1u << 30;
  EXPECT_EQ(proximity.closestPoint({3, 4, 0}, hint).parameter,
            proximity.closestPoint({3, 4, 0}).parameter);
}

} // namespace
} // namespace cncc::geom
