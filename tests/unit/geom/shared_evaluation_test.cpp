// Work a curve's evaluation shares between what it is asked (a polar
// curve's point and derivative from one r(t), an offset's point from its
// base's point and derivative at once, the chord walk's samples in reused
// memory): the same values to the bit, and the same points counted.
#include "cncc/geom/bspline_fitting.h"
#include "cncc/geom/curve_deviation.h"
#include "cncc/geom/deviation.h"
#include "cncc/geom/discretisation.h"
#include "cncc/geom/evaluation_budget.h"
#include "cncc/geom/function_curve.h"
#include "cncc/geom/offset_curve.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>

namespace cncc::geom {
namespace {

using std::numbers::pi;

// A 3-turn Archimedean spiral r = 1 + 2t, r' by differences as a CDL polar
// curve's.
std::shared_ptr<PolarCurve> spiral() {
  return std::make_shared<PolarCurve>(ParameterRange{0.0, 6 * pi},
                                      [](double t) { return 1.0 + 2.0 * t; });
}

TEST(SharedEvaluation, APolarCurvesPointWithDerivativeIsItsPointAndDerivative) {
  auto curve = spiral();
  BudgetedCurve counted(*curve, 1000);
  for (double t : {-1.0, 0.0, 1e-4, 2.5, 6 * pi - 1e-4, 6 * pi, 30.0}) {
    PointWithDerivative both = curve->pointWithDerivative(t);
    Eigen::Vector3d point = curve->point(t);
    Eigen::Vector3d first = curve->derivative(t);
    for (int i = 0; i < 3; ++i) {
      EXPECT_EQ(both.point[i], point[i]) << t;
      EXPECT_EQ(both.first[i], first[i]) << t;
    }
    std::size_t before = counted.used();
    PointWithDerivative viaBudget = counted.pointWithDerivative(t);
    EXPECT_EQ(counted.used(), before + 2);
    EXPECT_EQ(viaBudget.point, both.point);
    EXPECT_EQ(viaBudget.first, both.first);
  }
}

TEST(SharedEvaluation, AnOffsetsPointIsItsBasesPointPlusTheNormal) {
  auto base = spiral();
  OffsetCurve offset(base, 0.5);
  for (double t : {0.0, 0.7, 3.0, 9.1, 6 * pi}) {
    Eigen::Vector3d expected = base->point(t) + 0.5 * leftNormalOf(base->derivative(t));
    Eigen::Vector3d point = offset.point(t);
    EXPECT_EQ(point.x(), expected.x()) << t;
    EXPECT_EQ(point.y(), expected.y()) << t;
    EXPECT_EQ(point.z(), expected.z()) << t;
  }
}

TEST(SharedEvaluation, TheWalksChordsKeepTheirToleranceAndRepeat) {
  // The offset of the spiral beside a 1 mm tool within 1 um, as the cut
  // asks it: every chord within the tolerance, measured afresh, and a walk
  // again (its sample memory reused within each walk) the same to the bit.
  OffsetCurve offset(spiral(), 0.5);
  CurveSamples first = discretiseByChordTolerance(offset, 0.001);
  CurveSamples again = discretiseByChordTolerance(offset, 0.001);
  ASSERT_GT(first.chordCount(), 100u);
  ASSERT_EQ(first.parameters, again.parameters);
  for (std::size_t i = 0; i + 1 < first.parameters.size(); ++i) {
    EXPECT_LE(chordDeviation(offset, first.parameters[i], first.parameters[i + 1]), 0.001) << i;
  }
  // The greedy walk reaches as far as it can: one chord over two of its
  // pieces does not keep the tolerance.
  for (std::size_t i = 0; i + 2 < first.parameters.size(); i += 17) {
    EXPECT_GT(chordDeviation(offset, first.parameters[i], first.parameters[i + 2]), 0.001) << i;
  }
}

TEST(SharedEvaluation, ADeviationMeasuredWithAGivenProximityIsTheSame) {
  // A B-spline fit of the spiral (what the fit measures each candidate
  // against), measured with the curve's proximity built here and built by
  // the measurement: the same report to the bit.
  auto curve = spiral();
  BSplineFitOptions options;
  options.tolerance = 0.01;
  NurbsCurve fitted = fitBSpline(*curve, options).spline;
  DeviationOptions measurement{1e-5};
  CurveProximity proximity(*curve, measurement.accuracy);
  CurveDeviationReport own = measureCurveDeviation(fitted, *curve, measurement);
  CurveDeviationReport given = measureCurveDeviation(fitted, *curve, proximity, measurement);
  EXPECT_GT(own.maxDeviation(), 0.0);
  EXPECT_EQ(own.approximationToCurve.distance, given.approximationToCurve.distance);
  EXPECT_EQ(own.approximationToCurve.parameter, given.approximationToCurve.parameter);
  EXPECT_EQ(own.curveToApproximation.distance, given.curveToApproximation.distance);
  EXPECT_EQ(own.curveToApproximation.targetParameter, given.curveToApproximation.targetParameter);
}

} // namespace
} // namespace cncc::geom
