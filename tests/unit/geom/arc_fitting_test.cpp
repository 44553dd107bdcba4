// Biarc fitting: tangent-continuous arcs and lines within a tolerance of a curve.

#include "cncc/geom/arc_fitting.h"
#include "cncc/geom/curve_deviation.h"
#include "cncc/geom/deviation.h"
#include "cncc/geom/geometry_error.h"
#include "test_curves.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace cncc::geom {
namespace {

constexpr double kPi = std::numbers::pi;

// Checks what every fit promises, independently of the fitting code: joined moves,
// arcs of at most 180 degrees whose centre is at their radius from both ends, tangent
// continuity (where the curve has no corner), and the deviation measured again, also
// by a dense polyline through the path.
void expectValidFit(const ArcFit& fit, const Curve& curve, double tolerance) {
  ASSERT_FALSE(fit.segments.empty());
  ParameterRange range = curve.domain();
  EXPECT_LT((fit.segments.front().start - curve.point(range.t0)).norm(), 1e-12);
  EXPECT_LT((fit.segments.back().end - curve.point(range.t1)).norm(), 1e-12);
  std::vector<Eigen::Vector3d> dense;
  for (std::size_t i = 0; i < fit.segments.size(); ++i) {
    const ArcSegment& s = fit.segments[i];
    if (s.kind == ArcSegmentKind::Arc) {
      EXPECT_LE(std::fabs(s.sweep), kPi + 1e-12) << i;
      EXPECT_NEAR((s.start.head<2>() - s.centre).norm(), s.radius, 1e-9 * s.radius) << i;
      EXPECT_NEAR((s.end.head<2>() - s.centre).norm(), s.radius, 1e-9 * s.radius) << i;
      EXPECT_EQ(s.direction,
                s.sweep > 0 ? ArcDirection::CounterClockwise : ArcDirection::Clockwise);
    }
    std::shared_ptr<const Curve> piece = s.curve();
    ParameterRange domain = piece->domain();
    for (int k = 0; k < 64; ++k)
      dense.push_back(piece->point(domain.t0 + domain.length() * k / 64));
    if (i + 1 < fit.segments.size()) {
      const ArcSegment& next = fit.segments[i + 1];
      EXPECT_LT((s.end - next.start).norm(), 1e-12) << i;
      Eigen::Vector3d out = piece->derivative(domain.t1).normalized();
      Eigen::Vector3d in = next.curve()->derivative(next.curve()->domain().t0).normalized();
      EXPECT_LT((out - in).norm(), 1e-6) << "tangent jump after move " << i;
    }
  }
  dense.push_back(fit.segments.back().end);
  EXPECT_LE(fit.deviation, tolerance);
  EXPECT_LE(measureCurveDeviation(fit.path(), curve, {tolerance * 1e-3}).maxDeviation(), tolerance);
  // 64 points per move sag at most r (1 - cos(pi / 128)) = 3e-4 r from an arc.
  double sag = 0.0;
  for (const ArcSegment& s : fit.segments)
    sag = std::max(sag, s.radius * (1.0 - std::cos(std::fabs(s.sweep) / 128.0)));
  EXPECT_LE(measureDeviation(dense, curve, {tolerance * 1e-3}).maxDeviation(), tolerance + sag);
}

TEST(ArcFitting, QuarterCircleIsOneArc) {
  NurbsCurve quarter = testing::quarterCircle();
  ArcFit fit = fitArcs(quarter, {0.001});
  expectValidFit(fit, quarter, 0.001);
  ASSERT_EQ(fit.segments.size(), 1u);
  const ArcSegment& arc = fit.segments[0];
  EXPECT_EQ(arc.kind, ArcSegmentKind::Arc);
  EXPECT_NEAR(arc.radius, 1.0, 1e-12);
  EXPECT_LT(arc.centre.norm(), 1e-12);
  EXPECT_NEAR(arc.sweep, 0.5 * kPi, 1e-12);
  EXPECT_EQ(arc.direction, ArcDirection::CounterClockwise);
  EXPECT_LT(fit.deviation, 1e-12);
}

TEST(ArcFitting, FullCircleIsTwoHalfCircles) {
  NurbsCurve circle = testing::unitCircle();
  ArcFit fit = fitArcs(circle, {0.01});
  expectValidFit(fit, circle, 0.01);
  ASSERT_EQ(fit.segments.size(), 2u);
  for (const ArcSegment& arc : fit.segments) {
    EXPECT_EQ(arc.kind, ArcSegmentKind::Arc);
    EXPECT_NEAR(arc.radius, 1.0, 1e-12);
    EXPECT_NEAR(arc.sweep, kPi, 1e-9);
  }
}

TEST(ArcFitting, ClockwiseArcKeepsItsDirectionAndRadius) {
  ArcCurve arc({3, -2}, 5.0, 0.3, -2.0 * kPi / 3.0, 1.5);
  ArcFit fit = fitArcs(arc, {0.001});
  expectValidFit(fit, arc, 0.001);
  ASSERT_EQ(fit.segments.size(), 1u);
  EXPECT_EQ(fit.segments[0].direction, ArcDirection::Clockwise);
  EXPECT_NEAR(fit.segments[0].radius, 5.0, 1e-9);
  EXPECT_LT((fit.segments[0].centre - Eigen::Vector2d(3, -2)).norm(), 1e-9);
  EXPECT_NEAR(fit.segments[0].start.z(), 1.5, 1e-12);
}

TEST(ArcFitting, StraightPartsBecomeLinesAndCornersStay) {
  // A line, a tangent quarter arc, then a corner into another line.
  auto first = std::make_shared<LineCurve>(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(10, 0, 0));
  auto bend = std::make_shared<ArcCurve>(Eigen::Vector2d(10, 4), 4.0, -0.5 * kPi, 0.5 * kPi);
  auto last = std::make_shared<LineCurve>(Eigen::Vector3d(14, 4, 0), Eigen::Vector3d(20, 4, 0));
  CompositeCurve path({first, bend, last});
  ArcFit fit = fitArcs(path, {0.01});
  ASSERT_EQ(fit.segments.size(), 3u);
  EXPECT_EQ(fit.segments[0].kind, ArcSegmentKind::Line);
  EXPECT_EQ(fit.segments[1].kind, ArcSegmentKind::Arc);
  EXPECT_NEAR(fit.segments[1].radius, 4.0, 1e-9);
  EXPECT_EQ(fit.segments[2].kind, ArcSegmentKind::Line);
  EXPECT_LT(fit.deviation, 1e-9);
  EXPECT_EQ(fit.arcCount(), 1u);
  EXPECT_EQ(fit.lineCount(), 2u);
}

TEST(ArcFitting, SpiralNeedsAtMostAThirdOfTheChords) {
  // Reference case 2: 90 chords at 5 um.
  PolarCurve spiral = testing::archimedeanSpiral();
  ArcFit fit = fitArcs(spiral, {0.005});
  expectValidFit(fit, spiral, 0.005);
  RecordProperty("arcs", int(fit.segments.size()));
  EXPECT_LE(fit.segments.size(), 30u);
}

TEST(ArcFitting, PolarContourAndSProfile) {
  PolarCurve contour = testing::polarContour();
  ArcFit contourFit = fitArcs(contour, {0.01});
  expectValidFit(contourFit, contour, 0.01);
  RecordProperty("polarContour", int(contourFit.segments.size()));
  EXPECT_LT(contourFit.segments.size(), 181u / 2); // chords: 181
  NurbsCurve profile = testing::sProfile({1, 1, 1, 1, 1, 3, 1});
  ArcFit profileFit = fitArcs(profile, {0.01});
  expectValidFit(profileFit, profile, 0.01);
  RecordProperty("sProfile", int(profileFit.segments.size()));
  EXPECT_LT(profileFit.segments.size(), 115u / 2); // chords: 115
}

// The tolerances the gcode target fits with: the promise less the rounding of
// four decimals.
TEST(ArcFitting, SProfileAtPrintingTolerances) {
  NurbsCurve profile = testing::sProfile({1, 1, 1, 1, 1, 3, 1});
  for (double tolerance : {0.01 - 2.2e-4, 0.005, 0.002}) {
    SCOPED_TRACE(tolerance);
    expectValidFit(fitArcs(profile, {tolerance}), profile, tolerance);
  }
}

// A nearly straight stretch of the S profile is an arc of some 18 m radius,
// whose centre offsets a reader of 8 digits at 4 decimals cannot take: with
// a largest radius the fit cuts it as lines, still within the tolerance.
TEST(ArcFitting, ArcsOverTheLargestRadiusAreLines) {
  NurbsCurve profile = testing::sProfile({1, 1, 1, 1, 1, 3, 1});
  double tolerance = 0.01 - 2.2e-4;
  auto largestRadius = [](const ArcFit& fit) {
    double largest = 0.0;
    for (const ArcSegment& segment : fit.segments) {
      largest = segment.kind == ArcSegmentKind::Arc ? std::max(largest, segment.radius) : largest;
    }
    return largest;
  };
  ASSERT_GT(largestRadius(fitArcs(profile, {tolerance})), 9999.9999);
  ArcFit bounded = fitArcs(profile, {tolerance, 9999.9999});
  EXPECT_LE(largestRadius(bounded), 9999.9999);
  EXPECT_GT(bounded.lineCount(), 0u);
  EXPECT_LE(bounded.deviation, tolerance);
  EXPECT_LE(measureCurveDeviation(bounded.path(), profile, {tolerance * 1e-3}).maxDeviation(),
            tolerance);
}

TEST(ArcFitting, RejectsCurvesOutOfPlaneAndBadTolerances) {
  ArcCurve helix({0, 0}, 2.0, 0.0, kPi, 0.0, 3.0);
  EXPECT_TRUE(findArcFittingProblem(helix));
  EXPECT_THROW(fitArcs(helix, {0.01}), GeometryError);
  EXPECT_FALSE(findArcFittingProblem(testing::polarContour()));
  EXPECT_THROW(fitArcs(testing::polarContour(), {0.0}), GeometryError);
}

} // namespace
} // namespace cncc::geom
