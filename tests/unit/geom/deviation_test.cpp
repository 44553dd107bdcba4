#include "cncc/geom/composite_curve.h"
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

} // namespace
} // namespace cncc::geom
