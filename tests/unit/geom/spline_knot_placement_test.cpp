// Adaptive point placement for the modelled CSPLINE / ASPLINE, measured on the polar
// contour of reference case 3 (shared/REFERENCE-CASES.md).

#include "cncc/geom/curve_deviation.h"
#include "cncc/geom/deviation.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/geom/line_arc_curves.h"
#include "cncc/geom/spline_knot_placement.h"
#include "test_curves.h"

#include <gtest/gtest.h>

namespace cncc::geom {
namespace {

// Places the points, checks them against an independent measurement of the model
// spline through them, and returns the point count.
std::size_t placeAndVerify(const Curve& curve, InterpolatingSplineKind kind, double tolerance) {
  SplineKnotPlacementOptions options;
  options.kind = kind;
  options.tolerance = tolerance;
  SplineKnots knots = placeSplineKnots(curve, options);
  EXPECT_EQ(knots.points.size(), knots.parameters.size());
  EXPECT_EQ(knots.parameters.front(), curve.domain().t0);
  EXPECT_EQ(knots.parameters.back(), curve.domain().t1);
  for (std::size_t i = 0; i < knots.points.size(); ++i)
    EXPECT_LT((knots.points[i] - curve.point(knots.parameters[i])).norm(), 1e-12);
  // No two points almost on top of each other (a sliver before the end once
  // left 7e-8 mm), which printed coordinates could not resolve.
  for (std::size_t i = 1; i < knots.points.size(); ++i)
    EXPECT_GT((knots.points[i] - knots.points[i - 1]).norm(), 1e-3)
        << "points " << i - 1 << " and " << i;
  EXPECT_LE(knots.deviation, tolerance);
  PiecewisePolynomialCurve spline = modelSpline(kind, knots.points, knots.transitions);
  double measured = measureCurveDeviation(spline, curve, {tolerance * 1e-3}).maxDeviation();
  EXPECT_LE(measured, tolerance);
  EXPECT_NEAR(measured, knots.deviation, tolerance * 1e-2);
  // Independently: a polyline of 256 points per spline segment (its sag from the
  // spline is far below the tolerance) measured by the polyline deviation.
  std::vector<Eigen::Vector3d> dense;
  for (const PolynomialSpan& span : spline.spans())
    for (int k = 0; k < 256; ++k)
      dense.push_back(span.pointAt(k / 256.0));
  dense.push_back(knots.points.back());
  EXPECT_LE(measureDeviation(dense, curve, {tolerance * 1e-3}).maxDeviation(), tolerance * 1.01);
  return knots.points.size();
}

TEST(SplineKnotPlacement, PolarContourCSplineAtTenMicrometres) {
  // Equally spaced knots need 106 (every count from 106 on passes, 88 the first).
  std::size_t points =
      placeAndVerify(testing::polarContour(), InterpolatingSplineKind::CSpline, 0.01);
  RecordProperty("points", int(points));
  EXPECT_LE(points, 116u);
}

TEST(SplineKnotPlacement, PolarContourASplineAtTenMicrometres) {
  std::size_t points =
      placeAndVerify(testing::polarContour(), InterpolatingSplineKind::ASpline, 0.01);
  RecordProperty("points", int(points));
  EXPECT_LE(points, 128u);
}

TEST(SplineKnotPlacement, PolarContourCSplineAtOneMicrometre) {
  std::size_t points =
      placeAndVerify(testing::polarContour(), InterpolatingSplineKind::CSpline, 0.001);
  RecordProperty("points", int(points));
  EXPECT_LE(points, 182u);
}

TEST(SplineKnotPlacement, PolarContourASplineAtOneMicrometre) {
  std::size_t points =
      placeAndVerify(testing::polarContour(), InterpolatingSplineKind::ASpline, 0.001);
  RecordProperty("points", int(points));
  EXPECT_LE(points, 277u);
}

TEST(SplineKnotPlacement, ALineNeedsOnlyItsEnds) {
  LineCurve line({0, 0, 0}, {10, 5, 0});
  for (InterpolatingSplineKind kind :
       {InterpolatingSplineKind::CSpline, InterpolatingSplineKind::ASpline}) {
    SplineKnotPlacementOptions options;
    options.kind = kind;
    SplineKnots knots = placeSplineKnots(line, options);
    EXPECT_EQ(knots.points.size(), 2u);
    EXPECT_LT(knots.deviation, 1e-9);
  }
}

TEST(SplineKnotPlacement, SProfileWithBothModels) {
  NurbsCurve profile = testing::sProfile();
  std::size_t c = placeAndVerify(profile, InterpolatingSplineKind::CSpline, 0.01);
  std::size_t a = placeAndVerify(profile, InterpolatingSplineKind::ASpline, 0.01);
  RecordProperty("cspline", int(c));
  RecordProperty("aspline", int(a));
  // Far fewer than the 123 chords the same tolerance needs.
  EXPECT_LT(c, 123u / 2);
  EXPECT_LT(a, 123u);
}

TEST(SplineKnotPlacement, RejectsABadTolerance) {
  SplineKnotPlacementOptions options;
  options.tolerance = 0.0;
  EXPECT_THROW(placeSplineKnots(testing::polarContour(), options), GeometryError);
}

} // namespace
} // namespace cncc::geom
