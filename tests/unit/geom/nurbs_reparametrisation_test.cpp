// The linear-rational reparametrisation of a NURBS: the same points at the
// mapped parameters, the weights' ratios changed; and the weights brought
// into a range (Sinumerik's PW) when some lambda does it.
#include "cncc/geom/nurbs_reparametrisation.h"

#include "cncc/geom/geometry_error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace cncc::geom {
namespace {

// A clamped cubic over [0, 4] with uneven knots and weights.
NurbsCurve cubic(double middleWeight) {
  return NurbsCurve(
      KnotVector({0, 0, 0, 0, 0.7, 1.9, 2.5, 4, 4, 4, 4}, 3),
      {{0, 0, 0}, {10, 20, 1}, {30, 25, 0}, {40, 0, -2}, {60, 10, 0}, {70, 30, 0}, {90, 0, 0}},
      {1, 0.8, 1.5, 1, 2, middleWeight, 1});
}

TEST(NurbsReparametrisation, SamePointsAtTheMappedParameters) {
  NurbsCurve curve = cubic(5);
  for (double lambda : {0.05, 0.5, 1.0, 3.0, 40.0}) {
    NurbsCurve mapped = reparametrised(curve, lambda);
    EXPECT_EQ(mapped.domain().t0, 0);
    EXPECT_EQ(mapped.domain().t1, 4);
    for (int k = 0; k <= 40; ++k) {
      double t = 4.0 * k / 40;
      double s = reparametrisedParameter(curve, lambda, t);
      EXPECT_LT((mapped.point(s) - curve.point(t)).norm(), 1e-9) << lambda << " " << t;
    }
    // The control points stay; the ratios of the weights do not (lambda != 1).
    EXPECT_EQ(mapped.controlPoints(), curve.controlPoints());
    double before = curve.weights()[5] / curve.weights()[1];
    double after = mapped.weights()[5] / mapped.weights()[1];
    if (lambda != 1.0) {
      EXPECT_GT(std::abs(after / before - 1), 1e-3) << lambda;
    }
  }
}

TEST(NurbsReparametrisation, WeightsWithinScaleWhenThatIsEnough) {
  NurbsCurve scaled(cubic(2).knots(), cubic(2).controlPoints(), {2, 1.6, 3, 2, 4, 4, 2});
  std::optional<FittingWeights> fitting = weightsWithin(scaled, {1e-4, 3});
  ASSERT_TRUE(fitting);
  EXPECT_EQ(fitting->lambda, 1);
  EXPECT_EQ(fitting->curve.weights().front(), 1);
  EXPECT_DOUBLE_EQ(fitting->curve.weights()[4], 2);
}

TEST(NurbsReparametrisation, WeightsWithinReparametrisesOutOfRangeWeights) {
  NurbsCurve curve = cubic(5); // 5 relative to the first: beyond 3
  std::optional<FittingWeights> fitting = weightsWithin(curve, {1e-4, 3});
  ASSERT_TRUE(fitting);
  EXPECT_NE(fitting->lambda, 1);
  const std::vector<double>& weights = fitting->curve.weights();
  EXPECT_EQ(weights.front(), 1);
  EXPECT_LE(*std::max_element(weights.begin(), weights.end()), 3);
  EXPECT_GE(*std::min_element(weights.begin(), weights.end()), 1e-4);
  for (int k = 0; k <= 40; ++k) {
    double t = 4.0 * k / 40;
    double s = reparametrisedParameter(curve, fitting->lambda, t);
    EXPECT_LT((fitting->curve.point(s) - curve.point(t)).norm(), 1e-9) << t;
  }
}

TEST(NurbsReparametrisation, NothingWhenNoLambdaFits) {
  // A middle weight a millionth of its neighbours' cannot be raised to PW's
  // range while the last stays within it.
  NurbsCurve curve(cubic(1).knots(), cubic(1).controlPoints(), {1, 1, 1, 1e-6, 1, 1, 1});
  EXPECT_FALSE(weightsWithin(curve, {1e-4, 3}));
}

} // namespace
} // namespace cncc::geom
