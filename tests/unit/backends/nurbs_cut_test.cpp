// method=nurbs cuts on the macro targets, end to end: the part lowered with
// nurbsBlocks, printed as G06.2 blocks, run on the virtual controller, and
// each pass compared with the cut's true curve. For a NURBS source: within
// 1e-6 mm of the NURBS through the control points rounded to IS-B (0.001 mm)
// at every executed point, so within 1e-6 mm plus 7.1e-4 mm (half an
// increment on X and Y) of the source. For an analytic source: within the
// cut's tolerance.
#include "cncc/backends/controller_profile.h"
#include "cncc/backends/gcode_writer.h"
#include "cncc/backends/macro_program.h"
#include "cncc/backends/virtual_controller.h"
#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/geom/deviation.h"
#include "cncc/geom/nurbs_curve.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/nurbs_move.h"
#include "cncc/ir/passes.h"
#include "cncc/lowering/lowering.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

namespace cncc::backends {
namespace {

const char* sProfileSource = R"(part s_profile(depth = 2, step = 1, w6 = 3) {
  tool 1 diameter=10 spindle=3000 feed=300
  safe z=5
  let P = [(25,50), (42.8735,24.1467), (70.5832,72.3597), (86.608,165.3624),
           (112.4532,38.3852), (132.4671,35.1148), (175,150)]
  curve nurbs(order=4, points=P, weights=[1,1,1,1,1,w6,1]) sweep depth=depth step=step tolerance=0.01 method=nurbs
}
)";

const char* spiralSource = R"(part spiral(a = 1, b = 2) {
  tool 1 diameter=1 spindle=6000 feed=100
  safe z=2
  curve polar(r = a + b*t, t = 0 .. 2*pi) tolerance=0.005 method=nurbs
}
)";

struct CompiledNurbsPart {
  frontend::SourceManager sources;
  frontend::DiagnosticEngine diagnostics;
  std::optional<frontend::CheckedProgram> program;
  std::vector<ir::CutGeometry> cuts;
  std::optional<ir::Function> function;
  std::string text;
};

std::unique_ptr<CompiledNurbsPart> compile(const std::string& source, const std::string& target) {
  auto part = std::make_unique<CompiledNurbsPart>();
  frontend::FileId file = part->sources.addFile("part.cdl", source);
  frontend::CheckOptions check;
  check.requirePart = true;
  part->program = frontend::checkProgram(part->sources, file, check, part->diagnostics);
  if (part->diagnostics.hasErrors()) {
    ADD_FAILURE() << part->diagnostics.diagnostics().front().message;
    return nullptr;
  }
  const ControllerProfile& profile = *findControllerProfile(target);
  ir::LoweringOptions lowering = macroLoweringOptions(profile, false);
  lowering.nurbsBlocks = true;
  std::optional<ir::LoweredPart> lowered = ir::lowerPartWithCuts(
      *part->program, *part->program->selectedPart, part->diagnostics, lowering);
  if (!lowered) {
    ADD_FAILURE() << "does not lower";
    return nullptr;
  }
  EXPECT_TRUE(ir::runPasses(lowered->function, lowering.passesBeforePrinting, {}));
  part->cuts = lowered->function.cuts;
  part->function = lowered->function;
  MacroProgramOptions options;
  options.partName = part->program->selectedPart->name;
  MacroProgram program = writeMacroProgram(lowered->function, profile, options);
  if (!program.errors.empty()) {
    ADD_FAILURE() << program.errors.front();
    return nullptr;
  }
  part->text = program.text;
  return part;
}

// The executed feed moves at each depth below zero, by depth: the laps (the
// plunge ends at the lap's depth, so its end is the lap's first point).
std::map<double, std::vector<Eigen::Vector3d>> lapsOf(const std::string& text,
                                                      const std::string& target) {
  sim::SimulationResult result = sim::simulateProgram(text, *findControllerProfile(target));
  EXPECT_FALSE(result.error) << (result.error ? result.error->what() : "");
  std::map<double, std::vector<Eigen::Vector3d>> laps;
  for (const sim::ExecutedEvent& event : result.path.events) {
    if (event.kind != sim::ExecutedEvent::Kind::Feed || event.end.z != event.start.z) {
      continue;
    }
    std::vector<Eigen::Vector3d>& lap = laps[event.end.z];
    if (lap.empty()) {
      lap.emplace_back(event.start.x, event.start.y, 0);
    }
    lap.emplace_back(event.end.x, event.end.y, 0);
  }
  return laps;
}

double largestPointDistance(const std::vector<Eigen::Vector3d>& points, const geom::Curve& curve) {
  geom::CurveProximity proximity(curve, 1e-8);
  double largest = 0;
  for (const Eigen::Vector3d& point : points) {
    largest = std::max(largest, proximity.closestPoint(point).distance);
  }
  return largest;
}

