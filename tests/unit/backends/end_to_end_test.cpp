// Compiles the examples this version lowers, runs the IR, and measures the
// cut's deviation from the true curve, built here independently of the
// lowering. The gcode backend's G01 count is checked against
// REFERENCE-CASES.md.
#include "cncc/backends/gcode_writer.h"
#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/geom/deviation.h"
#include "cncc/geom/function_curve.h"
#include "cncc/geom/nurbs_curve.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/lowering.h"
#include "cncc/ir/verifier.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

namespace cncc {
namespace {

std::optional<ir::ToolPath> compileExample(const std::string& name, ir::Function* out = nullptr) {
  frontend::SourceManager sources;
  frontend::DiagnosticEngine diagnostics;
  std::optional<frontend::FileId> file =
      sources.loadFile(std::string(CNCC_SOURCE_DIR) + "/examples/" + name);
  if (!file) {
    ADD_FAILURE() << "cannot read " << name;
    return std::nullopt;
  }
  frontend::CheckOptions options;
  options.importPaths = {CNCC_STDLIB_DIR};
  options.requirePart = true;
  frontend::CheckedProgram program = frontend::checkProgram(sources, *file, options, diagnostics);
  if (diagnostics.hasErrors() || program.selectedPart == nullptr) {
    ADD_FAILURE() << name << " does not check";
    return std::nullopt;
  }
  std::optional<ir::Function> function = ir::lowerPart(program, *program.selectedPart, diagnostics);
  if (!function) {
    ADD_FAILURE() << name << " does not lower: " << diagnostics.diagnostics().back().message;
    return std::nullopt;
  }
  EXPECT_TRUE(ir::verifyFunction(*function).empty());
  if (out != nullptr) {
    *out = *function;
  }
  return ir::interpret(*function);
}

// The last pass's cut at its full depth: the feed moves at the deepest z, in
// the plane z = 0.
std::vector<Eigen::Vector3d> lastPass(const ir::ToolPath& path) {
  double deepest = 0;
  for (const ir::MachineEvent& event : path.events) {
    deepest = std::min(deepest, event.z);
  }
  std::vector<Eigen::Vector3d> polyline;
  for (const ir::MachineEvent& event : path.events) {
    if (event.kind == ir::MachineEvent::Kind::Feed && event.z == deepest) {
      polyline.emplace_back(event.x, event.y, 0);
    } else if (!polyline.empty() && event.kind == ir::MachineEvent::Kind::Rapid &&
               event.z > deepest) {
      if (&event != &path.events.back()) {
        // A later pass at the same depth would follow; keep the last one.
        polyline.clear();
      }
    }
  }
  return polyline;
}

int countG01(const std::string& program) {
  std::istringstream lines(program);
  std::string line;
  int count = 0;
  while (std::getline(lines, line)) {
    count += line.rfind("G01", 0) == 0 ? 1 : 0;
  }
  return count;
}

TEST(EndToEnd, ArchimedeanSpiralMeetsFiveMicronsInNinetyChords) {
  std::optional<ir::ToolPath> path = compileExample("archimedean_spiral.cdl");
  ASSERT_TRUE(path);
  geom::PolarCurve spiral({0, 2 * std::numbers::pi}, [](double t) { return 1 + 2 * t; });
  std::vector<Eigen::Vector3d> polyline = lastPass(*path);
  geom::DeviationReport report = geom::measureDeviation(polyline, spiral, {1e-6});
  EXPECT_LE(report.maxDeviation(), 0.005);
  RecordProperty("deviation", std::to_string(report.maxDeviation()));
  std::string program = backends::writeGcode(*path, {});
  int curveBlocks = countG01(program) - 1; // less the plunge
  EXPECT_LE(curveBlocks, 90);
  EXPECT_EQ(curveBlocks + 1, static_cast<int>(polyline.size()));
}

TEST(EndToEnd, SProfileNurbsWithinTolerance) {
  std::optional<ir::ToolPath> path = compileExample("s_profile.cdl");
  ASSERT_TRUE(path);
  std::vector<Eigen::Vector3d> points = {{25, 50, 0},          {42.8735, 24.1467, 0},
                                         {70.5832, 72.3597, 0}, {86.608, 165.3624, 0},
                                         {112.4532, 38.3852, 0}, {132.4671, 35.1148, 0},
                                         {175, 150, 0}};
  geom::NurbsCurve curve(geom::KnotVector::clampedUniform(3, 7), points, {1, 1, 1, 1, 1, 3, 1});
  std::vector<Eigen::Vector3d> polyline = lastPass(*path);
  geom::DeviationReport report = geom::measureDeviation(polyline, curve, {1e-6});
  EXPECT_LE(report.maxDeviation(), 0.01);
  RecordProperty("deviation", std::to_string(report.maxDeviation()));
  // REFERENCE-CASES.md case 1: 115 chords at 0.01 mm with w6 = 3.
  EXPECT_EQ(polyline.size(), 116u);
}

TEST(EndToEnd, PolarContourWithRampWithinTolerance) {
  std::optional<ir::ToolPath> path = compileExample("polar_contour.cdl");
  ASSERT_TRUE(path);
  geom::PolarCurve contour({0, 2 * std::numbers::pi},
                           [](double t) { return 18 + 4 * std::cos(2 * t) * std::cos(6 * t); });
  std::vector<Eigen::Vector3d> polyline = lastPass(*path);
  geom::DeviationReport report = geom::measureDeviation(polyline, contour, {1e-6});
  EXPECT_LE(report.maxDeviation(), 0.01);
  RecordProperty("deviation", std::to_string(report.maxDeviation()));
  // REFERENCE-CASES.md case 3: 181 chords at 0.01 mm (the ramp's last point
  // starts the full lap).
  EXPECT_EQ(polyline.size(), 182u);
  // The ramp descends monotonically from 0 to the depth.
  double z = 0;
  for (const ir::MachineEvent& event : path->events) {
    if (event.kind == ir::MachineEvent::Kind::Feed) {
      EXPECT_LE(event.z, z + 1e-12);
      z = event.z;
    }
  }
  EXPECT_EQ(z, -6);
}

} // namespace
} // namespace cncc
