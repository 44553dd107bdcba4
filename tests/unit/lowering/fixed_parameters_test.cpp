// The parameters whose defaults the lowering builds into the program
// (LoweredPart::fixedParameters): a loop bound and a sampled polar curve's
// radius fix theirs, a sweep depth computed on the controller does not; the
// warning is given for controller-side targets only.
#include "lowered_text.h"

#include "cncc/lowering/lowering.h"

#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/geom/deviation.h"
#include "cncc/geom/function_curve.h"
#include "cncc/ir/interpreter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <set>
#include <string>

namespace cncc::ir {
namespace {

using Lowered = test_support::LoweredText;

std::unique_ptr<Lowered> lower(const std::string& text, bool controllerLoops,
                               int maximumLoopNesting = 0) {
  LoweringOptions lowering;
  lowering.controllerLoops = controllerLoops;
  lowering.maximumLoopNesting = maximumLoopNesting;
  lowering.coordinateIncrement = 0.001;
  return test_support::lowerText(text, lowering, "fixed.cdl");
}

std::vector<std::string> fixedNames(const LoweredPart& part) {
  std::vector<std::string> names;
  for (const FixedParameter& fixed : part.fixedParameters) {
    names.push_back(fixed.name);
  }
  return names;
}

bool parameterFlagged(const LoweredPart& part, const std::string& name) {
  return std::any_of(
      part.function.parameters.begin(), part.function.parameters.end(),
      [&](const Parameter& parameter) { return parameter.name == name && parameter.fixed; });
}

std::size_t warningsOfKind(const frontend::DiagnosticEngine& diagnostics) {
  return static_cast<std::size_t>(
      std::count_if(diagnostics.diagnostics().begin(), diagnostics.diagnostics().end(),
                    [](const frontend::Diagnostic& diagnostic) {
                      return diagnostic.kind == frontend::DiagnosticKind::ParameterFixed;
                    }));
}

const char* const loopAndPolar = R"(part p(count = 3, radius = 10, depth = 2, unused = 1) {
  tool 1 diameter=6 feed=200
  safe z=5
  for i in 1 .. count {
    curve line(from=(i, 0), to=(i, 5)) sweep depth=depth step=1 tolerance=0.01*i
  }
  curve polar(r = radius + sqrt(1 + cos(3*t)), t = 0 .. 2*pi) tolerance=0.05
}
)";

// The loop's body needs its variable as a number (a tolerance), so the
// loop is unrolled; the root of 1 + cos(3t), which comes to 0, is beyond the
// bounds the controller computes.
TEST(FixedParameters, LoopBoundAndSampledCurveFixTheirParametersOnController) {
  std::unique_ptr<Lowered> result = lower(loopAndPolar, true);
  ASSERT_TRUE(result->part);
  std::vector<std::string> names = fixedNames(*result->part);
  ASSERT_EQ(names, (std::vector<std::string>{"count", "radius"}));
  EXPECT_TRUE(parameterFlagged(*result->part, "count"));
  EXPECT_TRUE(parameterFlagged(*result->part, "radius"));
  // The sweep's passes are computed on the controller from depth.
  EXPECT_FALSE(parameterFlagged(*result->part, "depth"));
  EXPECT_FALSE(parameterFlagged(*result->part, "unused"));
  EXPECT_EQ(warningsOfKind(result->diagnostics), 2u);
  // The first use that fixed it: the loop's range.
  const frontend::SourceSpan& use = result->part->fixedParameters.front().use;
  std::string text = loopAndPolar;
  EXPECT_EQ(text.substr(use.begin, use.end - use.begin), "1 .. count");
}

TEST(FixedParameters, HostTargetsRecordButDoNotWarn) {
  std::unique_ptr<Lowered> result = lower(loopAndPolar, false);
  ASSERT_TRUE(result->part);
  // The sweep's passes are computed from depth as on the controller; the
  // loop's bound and the sampled curve are numbers here.
  std::vector<std::string> names = fixedNames(*result->part);
  EXPECT_EQ(std::find(names.begin(), names.end(), "depth"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "count"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "radius"), names.end());
  EXPECT_FALSE(parameterFlagged(*result->part, "depth"));
  EXPECT_EQ(warningsOfKind(result->diagnostics), 0u);
}

