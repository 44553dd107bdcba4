// A chord that crosses a corner of the curve close to its own end: the
// corner's distance from the chord is measured, however near the end it
// lies (a pocket wall's concave corner between two offsets: the samples on
// either side of it turn too little to be sampled more finely, and the
// curve's bulge away from the corner is the larger sampled peak).
#include "cncc/geom/composite_curve.h"
#include "cncc/geom/discretisation.h"
#include "cncc/geom/line_arc_curves.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

namespace cncc::geom {
namespace {

// A flat arc 10 mm long (sagitta 0.0125 mm) ending at a corner, where a
// line turns back sharply.
CompositeCurve arcThenCorner() {
  auto arc = std::make_shared<ArcCurve>(Eigen::Vector2d(0, -1000), 1000,
                                        std::numbers::pi / 2 + 0.005, -0.01, 0.0, 0.0);
  Eigen::Vector3d corner = arc->point(arc->domain().t1);
  auto line = std::make_shared<LineCurve>(corner, corner + Eigen::Vector3d(-0.7, -0.7, 0));
  return CompositeCurve({arc, line}, 1e-9);
}

// The largest distance of the curve from the chord over [ta, tb], by brute force.
double bruteDeviation(const Curve& curve, double ta, double tb) {
  Eigen::Vector3d a = curve.point(ta);
  Eigen::Vector3d chord = curve.point(tb) - a;
  double largest = 0;
  for (int i = 0; i <= 200000; ++i) {
    Eigen::Vector3d p = curve.point(ta + (tb - ta) * i / 200000);
    double along = std::clamp((p - a).dot(chord) / chord.squaredNorm(), 0.0, 1.0);
    largest = std::max(largest, (p - a - along * chord).norm());
  }
  return largest;
}

TEST(ChordAcrossCorner, TheCornersDistanceIsTheDeviation) {
  CompositeCurve path = arcThenCorner();
  double corner = path.breakpoints()[1];
  double tb = corner + 0.03;
  double expected = bruteDeviation(path, 0.0, tb);
  ASSERT_GT(expected, 0.015); // the corner's, beyond the arc's bulge
  EXPECT_NEAR(chordDeviation(path, 0.0, tb), expected, 1e-4);
}

TEST(ChordAcrossCorner, ChordsKeepTheToleranceAtTheCorner) {
  CompositeCurve path = arcThenCorner();
  CurveSamples samples = discretiseByChordTolerance(path, 0.015, 1000);
  for (std::size_t i = 1; i < samples.parameters.size(); ++i) {
    EXPECT_LE(bruteDeviation(path, samples.parameters[i - 1], samples.parameters[i]), 0.015 + 1e-6)
        << i;
  }
}

} // namespace
} // namespace cncc::geom
