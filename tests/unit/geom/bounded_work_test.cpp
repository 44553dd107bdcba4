// The limits on work that grows with the input (issue 18): the estimate of
// a discretisation, the walk's chord limit, the arc length's split budget
// and the deviation measurement's work limit.
#include "cncc/geom/arc_length.h"
#include "cncc/geom/deviation.h"
#include "cncc/geom/discretisation.h"
#include "cncc/geom/function_curve.h"
#include "cncc/geom/line_arc_curves.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace cncc::geom {
namespace {

using std::numbers::pi;

TEST(EstimateDiscretisation, IsNearTheWalksChordCount) {
  ArcCurve circle({1, 2}, 10.0, 0.0, 2 * pi);
  DiscretisationEstimate estimate = estimateDiscretisation(circle, 0.01);
  double walked = static_cast<double>(discretiseByChordTolerance(circle, 0.01).chordCount());
  // A circle of radius 10 at 0.01: chords of sqrt(8 * 0.01 * 10) mm, 70 of them.
  EXPECT_NEAR(estimate.chords, walked, 0.1 * walked);
  EXPECT_NEAR(estimate.largestCoordinate, 12.0, 1e-6);
  EXPECT_EQ(estimateDiscretisation(circle, std::nan("")).chords, 0.0);
}

TEST(EstimateDiscretisation, OfAnOffsetIsTheOffsetCirclesEstimate) {
  // A counter-clockwise circle of radius 10: its offset 4 to the left is the
  // circle of radius 6, 4 to the right the circle of radius 14.
  ArcCurve circle({1, 2}, 10.0, 0.0, 2 * pi);
  for (double offset : {4.0, -4.0}) {
    ArcCurve offsetCircle({1, 2}, 10.0 - offset, 0.0, 2 * pi);
    EXPECT_NEAR(estimateDiscretisation(circle, 0.01, offset).chords,
                estimateDiscretisation(offsetCircle, 0.01).chords, 1e-6)
        << offset;
  }
  EXPECT_NEAR(estimateDiscretisation(circle, 0.01, 0.0).chords,
              estimateDiscretisation(circle, 0.01).chords, 1e-12);
}

TEST(EstimateDiscretisation, SeesAHugeCurveCheaply) {
  ArcCurve huge({0, 0}, 1e9, 0.0, 2 * pi);
  auto start = std::chrono::steady_clock::now();
  DiscretisationEstimate estimate = estimateDiscretisation(huge, 0.01);
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_GT(estimate.chords, 5e5);
  EXPECT_GE(estimate.largestCoordinate, 0.99e9);
  EXPECT_LT(seconds, 1.0);
}

TEST(DiscretiseByChordTolerance, StopsAtItsChordLimit) {
  ArcCurve circle({0, 0}, 10.0, 0.0, 2 * pi);
  try {
    discretiseByChordTolerance(circle, 1e-6, 50);
    FAIL() << "no ChordLimitExceeded";
  } catch (const ChordLimitExceeded& error) {
    EXPECT_EQ(error.limit, 50u);
  }
  EXPECT_LE(discretiseByChordTolerance(circle, 0.01, 200).chordCount(), 200u);
}

TEST(ArcLength, OfANoisySpeedEndsAtItsSplitBudget) {
  // A circle whose coordinates carry noise of 1e-9: no tolerance of 1e-12
  // can be met, and without the budget every interval would split 40 deep.
  auto noise = [](double t) { return 1e-9 * std::sin(1e7 * t); };
  FunctionCurve noisy = FunctionCurve::fromCoordinates(
      {0.0, 2 * pi}, [&](double t) { return std::cos(t) + noise(t); },
      [&](double t) { return std::sin(t) + noise(t); });
  auto start = std::chrono::steady_clock::now();
  double length = arcLength(noisy, 1e-12);
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_NEAR(length, 2 * pi, 1e-2);
  EXPECT_LT(seconds, 20.0);
}

TEST(MeasureDeviation, StopsAtItsWorkLimit) {
  ArcCurve circle({0, 0}, 50.0, 0.0, 2 * pi);
  // A path to and fro through the centre, where every sample of the circle
  // is as near as any other.
  std::vector<Eigen::Vector3d> polyline;
  for (int i = 0; i <= 200; ++i) {
    polyline.emplace_back(i % 2 == 0 ? -1.0 : 1.0, 0.01 * i, 0.0);
  }
  DeviationOptions options;
  options.accuracy = 1e-6;
  options.maximumWork = 1e5;
  EXPECT_THROW(measureDeviation(polyline, circle, options), MeasurementTooLarge);
  options.maximumWork = std::numeric_limits<double>::infinity();
  EXPECT_GT(measureDeviation(polyline, circle, options).maxDeviation(), 48.0);
}

// The work of measuring a six-turn path of 1 mm chords whose vertices are
// 0.00002 mm outside its circle (a helix seen in XY): the smallest power of
// ten that allows it.
double workOfAnEvenDeviation(double* deviation) {
  ArcCurve turns({0, 0}, 360.0, 0.0, 12 * pi);
  std::vector<Eigen::Vector3d> polyline;
  for (int i = 0; i <= 13600; ++i) {
    double angle = 12 * pi * i / 13600.0;
    polyline.emplace_back(360.00002 * std::cos(angle), 360.00002 * std::sin(angle), 0.0);
  }
  DeviationOptions options;
  options.accuracy = 1e-5;
  for (options.maximumWork = 1e5;; options.maximumWork *= 10) {
    try {
      *deviation = measureDeviation(polyline, turns, options).maxDeviation();
      return options.maximumWork;
    } catch (const MeasurementTooLarge&) {
    }
  }
}

TEST(MeasureDeviation, RefinesAnEvenDeviationAtAFewPeaks) {
  // Every chord's middle is a local maximum of the distance, all within the
  // sampling's margin of each other; refining each of them took minutes under
  // the sanitizers.
  double deviation = 0.0;
  double work = workOfAnEvenDeviation(&deviation);
  // The largest distance is at the chords' middles, inside the circle: their
  // sagitta (0.00034578 mm) less the 0.00002; refining every peak took 1e8.
  EXPECT_NEAR(deviation, 0.00032578, 5e-5);
  EXPECT_LE(work, 1e7);
}

} // namespace
} // namespace cncc::geom
