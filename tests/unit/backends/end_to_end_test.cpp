// Compiles every example, runs the IR, and measures each cut's deviation
// from its true curve: once against curves built here independently of the
// lowering (the reference cases), and for every cut of every example
// against the CutGeometry the lowering reports, the feed moves split by
// their CutBegin events. The gcode backend's G01 counts are checked against
// REFERENCE-CASES.md.
#include "cncc/backends/gcode_writer.h"
#include "cncc/backends/tool_path_csv.h"
#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/geom/deviation.h"
#include "cncc/geom/function_curve.h"
#include "cncc/geom/nurbs_curve.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/verifier.h"
#include "cncc/lowering/lowering.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <memory>
#include <numbers>
#include <sstream>
#include <string>

namespace cncc {
namespace {

// An example compiled and run; the program stays alive because analytic
// cut curves evaluate its expressions.
struct CompiledExample {
  frontend::SourceManager sources;
  frontend::DiagnosticEngine diagnostics;
  std::optional<frontend::CheckedProgram> program;
  std::optional<ir::LoweredPart> lowered;
  ir::ToolPath path;
};

std::unique_ptr<CompiledExample> compile(const std::string& name, const std::string& part = {}) {
  auto result = std::make_unique<CompiledExample>();
  std::optional<frontend::FileId> file =
      result->sources.loadFile(std::string(CNCC_SOURCE_DIR) + "/examples/" + name);
  if (!file) {
    ADD_FAILURE() << "cannot read " << name;
    return nullptr;
  }
  frontend::CheckOptions options;
  options.importPaths = {CNCC_STDLIB_DIR};
  options.requirePart = true;
  options.partName = part;
  result->program = frontend::checkProgram(result->sources, *file, options, result->diagnostics);
  if (result->diagnostics.hasErrors() || result->program->selectedPart == nullptr) {
    ADD_FAILURE() << name << " does not check";
    return nullptr;
  }
  result->lowered =
      ir::lowerPartWithCuts(*result->program, *result->program->selectedPart, result->diagnostics);
  if (!result->lowered) {
    ADD_FAILURE() << name
                  << " does not lower: " << result->diagnostics.diagnostics().back().message;
    return nullptr;
  }
  std::vector<std::string> problems = ir::verifyFunction(result->lowered->function);
  EXPECT_TRUE(problems.empty()) << name << ": " << (problems.empty() ? "" : problems.front());
  result->path = ir::interpret(result->lowered->function);
  return result;
}

std::optional<ir::ToolPath> compileExample(const std::string& name) {
  std::unique_ptr<CompiledExample> example = compile(name);
  if (!example) {
    return std::nullopt;
  }
  return example->path;
}

// The last pass's cut at its full depth: the feed moves at the deepest z, in
// the plane z = 0.
std::vector<Eigen::Vector3d> lastPass(const ir::ToolPath& path) {
  double deepest = 0;
  for (const ir::MachineEvent& event : path.events) {
    deepest = std::min(deepest, event.z);
  }
  // The feed moves at the deepest height between two rapids; the last run.
  std::vector<Eigen::Vector3d> polyline, run;
  for (const ir::MachineEvent& event : path.events) {
    if (event.kind == ir::MachineEvent::Kind::Feed && event.z == deepest) {
      run.emplace_back(event.x, event.y, 0);
    } else if (!run.empty() && event.kind == ir::MachineEvent::Kind::Rapid) {
      polyline = std::move(run);
      run.clear();
    }
  }
  return run.empty() ? polyline : run;
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

// A curve seen from above: its z set to 0.
class PlanView : public geom::Curve {
public:
  explicit PlanView(const geom::Curve& curve) : curve_(curve) {}
  geom::ParameterRange domain() const override { return curve_.domain(); }
  Eigen::Vector3d point(double t) const override { return flat(curve_.point(t)); }
  Eigen::Vector3d derivative(double t) const override { return flat(curve_.derivative(t)); }
  Eigen::Vector3d secondDerivative(double t) const override {
    return flat(curve_.secondDerivative(t));
  }
  std::vector<double> breakpoints() const override { return curve_.breakpoints(); }

private:
  static Eigen::Vector3d flat(Eigen::Vector3d v) {
    v.z() = 0;
    return v;
  }
  const geom::Curve& curve_;
};

// One pass of a cut: its feed moves from the plunge on, and whether it
// descends along the curve (entry=ramp).
struct Pass {
  std::vector<Eigen::Vector3d> moves;
  bool ramp = false;
};

// The passes of each cut, split by CutBegin events and by rapids.
std::vector<std::vector<Pass>> passesByCut(const ir::ToolPath& path, std::size_t cutCount) {
  std::vector<std::vector<Pass>> cuts(cutCount);
  std::vector<Pass>* current = nullptr;
  bool newPass = true;
  for (const ir::MachineEvent& event : path.events) {
    switch (event.kind) {
    case ir::MachineEvent::Kind::CutBegin:
      EXPECT_LT(event.number, static_cast<double>(cutCount));
      current = event.number < static_cast<double>(cutCount)
                    ? &cuts[static_cast<std::size_t>(event.number)]
                    : nullptr;
      newPass = true;
      break;
    case ir::MachineEvent::Kind::Rapid:
      newPass = true;
      break;
    case ir::MachineEvent::Kind::Comment:
      if (event.text == "ramp" && current != nullptr && !current->empty()) {
        current->back().ramp = true;
      }
      break;
    case ir::MachineEvent::Kind::Feed:
      EXPECT_NE(current, nullptr) << "a feed move outside every cut";
      if (current != nullptr) {
        if (newPass) {
          current->emplace_back();
          newPass = false;
        }
        current->back().moves.emplace_back(event.x, event.y, event.z);
      }
      break;
    default:
      break;
    }
  }
  return cuts;
}

// The largest deviation of a cut's passes from its curve. A pass at depth
// D runs at the curve's own z plus D (the plunge's offset from the curve's
// start); a ramped pass descends on purpose, so it is measured in plan.
double largestDeviation(const std::vector<Pass>& passes, const geom::Curve& curve) {
  double largest = 0;
  PlanView plan(curve);
  Eigen::Vector3d start = curve.point(curve.domain().t0);
  // The passes of a sweep repeat the first in plan; the first and the last
  // (where a ramp and the bottom differ) are measured.
  for (const Pass* pass : {&passes.front(), &passes.back()}) {
    if (pass == &passes.back() && passes.size() == 1) {
      break;
    }
    std::vector<Eigen::Vector3d> polyline = pass->moves;
    double offset = polyline.front().z() - start.z();
    for (Eigen::Vector3d& point : polyline) {
      point.z() = pass->ramp ? 0 : point.z() - offset;
    }
    const geom::Curve& reference = pass->ramp ? static_cast<const geom::Curve&>(plan) : curve;
    largest = std::max(largest, geom::measureDeviation(polyline, reference, {1e-6}).maxDeviation());
  }
  return largest;
}

struct ExampleCase {
  std::string file;
  std::string part;
};

class EveryExample : public testing::TestWithParam<ExampleCase> {};

TEST_P(EveryExample, EveryCutStaysWithinItsTolerance) {
  std::unique_ptr<CompiledExample> example = compile(GetParam().file, GetParam().part);
  ASSERT_TRUE(example);
  const std::vector<ir::CutGeometry>& cuts = example->lowered->function.cuts;
  ASSERT_FALSE(cuts.empty());
  // Arcs as the chords a controller's interpolation stays within (1e-5 mm).
  std::vector<std::vector<Pass>> passes =
      passesByCut(ir::flattenArcs(example->path, 1e-5), cuts.size());
  std::string program = backends::writeGcode(example->path, {});
  std::cout << GetParam().file << " " << GetParam().part << ": " << countG01(program)
            << " G01 blocks, " << cuts.size() << " cuts\n";
  for (std::size_t k = 0; k < cuts.size(); ++k) {
    ASSERT_FALSE(passes[k].empty()) << "cut " << k << " has no moves";
    ASSERT_TRUE(cuts[k].curve);
    EXPECT_TRUE(cuts[k].span.valid());
    if (std::isnan(cuts[k].tolerance)) {
      continue; // samples= or spacing= chose the points; there is no promise
    }
    double deviation = largestDeviation(passes[k], *cuts[k].curve);
    std::cout << "  cut " << k << ": " << passes[k].size() << " passes, deviation "
              << std::setprecision(9) << deviation << " mm, tolerance " << cuts[k].tolerance
              << " mm\n";
    EXPECT_LE(deviation, cuts[k].tolerance) << "cut " << k;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Examples, EveryExample,
    testing::Values(ExampleCase{"archimedean_spiral.cdl", ""}, ExampleCase{"bolt_circle.cdl", ""},
                    ExampleCase{"cam_profile.cdl", ""},
                    ExampleCase{"helix_bore.cdl", "bore_plate_mm"},
                    ExampleCase{"helix_bore.cdl", "bore_plate_inch"},
                    ExampleCase{"polar_contour.cdl", ""}, ExampleCase{"rosette_plate.cdl", ""},
                    ExampleCase{"s_profile.cdl", ""}),
    [](const testing::TestParamInfo<ExampleCase>& info) {
      std::string name = info.param.part.empty() ? info.param.file : info.param.part;
      return name.substr(0, name.find('.'));
    });

// The cut table follows the loops: the rosette's petals are one cut each,
// its bolt holes too, and only the finishing branch the if chose is cut.
TEST(EndToEnd, RosetteUnrollsLoopsAndChoosesOneBranch) {
  std::unique_ptr<CompiledExample> example = compile("rosette_plate.cdl");
  ASSERT_TRUE(example);
  const std::vector<ir::CutGeometry>& cuts = example->lowered->function.cuts;
  // Rough edge, 6 petals, 4 bolt holes, 1 finishing pass.
  ASSERT_EQ(cuts.size(), 12u);
  EXPECT_TRUE(std::isnan(cuts[7].tolerance)) << "the bolt holes use samples=";
  EXPECT_EQ(cuts[11].tolerance, 0.005) << "finish > 0 chose the first branch";
  // Petal i is rotated by 60 deg * i: its far end lies 30 mm out (16 or 12 mm long).
  for (int i = 0; i < 6; ++i) {
    const geom::Curve& petal = *cuts[1 + static_cast<std::size_t>(i)].curve;
    double reach = (i % 2 == 0 ? 16.0 : 12.0) + 14;
    double angle = std::numbers::pi / 3 * i;
    Eigen::Vector3d tip = petal.point(petal.domain().t0);
    EXPECT_NEAR(tip.x(), reach * std::cos(angle), 1e-9) << "petal " << i;
    EXPECT_NEAR(tip.y(), reach * std::sin(angle), 1e-9) << "petal " << i;
  }
  // The bolt holes: 36 samples on each pass, at 45 + 90 j deg.
  int holeFeeds = 0;
  std::vector<std::vector<Pass>> passes = passesByCut(example->path, cuts.size());
  for (std::size_t hole = 7; hole < 11; ++hole) {
    ASSERT_EQ(passes[hole].size(), 4u);
    EXPECT_EQ(passes[hole].front().moves.size(), 36u) << "the plunge and 35 steps";
    holeFeeds += static_cast<int>(passes[hole].front().moves.size());
  }
  EXPECT_EQ(holeFeeds, 4 * 36);
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
  std::vector<Eigen::Vector3d> points = {
      {25, 50, 0},           {42.8735, 24.1467, 0},  {70.5832, 72.3597, 0},
      {86.608, 165.3624, 0}, {112.4532, 38.3852, 0}, {132.4671, 35.1148, 0},
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

// The JIT target prints the same moves the G-code holds, its arcs as chords.
TEST(EndToEnd, JitAndGcodeShareTheToolPath) {
  std::optional<ir::ToolPath> path = compileExample("cam_profile.cdl");
  ASSERT_TRUE(path);
  std::string csv = backends::writeToolPathCsv(*path);
  std::size_t rows = 0;
  for (char c : csv) {
    rows += c == '\n' ? 1 : 0;
  }
  std::size_t moves = 0;
  std::size_t standingRapids = 0; // to where the tool is: no row
  ir::ToolPath flat = ir::flattenArcs(*path, backends::toolPathCsvArcSagitta);
  EXPECT_GT(flat.events.size(), path->events.size()); // the profile has arcs
  const ir::MachineEvent* last = nullptr;
  for (const ir::MachineEvent& event : flat.events) {
    bool rapid = event.kind == ir::MachineEvent::Kind::Rapid;
    if (!rapid && event.kind != ir::MachineEvent::Kind::Feed) {
      continue;
    }
    ++moves;
    standingRapids +=
        rapid && last != nullptr && last->x == event.x && last->y == event.y && last->z == event.z;
    last = &event;
  }
  EXPECT_GT(standingRapids, 0u);               // before each sweep's pass loop
  EXPECT_EQ(rows, moves - standingRapids + 1); // and the header
}

} // namespace
} // namespace cncc
