#include "cncc/geom/bspline_basis.h"

#include <gtest/gtest.h>

#include <vector>

namespace cncc::geom {
namespace {

// A non-uniform knot vector with a double knot, for degrees 2..5.
KnotVector irregularKnots(int degree) {
  std::vector<double> knots(static_cast<std::size_t>(degree + 1), 0.0);
  for (double k : {0.1, 0.35, 0.35, 0.6, 0.9})
    knots.push_back(k);
  knots.insert(knots.end(), static_cast<std::size_t>(degree + 1), 1.0);
  return KnotVector(knots, degree);
}

// Basis function i of the whole spline (zero outside its support) at t.
double basisFunction(const KnotVector& knots, int i, double t) {
  int span = knots.findSpan(t);
  int j = i - (span - knots.degree());
  if (j < 0 || j > knots.degree())
    return 0.0;
  return basisFunctions(knots, span, t)[j];
}

TEST(BSplineBasis, PartitionOfUnityAndNonNegativity) {
  for (int degree = 2; degree <= 5; ++degree) {
    KnotVector knots = irregularKnots(degree);
    for (int i = 0; i <= 1000; ++i) {
      double t = i / 1000.0;
      BasisValues n = basisFunctions(knots, knots.findSpan(t), t);
      EXPECT_NEAR(n.sum(), 1.0, 1e-14) << "degree " << degree << " t " << t;
      EXPECT_GE(n.minCoeff(), -1e-15);
    }
  }
}

TEST(BSplineBasis, QuadraticUniformValuesAtSpanMiddle) {
  // Uniform quadratic B-spline pieces at the middle of a span: 1/8, 3/4, 1/8.
  KnotVector knots({0, 1, 2, 3, 4, 5}, 2);
  BasisValues n = basisFunctions(knots, 2, 2.5);
  EXPECT_NEAR(n[0], 0.125, 1e-15);
  EXPECT_NEAR(n[1], 0.75, 1e-15);
  EXPECT_NEAR(n[2], 0.125, 1e-15);
}

TEST(BSplineBasis, DerivativeRowZeroEqualsTheBasisFunctions) {
  KnotVector knots = irregularKnots(3);
  for (double t : {0.0, 0.05, 0.2, 0.35, 0.5, 0.77, 1.0}) {
    int span = knots.findSpan(t);
    BasisDerivatives d = basisFunctionDerivatives(knots, span, t, 2);
    BasisValues n = basisFunctions(knots, span, t);
    for (int j = 0; j <= 3; ++j)
      EXPECT_NEAR(d(0, j), n[j], 1e-15);
  }
}

TEST(BSplineBasis, DerivativesMatchCentralDifferencesAndSumToZero) {
  for (int degree = 2; degree <= 5; ++degree) {
    KnotVector knots = irregularKnots(degree);
    const double h = 1e-5;
    for (double t : {0.05, 0.2, 0.3, 0.45, 0.7, 0.95}) {
      int span = knots.findSpan(t);
      BasisDerivatives d = basisFunctionDerivatives(knots, span, t, 2);
      EXPECT_NEAR(d.row(1).sum(), 0.0, 1e-10);
      EXPECT_NEAR(d.row(2).sum(), 0.0, 1e-8);
      for (int j = 0; j <= degree; ++j) {
        int i = span - degree + j;
        double fPlus = basisFunction(knots, i, t + h), fMinus = basisFunction(knots, i, t - h);
        double f = basisFunction(knots, i, t);
        double first = (fPlus - fMinus) / (2 * h);
        double second = (fPlus - 2 * f + fMinus) / (h * h);
        EXPECT_NEAR(d(1, j), first, 1e-6 * (1 + std::fabs(first)));
        EXPECT_NEAR(d(2, j), second, 1e-3 * (1 + std::fabs(second)));
      }
    }
  }
}

TEST(BSplineBasis, DerivativesBeyondTheDegreeAreZero) {
  KnotVector knots = irregularKnots(2);
  BasisDerivatives d = basisFunctionDerivatives(knots, knots.findSpan(0.5), 0.5, 4);
  ASSERT_EQ(d.rows(), 5);
  EXPECT_EQ(d.row(3).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(d.row(4).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_GT(d.row(2).cwiseAbs().maxCoeff(), 0.0);
}

TEST(BSplineBasis, BezierBasisIsBernstein) {
  KnotVector knots({0, 0, 0, 0, 1, 1, 1, 1}, 3);
  double t = 0.3, s = 1 - t;
  BasisValues n = basisFunctions(knots, 3, t);
  EXPECT_NEAR(n[0], s * s * s, 1e-15);
  EXPECT_NEAR(n[1], 3 * t * s * s, 1e-15);
  EXPECT_NEAR(n[2], 3 * t * t * s, 1e-15);
  EXPECT_NEAR(n[3], t * t * t, 1e-15);
}

} // namespace
} // namespace cncc::geom