TEST(FixedParameters, SymbolicSweepAndSpiralFixNothing) {
  std::unique_ptr<Lowered> result = lower(R"(part p(depth = 3, a = 1, b = 0.5) {
  tool 1 diameter=6 feed=200
  safe z=5
  curve polar(r = a + b*t, t = 0 .. 4*pi) sweep depth=depth step=1 tolerance=0.05
}
)",
                                          true);
  ASSERT_TRUE(result->part);
  EXPECT_TRUE(result->part->fixedParameters.empty()) << fixedNames(*result->part).front();
  EXPECT_EQ(warningsOfKind(result->diagnostics), 0u);
}

} // namespace
// Controller loops and branches: a `for` whose bounds and an `if` whose
// condition read parameters run on the controller and fix nothing.
namespace {

std::vector<MachineEvent> feedsOf(const Function& function,
                                  const std::map<std::string, double>& values) {
  InterpreterOptions options;
  options.parameters = values;
  std::vector<MachineEvent> feeds;
  for (const MachineEvent& event : interpret(function, options).events) {
    if (event.kind == MachineEvent::Kind::Feed) {
      feeds.push_back(event);
    }
  }
  return feeds;
}

TEST(ControllerControlFlow, LoopOverAParameterRunsOnTheController) {
  std::unique_ptr<Lowered> result = lower(R"(part p(count = 3, depth = 2) {
  tool 1 diameter=6 feed=200
  safe z=5
  for i in 1 .. count {
    curve line(from=(10*i, 0), to=(10*i, 5)) sweep depth=depth step=1
  }
}
)",
                                          true);
  ASSERT_TRUE(result->part);
  EXPECT_TRUE(fixedNames(*result->part).empty());
  EXPECT_EQ(warningsOfKind(result->diagnostics), 0u);
  for (double count : {0.0, 1.0, 5.0}) {
    std::set<double> columns;
    for (const MachineEvent& feed : feedsOf(result->part->function, {{"count", count}})) {
      columns.insert(feed.x);
    }
    std::set<double> expected;
    for (int i = 1; i <= count; ++i) {
      expected.insert(10.0 * i);
    }
    EXPECT_EQ(columns, expected) << "count = " << count;
  }
}

TEST(ControllerControlFlow, BranchIsChosenOnTheControllerWithItsFeed) {
  std::unique_ptr<Lowered> result = lower(R"(part p(deep = 1) {
  tool 1 diameter=6 feed=200
  safe z=5
  if deep > 0 {
    feed 100
    curve line(from=(0, 0), to=(5, 0)) sweep depth=4 step=2
  } else {
    curve line(from=(0, 0), to=(0, 5))
  }
  curve line(from=(20, 0), to=(25, 0))
}
)",
                                          true);
  ASSERT_TRUE(result->part);
  EXPECT_TRUE(fixedNames(*result->part).empty());
  std::vector<MachineEvent> deep = feedsOf(result->part->function, {{"deep", 1}});
  std::vector<MachineEvent> flat = feedsOf(result->part->function, {{"deep", 0}});
  ASSERT_FALSE(deep.empty());
  ASSERT_FALSE(flat.empty());
  EXPECT_EQ(deep.back().feed, 100) << "the branch's feed holds after the if";
  EXPECT_EQ(flat.back().feed, 200);
  double deepest = 0;
  for (const MachineEvent& feed : deep) {
    deepest = std::min(deepest, feed.z);
    EXPECT_EQ(feed.y, 0);
  }
  EXPECT_EQ(deepest, -4);
  bool alongY = false;
  for (const MachineEvent& feed : flat) {
    EXPECT_EQ(feed.z, 0);
    alongY = alongY || feed.y == 5;
  }
  EXPECT_TRUE(alongY);
}

// Loops the controller cannot nest (a Fanuc has DO1 to DO3) are unrolled
// from the innermost, which fixes its bound.
TEST(ControllerControlFlow, LoopsDeeperThanTheControllerNestsAreUnrolled) {
  const char* const grid = R"(part grid(rows = 2, columns = 3, depth = 2) {
  tool 1 diameter=6 feed=200
  safe z=5
  for i in 1 .. rows {
    for j in 1 .. columns {
      curve translate(polar(r = 3 + 0.5*cos(5*t), t = 0 .. 2*pi), 10*i, 10*j) sweep depth=depth step=1
    }
  }
}
)";
  std::unique_ptr<Lowered> limited = lower(grid, true, 3);
  ASSERT_TRUE(limited->part);
  EXPECT_EQ(fixedNames(*limited->part), std::vector<std::string>{"columns"});
  std::unique_ptr<Lowered> unlimited = lower(grid, true);
  ASSERT_TRUE(unlimited->part);
  EXPECT_TRUE(fixedNames(*unlimited->part).empty());
  // Each contour stays within 3.5 of its centre (10 i, 10 j): the cells
  // cut, with rows edited, are three rows of three.
  std::set<std::pair<double, double>> cells;
  for (const MachineEvent& feed : feedsOf(limited->part->function, {{"rows", 3}})) {
    cells.insert({std::round(feed.x / 10), std::round(feed.y / 10)});
  }
  EXPECT_EQ(cells.size(), 9u);
}

