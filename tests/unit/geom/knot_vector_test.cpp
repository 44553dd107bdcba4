#include "cncc/geom/geometry_error.h"
#include "cncc/geom/knot_vector.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace cncc::geom {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

TEST(KnotVector, ClampedUniformRepeatsEndsAndSpacesInteriorEvenly) {
  KnotVector knots = KnotVector::clampedUniform(3, 7);
  EXPECT_THAT(knots.values(), ElementsAre(0, 0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1, 1));
  EXPECT_EQ(knots.controlPointCount(), 7);
  EXPECT_TRUE(knots.isClamped());
  EXPECT_EQ(knots.domain().t0, 0.0);
  EXPECT_EQ(knots.domain().t1, 1.0);
}

TEST(KnotVector, ClampedUniformOverAnotherRange) {
  KnotVector knots = KnotVector::clampedUniform(2, 4, 10.0, 20.0);
  EXPECT_THAT(knots.values(), ElementsAre(10, 10, 10, 15, 20, 20, 20));
}

TEST(KnotVector, FindSpanReturnsTheHalfOpenSpanHoldingT) {
  KnotVector knots({0, 0, 0, 1, 2, 2, 3, 4, 4, 4}, 2);
  EXPECT_EQ(knots.findSpan(0.0), 2);
  EXPECT_EQ(knots.findSpan(0.5), 2);
  EXPECT_EQ(knots.findSpan(1.0), 3);
  EXPECT_EQ(knots.findSpan(1.99), 3);
  EXPECT_EQ(knots.findSpan(2.0), 5); // the double knot 2 closes span 4 (empty)
  EXPECT_EQ(knots.findSpan(3.5), 6);
  EXPECT_EQ(knots.findSpan(4.0), 6); // the end belongs to the last span
  EXPECT_EQ(knots.findSpan(9.0), 6); // clamped into the domain
  EXPECT_EQ(knots.findSpan(-1.0), 2);
}

TEST(KnotVector, FindSpanOnAnUnclampedVector) {
  KnotVector knots({0, 1, 2, 3, 4, 5, 6, 7}, 3);
  EXPECT_EQ(knots.domain().t0, 3.0);
  EXPECT_EQ(knots.domain().t1, 4.0);
  EXPECT_EQ(knots.findSpan(3.0), 3);
  EXPECT_EQ(knots.findSpan(4.0), 3);
  EXPECT_FALSE(knots.isClamped());
}

TEST(KnotVector, BreakpointsAreDistinctKnotsInTheDomain) {
  KnotVector knots({0, 0, 0, 1, 2, 2, 3, 4, 4, 4}, 2);
  EXPECT_THAT(knots.breakpoints(), ElementsAre(0, 1, 2, 3, 4));
  EXPECT_EQ(knots.multiplicity(2.0), 2);
  EXPECT_EQ(knots.multiplicity(0.0), 3);
  EXPECT_EQ(knots.multiplicity(0.5), 0);
}

TEST(KnotVector, RejectsDecreasingKnots) {
  EXPECT_THAT(KnotVector::findProblem({0, 0, 0, 2, 1, 3, 3, 3}, 2).value_or(""),
              HasSubstr("must not decrease"));
  EXPECT_THROW(KnotVector({0, 0, 0, 2, 1, 3, 3, 3}, 2), GeometryError);
}

TEST(KnotVector, RejectsTooFewKnotsBadDegreeAndNonFiniteKnots) {
  EXPECT_THAT(KnotVector::findProblem({0, 0, 1, 1}, 2).value_or(""), HasSubstr("at least 6"));
  EXPECT_THAT(KnotVector::findProblem({0, 1}, 0).value_or(""), HasSubstr("degree 0"));
  EXPECT_THAT(KnotVector::findProblem({0, 0, 1, 1}, kMaxDegree + 1).value_or(""),
              HasSubstr("outside"));
  EXPECT_THAT(KnotVector::findProblem({0, 0, NAN, 1}, 1).value_or(""), HasSubstr("finite"));
}

TEST(KnotVector, RejectsAnInteriorKnotRepeatedMoreThanTheDegree) {
  EXPECT_THAT(KnotVector::findProblem({0, 0, 0, 1, 1, 1, 2, 2, 2}, 2).value_or(""),
              HasSubstr("repeats 3 times"));
  EXPECT_FALSE(KnotVector::findProblem({0, 0, 0, 1, 1, 2, 2, 2}, 2).has_value());
}

TEST(KnotVector, RejectsAnEmptyDomain) {
  EXPECT_THAT(KnotVector::findProblem({1, 1, 1, 1}, 1).value_or(""), HasSubstr("empty"));
}

TEST(KnotVector, ClampedUniformRejectsTooFewControlPoints) {
  EXPECT_THROW(KnotVector::clampedUniform(3, 3), GeometryError);
}

} // namespace
} // namespace cncc::geom
