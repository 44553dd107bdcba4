// The step count of a rational Bezier span (cncc/lowering/rational_span_steps.h),
// run on doubles: the chords of that many uniform steps, measured on the
// true curve, stay within the budget for random spans and weights; the
// count is the classic one for equal weights, and below a bound of |C''|
// where the weights change fast.
#include "cncc/lowering/rational_span_steps.h"

#include "cncc/geom/discretisation.h"
#include "cncc/geom/nurbs_curve.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace cncc::ir::lowering {
namespace {

// A rational Bezier span of degree n: points b_j, weights w_j.
struct Span {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> weights;

  std::size_t degree() const { return points.size() - 1; }
  Eigen::Vector3d centre() const {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const Eigen::Vector3d& point : points) {
      sum += point;
    }
    return sum / static_cast<double>(points.size());
  }
  geom::NurbsCurve curve() const {
    std::vector<double> knots(points.size(), 0.0);
    knots.resize(2 * points.size(), 1.0);
    return geom::NurbsCurve(geom::KnotVector(knots, static_cast<int>(degree())), points, weights);
  }
};

class DoubleMath {
public:
  using Number = double;
  using Point = std::array<double, 4>;

  DoubleMath(const Span& span, Eigen::Vector3d centre) : span_(span), centre_(std::move(centre)) {}

  double constant(double value) { return value; }
  bool isZero(double value) { return value == 0; }
  double add(double a, double b) { return a + b; }
  double multiply(double a, double b) { return a * b; }
  double divide(double a, double b) { return a / b; }
  double squareRoot(double a) { return std::sqrt(a); }
  double larger(double a, double b) { return std::max(a, b); }
  double length(const Point& point) { return std::hypot(point[0], point[1], point[2]); }
  double weight(const Point& point) { return point[3]; }
  double weightTimes(const Point& point, double factor) { return std::abs(point[3]) * factor; }
  double sumOfSquaredWeights(const std::vector<Point>& points) {
    double sum = 0;
    for (const Point& point : points) {
      sum += point[3] * point[3];
    }
    return sum;
  }
  Point combination(const std::vector<double>& coefficients) {
    Point sum{0, 0, 0, 0};
    for (std::size_t j = 0; j < coefficients.size(); ++j) {
      double weight = span_.weights[j];
      Eigen::Vector3d offset = weight * (span_.points[j] - centre_);
      for (int c = 0; c < 3; ++c) {
        sum[static_cast<std::size_t>(c)] += coefficients[j] * offset[c];
      }
      sum[3] += coefficients[j] * weight;
    }
    return sum;
  }

private:
  const Span& span_;
  Eigen::Vector3d centre_;
};

// The fewest steps the bound allows (not rounded), its smallest weight and
// radius taken from the span's own control points.
double boundSteps(const Span& span, double budget, double stretch = 1) {
  Eigen::Vector3d centre = span.centre();
  double radius = 0;
  for (const Eigen::Vector3d& point : span.points) {
    radius = std::max(radius, (point - centre).norm());
  }
  double smallest = *std::min_element(span.weights.begin(), span.weights.end());
  DoubleMath math(span, centre);
  return rationalSpanSteps(math, span.degree(), 1 / (8 * budget), stretch, smallest, radius);
}

// The largest deviation from the curve of the chords of `steps` uniform steps.
double largestChordDeviation(const geom::Curve& curve, int steps) {
  double largest = 0;
  for (int k = 0; k < steps; ++k) {
    largest = std::max(largest, geom::chordDeviation(curve, static_cast<double>(k) / steps,
                                                     static_cast<double>(k + 1) / steps));
  }
  return largest;
}

