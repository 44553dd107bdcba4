// The lowering for controller-side targets (LoweringOptions::controllerLoops):
// no constant tables, loops over uniform steps, and step counts that the IR
// computes from the parameters where the geometry depends on them. The IR
// is run by the interpreter with parameter values other than the defaults
// and its points are measured against the true curve for those values: the
// chords must stay within the tolerance less the increment rounding.
#include "cncc/lowering/lowering.h"

#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/geom/deviation.h"
#include "cncc/geom/function_curve.h"
#include "cncc/geom/nurbs_curve.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/verifier.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

namespace cncc::ir {
namespace {

constexpr double increment = 0.001;

struct Lowering {
  frontend::SourceManager sources;
  frontend::DiagnosticEngine diagnostics;
  std::optional<frontend::CheckedProgram> program;
  std::optional<Function> function;
};

std::unique_ptr<Lowering> lowerExample(const std::string& name) {
  std::ifstream file(std::string(CNCC_SOURCE_DIR) + "/examples/" + name);
  std::stringstream text;
  text << file.rdbuf();
  auto result = std::make_unique<Lowering>();
  frontend::FileId id = result->sources.addFile(name, text.str());
  frontend::CheckOptions options;
  options.importPaths = {CNCC_STDLIB_DIR};
  options.requirePart = true;
  result->program = frontend::checkProgram(result->sources, id, options, result->diagnostics);
  EXPECT_FALSE(result->diagnostics.hasErrors());
  LoweringOptions lowering;
  lowering.controllerLoops = true;
  lowering.coordinateIncrement = increment;
  if (result->program->selectedPart != nullptr) {
    result->function =
        lowerPart(*result->program, *result->program->selectedPart, result->diagnostics, lowering);
  }
  if (result->function) {
    runDefaultPipeline(*result->function);
    EXPECT_TRUE(verifyFunction(*result->function).empty());
  }
  return result;
}

// The feed points at height z (the plunge's end included).
std::vector<Eigen::Vector3d> feedPointsAt(const ToolPath& path, double z) {
  std::vector<Eigen::Vector3d> points;
  for (const MachineEvent& event : path.events) {
    if (event.kind == MachineEvent::Kind::Feed && std::abs(event.z - z) < 1e-9) {
      points.emplace_back(event.x, event.y, 0);
    }
  }
  return points;
}

bool hasTableOrConstantBoundLoop(const Function& function, bool& anyComputedBound) {
  anyComputedBound = false;
  for (const Instruction& instruction : function.instructions) {
    if (instruction.opcode == Opcode::Loop &&
        function.definition(instruction.operands[1]).opcode != Opcode::Const) {
      anyComputedBound = true;
    }
  }
  return !function.tables.empty();
}

class SpiralParameters : public ::testing::TestWithParam<std::pair<double, double>> {};

TEST_P(SpiralParameters, ChordsStayWithinTheBudgetForTheValuesItRunsWith) {
  auto lowered = lowerExample("archimedean_spiral.cdl");
  ASSERT_TRUE(lowered->function);
  bool computed = false;
  EXPECT_FALSE(hasTableOrConstantBoundLoop(*lowered->function, computed));
  EXPECT_TRUE(computed) << "the step count depends on a and b";
  auto [a, b] = GetParam();
  InterpreterOptions options;
  options.parameters = {{"a", a}, {"b", b}};
  std::vector<Eigen::Vector3d> points = feedPointsAt(interpret(*lowered->function, options), 0);
  ASSERT_GT(points.size(), 50u);
  geom::PolarCurve truth({0, 2 * M_PI}, [a = a, b = b](double t) { return a + b * t; });
  double budget = 0.005 - std::sqrt(2.0) * increment / 2;
  EXPECT_LE(geom::measureDeviation(points, truth).maxDeviation(), budget);
}

INSTANTIATE_TEST_SUITE_P(Values, SpiralParameters,
                         ::testing::Values(std::pair{1.0, 2.0}, std::pair{3.0, 0.5},
                                           std::pair{0.5, 4.0}, std::pair{10.0, 0.1}));

class SProfileWeights : public ::testing::TestWithParam<double> {};

TEST_P(SProfileWeights, ChordsStayWithinTheBudgetForTheWeightItRunsWith) {
  auto lowered = lowerExample("s_profile.cdl");
  ASSERT_TRUE(lowered->function);
  bool computed = false;
  EXPECT_FALSE(hasTableOrConstantBoundLoop(*lowered->function, computed));
  EXPECT_TRUE(computed) << "the spans that w6 moves count their steps on the controller";
  double w6 = GetParam();
  InterpreterOptions options;
  options.parameters = {{"w6", w6}, {"depth", 2}, {"step", 1}};
  ToolPath path = interpret(*lowered->function, options);
  EXPECT_TRUE(feedPointsAt(path, -3).empty()) << "the edited depth sets the passes";
  std::vector<Eigen::Vector3d> points = feedPointsAt(path, -2);
  ASSERT_GT(points.size(), 100u);
  std::vector<Eigen::Vector3d> controlPoints = {
      {25, 50, 0},           {42.8735, 24.1467, 0},  {70.5832, 72.3597, 0},
      {86.608, 165.3624, 0}, {112.4532, 38.3852, 0}, {132.4671, 35.1148, 0},
      {175, 150, 0}};
  geom::NurbsCurve truth(geom::KnotVector({0, 0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1, 1}, 3),
                         controlPoints, {1, 1, 1, 1, 1, w6, 1});
  double budget = 0.01 - std::sqrt(2.0) * increment / 2;
  EXPECT_LE(geom::measureDeviation(points, truth).maxDeviation(), budget);
}

INSTANTIATE_TEST_SUITE_P(Values, SProfileWeights, ::testing::Values(3.0, 1.0, 8.0, 0.3));

// The points of a pass on the two spans w6 moves (the two others take 108),
// each walked with a step computed at each point (rational_span_walk.cpp).
// The same spans with w6 a literal take 110, 94 and 79 uniform steps (the
// fewest, measured on the curve); a count per span from the chord bound
// over their Bezier control points took 154, 279 and 500, the earlier
// bound of |C''| over the B-spline's hull 174, 658 and 1820.
TEST(ControllerLoopsLowering, SProfileSpansOfW6TakeFewPointsPerPass) {
  auto lowered = lowerExample("s_profile.cdl");
  ASSERT_TRUE(lowered->function);
  for (auto [w6, reference] : {std::pair{1.0, 110u}, std::pair{3.0, 94u}, std::pair{8.0, 79u}}) {
    InterpreterOptions options;
    options.parameters = {{"w6", w6}};
    ToolPath path = interpret(*lowered->function, options);
    // The pass's feed points less the plunge's end and the two constant spans.
    std::size_t points = feedPointsAt(path, -1).size() - 1 - 108;
    EXPECT_LE(static_cast<double>(points), 1.5 * reference) << "w6 = " << w6;
    EXPECT_GE(points, reference * 9 / 10) << "w6 = " << w6 << ": fewer than the curve needs";
  }
}

TEST(ControllerLoopsLowering, AWeightThatIsNotPositiveStopsTheProgram) {
  auto lowered = lowerExample("s_profile.cdl");
  ASSERT_TRUE(lowered->function);
  for (double w6 : {0.0, -1.0}) {
    InterpreterOptions options;
    options.parameters = {{"w6", w6}};
    try {
      interpret(*lowered->function, options);
      ADD_FAILURE() << "w6 = " << w6 << " ran";
    } catch (const InterpreterError& error) {
      EXPECT_NE(std::string(error.what()).find("a weight of a NURBS is not positive"),
                std::string::npos)
          << error.what();
    }
  }
}

TEST(ControllerLoopsLowering, ConstantCurvesCountTheirStepsAtCompileTime) {
  // The contour is constant; only its depth is a parameter. The ramp lap
  // and the lap at depth are loops of a constant count, the passes a loop
  // of a count the controller rounds.
  auto lowered = lowerExample("polar_contour.cdl");
  ASSERT_TRUE(lowered->function);
  EXPECT_TRUE(lowered->function->tables.empty());
  int constantLoops = 0;
  for (const Instruction& instruction : lowered->function->instructions) {
    if (instruction.opcode == Opcode::Loop) {
      const Instruction& bound = lowered->function->definition(instruction.operands[1]);
      EXPECT_TRUE(bound.opcode == Opcode::Const || bound.opcode == Opcode::Round);
      constantLoops += bound.opcode == Opcode::Const ? 1 : 0;
    }
  }
  EXPECT_EQ(constantLoops, 2);
}

} // namespace
} // namespace cncc::ir