// A curve of constants cut in single steps (lines: one move each) prints no
// loop of its own, though choose-controller-steps, not the lowering, cuts
// it in steps: two loops and a pass loop nest three deep, as a Fanuc can.
// A polar curve's steps are a loop: the inner for is unrolled.
TEST(ControllerControlFlow, LapsOfSingleStepsAreNoLoopToNest) {
  const std::string grid = R"(part grid(rows = 2, columns = 3, depth = 2) {
  tool 1 diameter=6 feed=200
  safe z=5
  for i in 1 .. rows {
    for j in 1 .. columns {
      curve CURVE sweep depth=depth*j step=1
    }
  }
}
)";
  auto withCurve = [&](const std::string& curve) {
    std::string text = grid;
    return text.replace(text.find("CURVE"), 5, curve);
  };
  std::unique_ptr<Lowered> lines =
      lower(withCurve("path(line(from=(0,0), to=(5,0)), line(from=(5,0), to=(5,5)))"), true, 3);
  ASSERT_TRUE(lines->part);
  EXPECT_TRUE(fixedNames(*lines->part).empty());
  // Arc pieces are move.arc blocks between the lines' laps, no loop either.
  std::unique_ptr<Lowered> withArc =
      lower(withCurve("path(line(from=(0,0), to=(5,0)), arc(center=(5,2), radius=2, from=-pi/2, "
                      "to=pi/2))"),
            true, 3);
  ASSERT_TRUE(withArc->part);
  EXPECT_TRUE(fixedNames(*withArc->part).empty());
  std::unique_ptr<Lowered> polar = lower(withCurve("polar(r = 3, t = 0 .. pi)"), true, 3);
  ASSERT_TRUE(polar->part);
  EXPECT_EQ(fixedNames(*polar->part), std::vector<std::string>{"columns"});
}

// A list of points computed from a parameter: an element at a known index
// lowers to its own expression; what the lowering cannot follow (a length
// of a list stays a number) fixes nothing it does not read.
TEST(ControllerControlFlow, ListElementsOfParametersStaySymbolic) {
  std::unique_ptr<Lowered> result = lower(R"(part p(a = 10) {
  tool 1 diameter=6 feed=300
  safe z=5
  let P = [(0, 0), (a, 5)]
  for i in 0 .. len(P) - 1 {
    curve line(from=P[0], to=P[1] + (0, 10*i)) tolerance=0.01
  }
}
)",
                                          true);
  ASSERT_TRUE(result->part);
  EXPECT_TRUE(fixedNames(*result->part).empty());
  std::vector<MachineEvent> feeds = feedsOf(result->part->function, {{"a", 25}});
  ASSERT_FALSE(feeds.empty());
  std::set<std::pair<double, double>> ends;
  for (const MachineEvent& feed : feeds) {
    ends.insert({feed.x, feed.y});
  }
  EXPECT_TRUE(ends.contains({25, 5}));
  EXPECT_TRUE(ends.contains({25, 15}));
}

// The step count of a param curve whose coefficients are parameters,
// computed on the controller from bounds of |C''|, keeps the tolerance for
// values far from the defaults.
TEST(ControllerControlFlow, ParamCurveOfParametersKeepsItsTolerance) {
  std::unique_ptr<Lowered> result = lower(R"(part p(a = 10, b = 6, c = 1) {
  tool 1 diameter=6 feed=200
  safe z=5
  curve param(x = a*cos(3*t), y = b*sin(2*t) + c*t, t = 0 .. 2*pi) tolerance=0.01
}
)",
                                          true);
  ASSERT_TRUE(result->part);
  EXPECT_TRUE(fixedNames(*result->part).empty());
  for (auto [a, b, c] : {std::array<double, 3>{10, 6, 1}, {40, 2, 0}, {3, 25, -4}}) {
    std::vector<Eigen::Vector3d> points;
    for (const MachineEvent& feed :
         feedsOf(result->part->function, {{"a", a}, {"b", b}, {"c", c}})) {
      points.emplace_back(feed.x, feed.y, feed.z);
    }
    geom::FunctionCurve truth = geom::FunctionCurve::fromCoordinates(
        {0, 2 * M_PI}, [a = a](double t) { return a * std::cos(3 * t); },
        [b = b, c = c](double t) { return b * std::sin(2 * t) + c * t; }, {});
    ASSERT_GT(points.size(), 10u);
    // The controller's rounding of the coordinates is the rest of the budget.
    EXPECT_LE(geom::measureDeviation(points, truth).maxDeviation(), 0.01 - 0.0005 * std::sqrt(2))
        << "a = " << a << ", b = " << b << ", c = " << c;
  }
}

} // namespace
} // namespace cncc::ir
