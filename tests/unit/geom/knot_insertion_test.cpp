#include "cncc/geom/geometry_error.h"
#include "cncc/geom/nurbs_curve.h"
#include "test_curves.h"

#include <gtest/gtest.h>

namespace cncc::geom {
namespace {

using testing::parameterGrid;

void expectSameCurve(const NurbsCurve& a, const NurbsCurve& b, double tolerance) {
  ASSERT_EQ(a.domain().t0, b.domain().t0);
  ASSERT_EQ(a.domain().t1, b.domain().t1);
  for (double t : parameterGrid(a, 1000)) {
    EXPECT_LT((a.point(t) - b.point(t)).norm(), tolerance) << t;
    EXPECT_LT((a.derivative(t) - b.derivative(t)).norm(), 1e3 * tolerance) << t;
  }
}

TEST(KnotInsertion, LeavesTheSProfileUnchanged) {
  NurbsCurve curve = testing::sProfile({1, 3, 1, 1, 1, 3, 1});
  NurbsCurve refined = insertKnot(curve, 0.4);
  EXPECT_EQ(refined.controlPoints().size(), curve.controlPoints().size() + 1);
  EXPECT_EQ(refined.knots().multiplicity(0.4), 1);
  expectSameCurve(curve, refined, 1e-12);
}

TEST(KnotInsertion, AtAnExistingKnotAndSeveralTimes) {
  NurbsCurve curve = testing::sProfile();
  NurbsCurve twice = insertKnot(curve, 0.5, 2);
  EXPECT_EQ(twice.knots().multiplicity(0.5), 3);
  EXPECT_EQ(twice.controlPoints().size(), curve.controlPoints().size() + 2);
  expectSameCurve(curve, twice, 1e-12);
  // At full multiplicity the curve passes through a control point.
  EXPECT_LT((twice.point(0.5) - twice.controlPoints()[4]).norm(), 1e-12);
}

TEST(KnotInsertion, LeavesTheRationalCircleUnchanged) {
  NurbsCurve circle = testing::unitCircle();
  NurbsCurve refined = insertKnot(insertKnot(circle, 0.1), 0.6, 2);
  expectSameCurve(circle, refined, 1e-14);
  for (double t : parameterGrid(refined, 500))
    EXPECT_NEAR(refined.point(t).norm(), 1.0, 1e-14);
}

TEST(KnotInsertion, RejectsKnotsOutsideTheDomainOrBeyondTheDegree) {
  NurbsCurve curve = testing::sProfile();
  EXPECT_THROW(insertKnot(curve, 0.0), GeometryError);
  EXPECT_THROW(insertKnot(curve, 1.5), GeometryError);
  EXPECT_THROW(insertKnot(curve, 0.5, 3), GeometryError); // 0.5 is already a knot
  EXPECT_THROW(insertKnot(curve, 0.3, 0), GeometryError);
}

} // namespace
} // namespace cncc::geom