TEST(RationalSpanSteps, ChordsOfTheCountStayWithinTheBudgetForRandomWeights) {
  std::mt19937 random(20261203);
  std::uniform_real_distribution<double> coordinate(-100, 100);
  std::uniform_real_distribution<double> logWeight(std::log(0.05), std::log(20.0));
  std::uniform_real_distribution<double> logBudget(std::log(0.01), std::log(1.0));
  std::uniform_int_distribution<int> degree(2, 5);
  int tightest = 0; // how often a chord uses more than a quarter of the budget
  double closest = 0;
  int measured = 0;
  for (int trial = 0; trial < 150; ++trial) {
    Span span;
    bool planar = trial % 3 != 0;
    for (int j = 0, n = degree(random); j <= n; ++j) {
      span.points.emplace_back(coordinate(random), coordinate(random),
                               planar ? 0.0 : coordinate(random));
      span.weights.push_back(std::exp(logWeight(random)));
    }
    double budget = std::exp(logBudget(random));
    double steps = boundSteps(span, budget);
    ASSERT_TRUE(std::isfinite(steps)) << "trial " << trial;
    int count = std::max(1, static_cast<int>(std::ceil(steps)));
    if (count > 5000) {
      continue; // extreme weights: too slow to measure here
    }
    ++measured;
    double deviation = largestChordDeviation(span.curve(), count);
    EXPECT_LE(deviation, budget) << "trial " << trial << ", " << count << " steps";
    tightest += deviation > budget / 4 ? 1 : 0;
    closest = std::max(closest, deviation / budget);
  }
  EXPECT_GT(measured, 100);
  // The bound is not vacuous: some counts come close to what the curve needs.
  EXPECT_GT(tightest, measured / 10) << "of " << measured;
  EXPECT_GT(closest, 0.7);
}

TEST(RationalSpanSteps, AStretchedSpanTakesTheStretchedCount) {
  Span span{{{0, 0, 0}, {10, 30, 0}, {40, -20, 0}, {50, 10, 0}}, {1, 6, 0.5, 2}};
  Span doubled = span;
  for (Eigen::Vector3d& point : doubled.points) {
    point *= 2;
  }
  EXPECT_NEAR(boundSteps(span, 0.01, 2), boundSteps(doubled, 0.01), 1e-9);
  int count = static_cast<int>(std::ceil(boundSteps(span, 0.01, 2)));
  EXPECT_LE(largestChordDeviation(doubled.curve(), count), 0.01);
}

TEST(RationalSpanSteps, EqualWeightsGiveTheClassicCountOfAPolynomial) {
  // A parabola with C'' = 2 (b0 - 2 b1 + b2) = (0, -8): a chord over a step
  // h is h^2 |C''| / 8 from the curve along y, so 10 steps for a budget of
  // 0.01 (slanted chords are a little closer).
  Span parabola{{{0, 0, 0}, {1, 2, 0}, {2, 0, 0}}, {3, 3, 3}};
  EXPECT_NEAR(boundSteps(parabola, 0.01), 10, 1e-9);
  EXPECT_LE(largestChordDeviation(parabola.curve(), 10), 0.01);
  EXPECT_GT(largestChordDeviation(parabola.curve(), 10), 0.0095);
  EXPECT_GT(largestChordDeviation(parabola.curve(), 9), 0.01);
}

TEST(RationalSpanSteps, FastChangingWeightsNeedFewerStepsThanABoundOfTheSecondDerivative) {
  // The S-profile's last span at w6 = 8 (Bezier form): the speed along the
  // curve changes fast, |C''| is mostly along the curve.
  Span span{{{125.4424, 43.7023, 0}, {130.2433, 35.4782, 0}, {132.4671, 35.1148, 0}, {175, 150, 0}},
            {2.75, 4.5, 8, 1}};
  double budget = 0.01;
  geom::NurbsCurve curve = span.curve();
  double secondDerivative = 0;
  for (int k = 0; k <= 1000; ++k) {
    secondDerivative = std::max(secondDerivative, curve.derivatives(k / 1000.0).second.norm());
  }
  double steps = boundSteps(span, budget);
  EXPECT_LT(steps, 0.5 * std::sqrt(secondDerivative / (8 * budget)));
  EXPECT_LE(largestChordDeviation(curve, static_cast<int>(std::ceil(steps))), budget);
}

TEST(RationalSpanSteps, WeightsThatChangeFastKeepEachStepsChordAhead) {
  // Collinear points and a budget of a kilometre: the steps are those the
  // weights ask for, sqrt(n^2 sum of squared differences) / wmin = 2
  // sqrt(81 + 81), at least n max |difference| / wmin = 18.
  Span line{{{0, 0, 0}, {50, 0, 0}, {100, 0, 0}}, {1, 10, 1}};
  EXPECT_NEAR(boundSteps(line, 1e12), 2 * std::sqrt(162.0), 1e-9);
}

} // namespace
} // namespace cncc::ir::lowering
