// --arcs on the controller-side targets. m80 and fanuc: every example, and
// the spiral of tests/golden/arcs with its numbers written in, compiled as
// the macro targets compile them with --arcs (a cut whose curve depends on a
// part parameter keeps its loops), run on the virtual controller and
// measured against the true curves (verifyProgram, as `cncc verify` does).
// LinuxCNC: the spiral run by LinuxCNC's own interpreter (`rs274 -g`), its
// ARC_FEED calls measured against the curve.
#include "linuxcnc_rs274.h"
#include "target_compile.h"

#include "cncc/backends/controller_profile.h"
#include "cncc/backends/linuxcnc_canon.h"
#include "cncc/backends/linuxcnc_program.h"
#include "cncc/backends/macro_program.h"
#include "cncc/backends/target_info.h"
#include "cncc/backends/verification.h"
#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/geom/deviation.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/verifier.h"
#include "cncc/lowering/lowering.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>
#include <string_view>

namespace cncc::backends {
namespace {

const std::string spiralFile = "tests/golden/arcs/spiral_fanuc.cdl";

using Checked = testing::CheckedExample;

// The source at `file` (from the source tree's root) checked, `part` selected.
std::unique_ptr<Checked> check(const std::string& file, const std::string& part) {
  return testing::checkSource(file, part);
}

// The part compiled for `target` with --arcs, as `cncc FILE -t TARGET --arcs`.
std::optional<testing::TargetCompilation>
compileWithArcs(const Checked& checked, const std::string& target, const std::string& sourceName) {
  const TargetInfo& info = *findTargetInfo(target);
  TargetSettings settings = testing::defaultSettings(info, *checked.program->selectedPart);
  settings.sourceName = sourceName;
  settings.arcs = true;
  std::optional<testing::TargetCompilation> compiled =
      testing::compileThroughTarget(info, checked, settings);
  if (compiled && !compiled->printed.problems.empty()) {
    return std::nullopt;
  }
  return compiled;
}

// Blocks that end an arc: `G2 X.. Y.. I.. J..`, or the same without the
// motion word in force (plain string tests: std::regex warns under the
// sanitizers' GCC headers).
bool isArcBlock(std::string_view line) {
  for (std::string_view motion : {"G2 ", "G3 ", "G02 ", "G03 "}) {
    if (line.starts_with(motion)) {
      line.remove_prefix(motion.size());
    }
  }
  return line.starts_with("X") && line.find(" I") != std::string_view::npos &&
         line.find(" J") != std::string_view::npos;
}

std::size_t arcBlockCount(const std::string& text) {
  std::size_t count = 0;
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    end = end == std::string::npos ? text.size() : end;
    count += isArcBlock(std::string_view(text).substr(start, end - start)) ? 1 : 0;
    start = end + 1;
  }
  return count;
}

struct ArcCase {
  std::string file;
  std::string part;
  std::string target;
};

void PrintTo(const ArcCase& test, std::ostream* out) {
  *out << test.file << (test.part.empty() ? "" : " -p " + test.part) << " -t " << test.target
       << " --arcs";
}

struct MacroRun {
  std::string text;
  VerificationReport report;
  std::vector<ir::CutGeometry> cuts;
};

std::optional<MacroRun> runMacro(const ArcCase& test) {
  std::unique_ptr<Checked> checked = check(test.file, test.part);
  if (!checked) {
    return std::nullopt;
  }
  const frontend::PartItem& part = *checked->program->selectedPart;
  bool inches = ir::partUnits(part) == ir::PartUnits::Inches;
  std::optional<testing::TargetCompilation> compiled =
      compileWithArcs(*checked, test.target, test.file);
  if (!compiled) {
    return std::nullopt;
  }
  const std::string& text = compiled->printed.text;
  // The reference: the part run on the host as the gcode target lowers it.
  frontend::DiagnosticEngine diagnostics;
  std::optional<ir::LoweredPart> host = ir::lowerPartWithCuts(*checked->program, part, diagnostics);
  if (!host) {
    ADD_FAILURE() << "the part does not lower for the host";
    return std::nullopt;
  }
  ExecutionRequest execution;
  execution.text = text;
  execution.passing = ParameterPassing::EditedDefaults;
  StatisticsOptions statistics;
  statistics.unit = inches ? "in" : "mm";
  MacroRun run;
  run.text = text;
  run.cuts = host->function.cuts;
  run.report =
      verifyProgram({test.target, findTargetInfo(test.target)->execute, std::move(execution),
                     executedPathOfToolPath(ir::interpret(host->function)), run.cuts},
                    statistics);
  return run;
}

void expectWithinTolerances(const MacroRun& run) {
  std::string summary = formatVerification(run.report, {});
  ASSERT_FALSE(run.report.failure) << summary;
  EXPECT_TRUE(run.report.missedCuts.empty()) << summary;
  EXPECT_EQ(run.report.stray.count, 0u) << summary;
  ASSERT_EQ(run.report.statistics.cuts.size(), run.cuts.size()) << summary;
  for (const CutDeviation& cut : run.report.statistics.cuts) {
    double tolerance = run.cuts[cut.cut].tolerance;
    if (!std::isnan(tolerance)) {
      EXPECT_LE(cut.maxDeviation, tolerance) << "cut " << cut.cut + 1 << "\n" << summary;
    }
  }
  EXPECT_TRUE(run.report.passed()) << summary;
}

class MacroArcs : public ::testing::TestWithParam<ArcCase> {};

TEST_P(MacroArcs, KeepsEveryCutWithinItsTolerance) {
  std::optional<MacroRun> run = runMacro(GetParam());
  ASSERT_TRUE(run);
  expectWithinTolerances(*run);
}

std::vector<ArcCase> macroCases() {
  std::vector<ArcCase> cases;
  const std::pair<const char*, const char*> examples[] = {{"archimedean_spiral.cdl", ""},
                                                          {"cam_profile.cdl", ""},
                                                          {"helix_bore.cdl", "bore_plate_mm"},
                                                          {"helix_bore.cdl", "bore_plate_inch"},
                                                          {"polar_contour.cdl", ""},
                                                          {"rosette_plate.cdl", ""},
                                                          {"s_profile.cdl", ""}};
  for (const char* target : {"m80", "fanuc"}) {
    for (const auto& [file, part] : examples) {
      cases.push_back({std::string("examples/") + file, part, target});
    }
    cases.push_back({spiralFile, "", target});
  }
  return cases;
}

std::string caseName(const ::testing::TestParamInfo<ArcCase>& info) {
  std::string name = info.param.file.substr(info.param.file.rfind('/') + 1);
  name = name.substr(0, name.find('.')) + "_" + info.param.part + "_" + info.param.target;
  for (char& c : name) {
    c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  }
  return name;
}

INSTANTIATE_TEST_SUITE_P(Examples, MacroArcs, ::testing::ValuesIn(macroCases()), caseName);

TEST(MacroArcs, PrintsTheSpiralAsAtMostThirtyArcs) {
  for (const char* target : {"m80", "fanuc"}) {
    std::optional<MacroRun> run = runMacro({spiralFile, "", target});
    ASSERT_TRUE(run);
    std::size_t arcs = arcBlockCount(run->text);
    EXPECT_GT(arcs, 0u) << run->text;
    EXPECT_LE(arcs, 30u) << run->text;
    EXPECT_EQ(run->text.find("WHILE"), std::string::npos) << "the spiral kept its loop";
    expectWithinTolerances(*run);
  }
}

TEST(LinuxcncArcs, Rs274CutsTheSpiralArcsWithinItsTolerance) {
  CNCC_FIND_RS274(rs274);
  std::unique_ptr<Checked> checked = check(spiralFile, "");
  ASSERT_TRUE(checked);
  std::optional<testing::TargetCompilation> compiled =
      compileWithArcs(*checked, "linuxcnc", "spiral.cdl");
  ASSERT_TRUE(compiled);
  const PrintedProgram& program = compiled->printed;
  std::size_t arcs = arcBlockCount(program.text);
  EXPECT_GT(arcs, 0u) << program.text;
  EXPECT_LE(arcs, 30u) << program.text;

  const ir::ToolPath& host = compiled->programmed;
  testing::Rs274Run run = testing::runRs274(*rs274, program.text, testing::toolTableOf(host));
  ASSERT_EQ(run.exitCode, 0) << run.errors << run.canon;
  std::size_t arcFeeds = 0;
  for (std::size_t at = run.canon.find("ARC_FEED"); at != std::string::npos;
       at = run.canon.find("ARC_FEED", at + 1)) {
    ++arcFeeds;
  }
  EXPECT_EQ(arcFeeds, arcs) << run.canon;
  ExecutedPath executed = readLinuxcncCanon(run.canon);
  // The lap: the plunge's end (the curve's start at z 0), then the ends of
  // the feed moves at z 0 until the retract.
  std::vector<Eigen::Vector3d> lap;
  for (const ExecutedMove& move : executed.moves) {
    if (!move.rapid && std::fabs(move.end.z()) < 1e-9) {
      lap.push_back(move.end);
    }
  }
  ASSERT_GE(lap.size(), arcs + 1);
  const ir::CutGeometry& cut = compiled->lowered.function.cuts.front();
  double deviation = geom::measureDeviation(lap, *cut.curve, {1e-6}).maxDeviation();
  // rs274 prints four decimals: half a unit of the last on each axis.
  EXPECT_LE(deviation, cut.tolerance + 0.5e-4 * std::sqrt(3.0));
  std::cout << "linuxcnc spiral: " << arcs << " arcs, deviation " << deviation << " mm\n";
}

} // namespace
} // namespace cncc::backends
