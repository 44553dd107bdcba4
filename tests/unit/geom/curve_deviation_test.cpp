// Deviation between two curves.

#include "cncc/geom/curve_deviation.h"
#include "cncc/geom/evaluation_budget.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/geom/line_arc_curves.h"
#include "test_curves.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace cncc::geom {
namespace {

constexpr double kPi = std::numbers::pi;

TEST(CurveDeviation, ConcentricArcsAreTheirRadiusApart) {
  ArcCurve inner({1, 2}, 5.0, 0.0, kPi);
  ArcCurve outer({1, 2}, 5.01, 0.0, kPi);
  CurveDeviationReport report = measureCurveDeviation(inner, outer, {1e-7});
  EXPECT_NEAR(report.approximationToCurve.distance, 0.01, 1e-12);
  EXPECT_NEAR(report.curveToApproximation.distance, 0.01, 1e-12);
  EXPECT_NEAR(report.maxDeviation(), 0.01, 1e-12);
}

TEST(CurveDeviation, BothDirectionsCatchAPathThatStopsShort) {
  LineCurve whole({0, 0, 0}, {10, 0, 0});
  LineCurve part({0, 0.001, 0}, {7, 0.001, 0});
  CurveDeviationReport report = measureCurveDeviation(part, whole, {1e-7});
  // The part stays near the whole line, but the last 3 mm of it are not covered.
  EXPECT_NEAR(report.approximationToCurve.distance, 0.001, 1e-12);
  EXPECT_NEAR(report.curveToApproximation.distance, std::hypot(3.0, 0.001), 1e-9);
  EXPECT_NEAR(report.curveToApproximation.parameter, 10.0, 1e-9);
}

TEST(CurveDeviation, FindsANarrowBumpBetweenSamples) {
  // A line against a curve with a bump of height 0.002 and width 0.05 around x = 3.3.
  auto bump = [](double x) { return 0.002 * std::exp(-std::pow((x - 3.3) / 0.05, 2)); };
  FunctionCurve bumpy({0.0, 10.0}, [&](double t) { return Eigen::Vector3d(t, bump(t), 0.0); });
  LineCurve line({0, 0, 0}, {10, 0, 0});
  CurveDeviationReport report = measureCurveDeviation(line, bumpy, {1e-6});
  EXPECT_NEAR(report.maxDeviation(), 0.002, 1e-6);
  EXPECT_NEAR(report.curveToApproximation.parameter, 3.3, 1e-3);
}

TEST(CurveDeviation, ABudgetedCurveIsAskedItsPointsBeforeTheApproximation) {
  ArcCurve arc({0, 0}, 10.0, 0.0, kPi);
  ArcCurve approximation({0, 0.001}, 10.0, 0.0, kPi);
  constexpr double kAccuracy = 1e-7;
  auto measured = [&](std::size_t limit) {
    BudgetedCurve curve(arc, limit);
    CurveProximity proximity(curve, kAccuracy);
    return measureCurveDeviation(approximation, curve, proximity, {kAccuracy}).maxDeviation();
  };
  // Every point the measurement asks of the curve, the proximity's first.
  BudgetedCurve counted(arc, std::numeric_limits<std::size_t>::max());
  CurveProximity proximity(counted, kAccuracy);
  std::size_t forProximity = counted.used();
  double deviation =
      measureCurveDeviation(approximation, counted, proximity, {kAccuracy}).maxDeviation();
  std::size_t all = counted.used();
  EXPECT_NEAR(deviation, 0.001, 1e-9);
  // Refused exactly past them all.
  EXPECT_EQ(measured(all), deviation);
  EXPECT_THROW(measured(all - 1), EvaluationBudgetExceeded);
  // Refused within the curve's own samples: the approximation is asked nothing.
  BudgetedCurve curve(arc, forProximity + 100);
  BudgetedCurve approximationAsked(approximation, std::numeric_limits<std::size_t>::max());
  CurveProximity curveProximity(curve, kAccuracy);
  EXPECT_THROW(measureCurveDeviation(approximationAsked, curve, curveProximity, {kAccuracy}),
               EvaluationBudgetExceeded);
  EXPECT_EQ(approximationAsked.used(), 0u);
}

TEST(CurveDeviation, LargestDistanceOverAnInterval) {
  NurbsCurve quarter = testing::quarterCircle();
  CurveProximity circle(quarter, 1e-7);
  ArcCurve bigger({0, 0}, 1.5, 0.0, 0.5 * kPi);
  CurveDistanceWitness witness =
      largestDistanceToCurve(bigger, 0.0, bigger.length() / 2, circle, 16);
  EXPECT_NEAR(witness.distance, 0.5, 1e-12);
  EXPECT_THROW(largestDistanceToCurve(bigger, 1.0, 0.0, circle), GeometryError);
}

} // namespace
} // namespace cncc::geom
