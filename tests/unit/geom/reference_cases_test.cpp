// The figures of shared/REFERENCE-CASES.md, recomputed by the kernel.

#include "cncc/geom/arc_length.h"
#include "cncc/geom/curvature.h"
#include "cncc/geom/deviation.h"
#include "cncc/geom/discretisation.h"
#include "test_curves.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>

namespace cncc::geom {
namespace {

// Discretises at `tolerance`, expects `chords` chords, and re-measures every chord
// against the arc it replaces with the independent deviation measurement.
void expectMinimumChordCount(const Curve& curve, double tolerance, std::size_t chords) {
  CurveSamples samples = discretiseByChordTolerance(curve, tolerance);
  EXPECT_EQ(samples.chordCount(), chords) << "tolerance " << tolerance;
  double worst = 0.0;
  for (std::size_t i = 0; i + 1 < samples.points.size(); ++i) {
    FunctionCurve arc =
        testing::restrictTo(curve, samples.parameters[i], samples.parameters[i + 1]);
    DeviationReport report =
        measureDeviation({samples.points[i], samples.points[i + 1]}, arc, {tolerance * 1e-3});
    EXPECT_LE(report.maxDeviation(), tolerance) << "chord " << i;
    worst = std::max(worst, report.maxDeviation());
  }
  // Chords are as long as allowed, so the worst one is at the tolerance.
  EXPECT_GT(worst, (1 - 1e-6) * tolerance);
  DeviationReport whole = measureDeviation(samples.points, curve, {tolerance * 1e-2});
  EXPECT_LE(whole.maxDeviation(), tolerance);
}

TEST(ReferenceCase3PolarContour, LengthAndMinimumRadius) {
  PolarCurve contour = testing::polarContour();
  EXPECT_NEAR(arcLength(contour), 136.1895, 5e-5);
  CurvatureExtreme tightest = minimumRadiusOfCurvature(contour);
  EXPECT_NEAR(tightest.radius, 2.3314, 5e-5);
  // Convex minimum 2.659 at t = 0 (a local, not the global, minimum).
  EXPECT_NEAR(1.0 / contour.curvature(0.0), 2.659, 5e-4);
  // The tightest bend is concave: the curve turns clockwise there.
  CurveDerivatives d = contour.derivatives(tightest.parameter);
  EXPECT_LT(d.first.cross(d.second).z(), 0.0);
}

TEST(ReferenceCase3PolarContour, MinimumChordCounts) {
  PolarCurve contour = testing::polarContour();
  expectMinimumChordCount(contour, 0.001, 580);
  expectMinimumChordCount(contour, 0.005, 257);
  expectMinimumChordCount(contour, 0.01, 181);
  expectMinimumChordCount(contour, 0.05, 80);
}

TEST(ReferenceCase3PolarContour, SameFiguresFromFiniteDifferences) {
  // The contour as the language gives it: x(t), y(t) with no derivatives.
  auto r = [](double t) { return 18.0 + 4.0 * std::cos(2 * t) * std::cos(6 * t); };
  FunctionCurve contour = FunctionCurve::fromCoordinates(
      {0.0, testing::kTwoPi}, [r](double t) { return r(t) * std::cos(t); },
      [r](double t) { return r(t) * std::sin(t); });
  EXPECT_NEAR(arcLength(contour), 136.1895, 5e-5);
  EXPECT_NEAR(minimumRadiusOfCurvature(contour).radius, 2.3314, 5e-5);
  EXPECT_EQ(discretiseByChordTolerance(contour, 0.01).chordCount(), 181u);
}

TEST(ReferenceCase3PolarContour, DeviationOfOneDegreeChords) {
  PolarCurve contour = testing::polarContour();
  CurveSamples oneDegree = sampleUniformParameter(contour, 361);
  EXPECT_NEAR(measureDeviation(oneDegree.points, contour, {1e-5}).maxDeviation(), 0.00691, 5e-6);
  CurveSamples equalArc = sampleUniformParameter(contour, 2);
  equalArc.points.clear();
  for (double t : equalArcLengthParameters(contour, 178)) // 177 chords
    equalArc.points.push_back(contour.point(t));
  EXPECT_NEAR(measureDeviation(equalArc.points, contour, {1e-6}).maxDeviation(), 0.0312, 5e-5);
}

TEST(ReferenceCase2Spiral, LengthAndMinimumRadius) {
  PolarCurve spiral = testing::archimedeanSpiral();
  EXPECT_NEAR(arcLength(spiral), 48.0817, 5e-5);
  CurvatureExtreme tightest = minimumRadiusOfCurvature(spiral);
  EXPECT_NEAR(tightest.radius, 1.2423, 5e-5);
  EXPECT_EQ(tightest.parameter, 0.0);
}

TEST(ReferenceCase2Spiral, MinimumChordCounts) {
  PolarCurve spiral = testing::archimedeanSpiral();
  expectMinimumChordCount(spiral, 0.005, 90);
  expectMinimumChordCount(spiral, 0.004, 100);
  expectMinimumChordCount(spiral, 0.003, 116);
  expectMinimumChordCount(spiral, 0.002, 141);
}

TEST(ReferenceCase2Spiral, PublishedHundredStepPolylineBreaksFiveMicrometres) {
  PolarCurve spiral = testing::archimedeanSpiral();
  CurveSamples published = sampleUniformParameter(spiral, 101);
  DeviationReport report = measureDeviation(published.points, spiral, {1e-7});
  EXPECT_NEAR(report.maxDeviation(), 0.00688, 5e-6);
  EXPECT_EQ(report.worst().segment, 99u); // the last span
}

TEST(ReferenceCase1SProfile, UnitWeights) {
  NurbsCurve curve = testing::sProfile();
  EXPECT_NEAR(arcLength(curve), 334.7, 0.05);
  EXPECT_NEAR(minimumRadiusOfCurvature(curve).radius, 2.046, 5e-4);
  expectMinimumChordCount(curve, 0.01, 123);
  expectMinimumChordCount(curve, 0.001, 388);
}

TEST(ReferenceCase1SProfile, WeightSixIsThree) {
  NurbsCurve curve = testing::sProfile({1, 1, 1, 1, 1, 3, 1});
  EXPECT_NEAR(arcLength(curve), 344.31, 5e-3);
  EXPECT_NEAR(minimumRadiusOfCurvature(curve).radius, 2.046, 5e-4);
  expectMinimumChordCount(curve, 0.01, 115);
  expectMinimumChordCount(curve, 0.001, 362);
}

TEST(ReferenceCase1SProfile, PublishedFiftyPointPolylineDeviation) {
  NurbsCurve curve = testing::sProfile();
  CurveSamples published = sampleUniformParameter(curve, 50);
  EXPECT_NEAR(measureDeviation(published.points, curve, {1e-5}).maxDeviation(), 0.2506, 5e-5);
}

} // namespace
} // namespace cncc::geom
