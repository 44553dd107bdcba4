// Curves whose points are whole powers, exponentials, quotients or roots
// of t (a denominator or root's argument that stays above a number) and
// depend on part parameters stay editable on the controller: the program computes
// each piece's step count from a bound on |C''| (curvature_bounds.cpp), and
// for parameter values other than the defaults the chords it runs stay
// within the tolerance less the increment rounding, measured on the true
// curve for those values. After expand-whole-powers (the macro programs'
// pass before printing) the path is the same within rounding.
#include "lowered_text.h"

#include "cncc/geom/deviation.h"
#include "cncc/geom/function_curve.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/verifier.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <map>
#include <string>

namespace cncc::ir {
namespace {

constexpr double increment = 0.001;
constexpr double tolerance = 0.01;

LoweringOptions controllerLike() {
  LoweringOptions options;
  options.controllerLoops = true;
  options.coordinateIncrement = increment;
  options.literalSignificantDigits = 8;
  return options;
}

struct EditableCurve {
  std::string curve; // reads the parameters a and b
  double low, high;
  std::function<double(double t, double a, double b)> x, y;
};

// The part's points at its one pass, with a and b as given.
std::vector<Eigen::Vector3d> pointsAt(const Function& function, double a, double b) {
  InterpreterOptions options;
  options.parameters = {{"a", a}, {"b", b}};
  std::vector<Eigen::Vector3d> points;
  for (const MachineEvent& event : interpret(function, options).events) {
    if (event.kind == MachineEvent::Kind::Feed) {
      points.emplace_back(event.x, event.y, 0);
    }
  }
  return points;
}

class EditableCurveBounds : public ::testing::TestWithParam<EditableCurve> {};

TEST_P(EditableCurveBounds, ChordsStayWithinTheBudgetForTheValuesItRunsWith) {
  const EditableCurve& shape = GetParam();
  std::string source = "part p(a = 20, b = 10) {\n  tool 1 diameter=6 feed=300\n  safe z=5\n"
                       "  curve " +
                       shape.curve + " tolerance=0.01\n}\n";
  auto lowered = test_support::lowerText(source, controllerLike());
  ASSERT_TRUE(lowered->part);
  Function& function = lowered->part->function;
  ASSERT_TRUE(legaliseCurves(function, lowered->diagnostics));
  runDefaultPipeline(function);
  EXPECT_TRUE(function.tables.empty()) << shape.curve;
  for (const Parameter& parameter : function.parameters) {
    EXPECT_FALSE(parameter.fixed) << parameter.name << " in " << shape.curve;
  }
  Function printed = function;
  expandWholePowers(printed);
  EXPECT_TRUE(verifyFunction(printed).empty());
  double budget = tolerance - std::sqrt(2.0) * increment / 2;
  for (auto [a, b] : {std::pair{20.0, 10.0}, std::pair{5.0, 3.0}, std::pair{60.0, 25.0}}) {
    std::vector<Eigen::Vector3d> points = pointsAt(function, a, b);
    ASSERT_GT(points.size(), 10u) << shape.curve;
    geom::FunctionCurve truth = geom::FunctionCurve::fromCoordinates(
        {shape.low, shape.high}, [&, a = a, b = b](double t) { return shape.x(t, a, b); },
        [&, a = a, b = b](double t) { return shape.y(t, a, b); });
    EXPECT_LE(geom::measureDeviation(points, truth).maxDeviation(), budget)
        << shape.curve << " a=" << a << " b=" << b;
    std::vector<Eigen::Vector3d> expanded = pointsAt(printed, a, b);
    ASSERT_EQ(expanded.size(), points.size());
    for (std::size_t k = 0; k < points.size(); ++k) {
      EXPECT_LE((expanded[k] - points[k]).norm(), 1e-9) << shape.curve;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    Curves, EditableCurveBounds,
    ::testing::Values(EditableCurve{"param(x = t, y = a*t^2/100, t = -5 .. 5)", -5, 5,
                                    [](double t, double, double) { return t; },
                                    [](double t, double a, double) { return a * t * t / 100; }},
                      EditableCurve{"param(x = t, y = t^3/b, t = -3 .. 3)", -3, 3,
                                    [](double t, double, double) { return t; },
                                    [](double t, double, double b) { return t * t * t / b; }},
                      EditableCurve{"param(x = a*t, y = b*exp(-t), t = 0 .. 3)", 0, 3,
                                    [](double t, double a, double) { return a * t; },
                                    [](double t, double, double b) { return b * std::exp(-t); }},
                      EditableCurve{"polar(r = a*(1 + cos(t))^2/4 + b, t = 0 .. 2*pi)", 0, 2 * M_PI,
                                    [](double t, double a, double b) {
                                      return (a * std::pow(1 + std::cos(t), 2) / 4 + b) *
                                             std::cos(t);
                                    },
                                    [](double t, double a, double b) {
                                      return (a * std::pow(1 + std::cos(t), 2) / 4 + b) *
                                             std::sin(t);
                                    }},
                      EditableCurve{"polar(r = a/(1 + 0.5*cos(t)) + b, t = 0 .. 2*pi)", 0, 2 * M_PI,
                                    [](double t, double a, double b) {
                                      return (a / (1 + 0.5 * std::cos(t)) + b) * std::cos(t);
                                    },
                                    [](double t, double a, double b) {
                                      return (a / (1 + 0.5 * std::cos(t)) + b) * std::sin(t);
                                    }},
                      EditableCurve{"param(x = t, y = a*sqrt(4 + sin(b*t/5)), t = 0 .. 10)", 0, 10,
                                    [](double t, double, double) { return t; },
                                    [](double t, double a, double b) {
                                      return a * std::sqrt(4 + std::sin(b * t / 5));
                                    }}));

} // namespace
} // namespace cncc::ir