TEST(NurbsCut, SProfileIsTheSourceNurbsUpToTheIncrement) {
  for (const char* target : {"m80", "fanuc"}) {
    SCOPED_TRACE(target);
    std::unique_ptr<CompiledNurbsPart> part = compile(sProfileSource, target);
    ASSERT_TRUE(part);
    EXPECT_NE(part->text.find("G06.2 P4"), std::string::npos);
    EXPECT_NE(part->text.find(" R#"), std::string::npos) << "w6 stays a variable";
    const auto& source = dynamic_cast<const geom::NurbsCurve&>(*part->cuts.at(0).curve);
    std::vector<Eigen::Vector3d> rounded;
    for (const Eigen::Vector3d& point : source.controlPoints()) {
      rounded.emplace_back(std::stod(formatGcodeNumber(point.x(), 3)),
                           std::stod(formatGcodeNumber(point.y(), 3)), 0);
    }
    geom::NurbsCurve printed(source.knots(), rounded, source.weights());
    std::map<double, std::vector<Eigen::Vector3d>> laps = lapsOf(part->text, target);
    ASSERT_EQ(laps.size(), 2u); // depth 2, step 1
    for (const auto& [z, points] : laps) {
      SCOPED_TRACE(z);
      ASSERT_GT(points.size(), 100u);
      // The controller's curve: the control points as printed.
      EXPECT_LT(largestPointDistance(points, printed), 1e-6);
      EXPECT_LE(largestPointDistance(points, source), 7.1e-4 + 1e-6);
      EXPECT_LE(geom::measureDeviation(points, source, {1e-6}).maxDeviation(), 0.01);
    }
  }
}

// The curve of the IR's move.nurbs (its table, its weights at their
// defaults) at the pass height of 0.
geom::NurbsCurve curveOfTheIr(const ir::Function& function) {
  for (const ir::Instruction& instruction : function.instructions) {
    if (instruction.opcode != ir::Opcode::Nurbs) {
      continue;
    }
    std::vector<double> weights;
    for (std::size_t k = 2; k < instruction.operands.size(); ++k) {
      const ir::Instruction& definition = function.definition(instruction.operands[k]);
      weights.push_back(definition.opcode == ir::Opcode::Param
                            ? function.parameters[definition.index].defaultValue
                            : definition.number);
    }
    std::optional<ir::NurbsBlockData> data =
        ir::readNurbsMoveTable(function.tables[instruction.index], weights.size());
    EXPECT_TRUE(data);
    return ir::nurbsMoveCurve(*data, 0, weights);
  }
  ADD_FAILURE() << "no move.nurbs";
  return geom::NurbsCurve::bezier({{0, 0, 0}, {1, 0, 0}});
}

// The IR holds the curve the controller cuts: every point the printed
// program executes, and every point of the interpreted IR, lies on the
// curve of the IR's move.nurbs.
TEST(NurbsCut, TheIrHoldsTheCurveTheControllerCuts) {
  for (const char* target : {"m80", "fanuc"}) {
    SCOPED_TRACE(target);
    std::unique_ptr<CompiledNurbsPart> part = compile(sProfileSource, target);
    ASSERT_TRUE(part);
    geom::NurbsCurve curve = curveOfTheIr(*part->function);
    for (const auto& [z, points] : lapsOf(part->text, target)) {
      EXPECT_LT(largestPointDistance(points, curve), 1e-6) << z;
    }
    std::vector<Eigen::Vector3d> interpreted;
    for (const ir::MachineEvent& event : ir::interpret(*part->function).events) {
      if (event.kind == ir::MachineEvent::Kind::Feed && event.z == -1) {
        interpreted.emplace_back(event.x, event.y, 0);
      }
    }
    ASSERT_GT(interpreted.size(), 100u);
    EXPECT_LT(largestPointDistance(interpreted, curve), 1e-6);
  }
}

TEST(NurbsCut, AnalyticCurveIsFittedWithinItsTolerance) {
  for (const char* target : {"m80", "fanuc"}) {
    SCOPED_TRACE(target);
    std::unique_ptr<CompiledNurbsPart> part = compile(spiralSource, target);
    ASSERT_TRUE(part);
    std::map<double, std::vector<Eigen::Vector3d>> laps = lapsOf(part->text, target);
    ASSERT_EQ(laps.size(), 1u);
    const std::vector<Eigen::Vector3d>& points = laps.begin()->second;
    EXPECT_LE(geom::measureDeviation(points, *part->cuts.at(0).curve, {1e-6}).maxDeviation(),
              0.005);
  }
}

} // namespace
} // namespace cncc::backends
