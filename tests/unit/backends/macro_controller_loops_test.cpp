// Macro programs that evaluate the curve on the controller: the programs
// the m80 and fanuc targets print (lowered with macroLoweringOptions, the
// default pipeline) run in the virtual controller with the part parameters
// edited there, and the executed path is measured against the true curve
// built with the same values. The figures of bench/RESULTS.md ("Macro
// programs") are asserted so that a regression fails.
#include "cncc/backends/controller_profile.h"
#include "cncc/backends/macro_program.h"
#include "cncc/backends/program_execution.h"
#include "cncc/backends/target_info.h"
#include "cncc/backends/verification.h"
#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/verifier.h"
#include "cncc/lowering/lowering.h"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>

namespace cncc::backends {
namespace {

using Parameters = frontend::ParameterDefines;

struct CheckedPart {
  frontend::SourceManager sources;
  frontend::DiagnosticEngine diagnostics;
  std::optional<frontend::CheckedProgram> program;
};

std::string exampleText(const std::string& name) {
  std::ifstream file(std::string(CNCC_SOURCE_DIR) + "/examples/" + name);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

std::unique_ptr<CheckedPart> checkPart(const std::string& text, const Parameters& defines) {
  auto part = std::make_unique<CheckedPart>();
  frontend::FileId file = part->sources.addFile("part.cdl", text);
  frontend::CheckOptions options;
  options.importPaths = {CNCC_STDLIB_DIR};
  options.requirePart = true;
  options.defines = defines;
  part->program = frontend::checkProgram(part->sources, file, options, part->diagnostics);
  if (part->diagnostics.hasErrors() || part->program->selectedPart == nullptr) {
    ADD_FAILURE() << "the part does not check";
    return nullptr;
  }
  return part;
}

struct Compiled {
  MacroProgram program;
  std::unique_ptr<CheckedPart> part;
};

// What `cncc PART -t TARGET` prints.
Compiled compile(const std::string& text, const std::string& target, bool callable = false,
                 bool common = false) {
  Compiled compiled{{}, checkPart(text, {})};
  if (!compiled.part) {
    return compiled;
  }
  const frontend::PartItem& part = *compiled.part->program->selectedPart;
  const ControllerProfile& profile = *findControllerProfile(target);
  bool inches = ir::partUnits(part) == ir::PartUnits::Inches;
  ir::LoweringOptions lowering = macroLoweringOptions(profile, inches);
  std::optional<ir::Function> function =
      ir::lowerPart(*compiled.part->program, part, compiled.part->diagnostics, lowering);
  if (!function) {
    ADD_FAILURE() << "the part does not lower";
    return compiled;
  }
  ir::runDefaultPipeline(*function);
  EXPECT_TRUE(ir::runPasses(*function, lowering.passesBeforePrinting, {}));
  std::vector<std::string> problems = ir::verifyFunction(*function);
  EXPECT_TRUE(problems.empty()) << problems.front();
  MacroProgramOptions options;
  options.sourceName = "part.cdl";
  options.partName = part.name;
  options.inches = inches;
  options.callable = callable;
  options.parametersInCommon = common;
  compiled.program = writeMacroProgram(*function, profile, options);
  EXPECT_TRUE(compiled.program.errors.empty()) << compiled.program.errors.front();
  return compiled;
}

// The program run with `values` set as the operator (or the caller) would,
// measured against the part built with those values.
VerificationReport run(const std::string& text, const std::string& target, const Parameters& values,
                       bool callable = false, bool common = false) {
  Compiled compiled = compile(text, target, callable, common);
  std::unique_ptr<CheckedPart> truth = checkPart(text, values);
  if (compiled.program.text.empty() || !truth) {
    ADD_FAILURE() << "no program";
    return {};
  }
  frontend::DiagnosticEngine diagnostics;
  std::optional<ir::LoweredPart> lowered =
      ir::lowerPartWithCuts(*truth->program, *truth->program->selectedPart, diagnostics);
  if (!lowered) {
    ADD_FAILURE() << "the true part does not lower";
    return {};
  }
  const frontend::PartItem& part = *truth->program->selectedPart;
  std::vector<std::string> errors;
  std::vector<int> variables = macroParameterVariables(
      part.parameters.size(), *findControllerProfile(target), common, errors);
  ExecutionRequest execution;
  execution.text = compiled.program.text;
  execution.passing = callable ? ParameterPassing::MacroArguments
                      : common ? ParameterPassing::CommonVariables
                               : ParameterPassing::EditedDefaults;
  execution.callable = callable;
  for (std::size_t i = 0; i < part.parameters.size(); ++i) {
    auto found = values.find(std::string(part.parameters[i].name));
    if (found != values.end()) {
      execution.parameters.push_back({found->first, variables[i], found->second});
    }
  }
  ExecutedPath reference = executedPathOfToolPath(ir::interpret(lowered->function));
  StatisticsOptions options;
  VerificationReport report =
      verifyProgram({target, findTargetInfo(target)->execute, std::move(execution),
                     std::move(reference), lowered->function.cuts},
                    options);
  EXPECT_FALSE(report.failure) << formatVerification(report, options);
  EXPECT_TRUE(report.missedCuts.empty()) << formatVerification(report, options);
  EXPECT_EQ(report.stray.count, 0u) << formatVerification(report, options);
  EXPECT_EQ(report.statistics.cuts.size(), lowered->function.cuts.size());
  for (const CutDeviation& cut : report.statistics.cuts) {
    EXPECT_LE(cut.maxDeviation, lowered->function.cuts[cut.cut].tolerance)
        << formatVerification(report, options);
  }
  return report;
}

struct ParameterCase {
  std::string example;
  std::string target;
  Parameters values;
  bool callable = false;
  bool common = false;
};

void PrintTo(const ParameterCase& test, std::ostream* out) {
  *out << test.example << " -t " << test.target << (test.callable ? " --macro" : "")
       << (test.common ? " --params=common" : "");
  for (const auto& [name, value] : test.values) {
    *out << " -D " << name << "=" << value;
  }
}

class MacroControllerLoops : public ::testing::TestWithParam<ParameterCase> {};

TEST_P(MacroControllerLoops, HoldTheToleranceForTheValuesTheProgramRunsWith) {
  const ParameterCase& test = GetParam();
  VerificationReport report =
      run(exampleText(test.example), test.target, test.values, test.callable, test.common);
  EXPECT_TRUE(report.passed());
}

INSTANTIATE_TEST_SUITE_P(
    Examples, MacroControllerLoops,
    ::testing::Values(ParameterCase{"s_profile.cdl", "m80", {}},
                      ParameterCase{"s_profile.cdl", "m80", {{"w6", 1}}},
                      ParameterCase{"s_profile.cdl", "m80", {{"w6", 8}}},
                      ParameterCase{"s_profile.cdl", "m80", {{"w6", 0.4}, {"depth", 2.5}}},
                      ParameterCase{"s_profile.cdl", "fanuc", {{"w6", 8}}, true},
                      ParameterCase{"s_profile.cdl", "m80", {{"w6", 2}}, false, true},
                      ParameterCase{"archimedean_spiral.cdl", "fanuc", {}},
                      ParameterCase{"archimedean_spiral.cdl", "fanuc", {{"a", 3}, {"b", 0.5}}},
                      ParameterCase{"archimedean_spiral.cdl", "fanuc", {{"a", 0.5}, {"b", 4}}},
                      ParameterCase{"archimedean_spiral.cdl", "m80", {{"a", 0.5}, {"b", 4}}, true},
                      // The tool centre beside the curve, at three diameters.
                      ParameterCase{"worn_cutter.cdl", "fanuc", {{"diameter", 1}}},
                      ParameterCase{"worn_cutter.cdl", "m80", {{"diameter", 3.96}}},
                      ParameterCase{"worn_cutter.cdl", "fanuc", {{"diameter", 4.6}}, true}));

// A diameter the curve cannot take: the program stops with its alarm
// before it cuts (the polar contour's outside bends at 2.331 mm at least).
TEST(MacroControllerLoops, ToolTooLargeForTheCurveRaisesItsAlarm) {
  std::string text = exampleText("worn_cutter.cdl");
  Compiled compiled = compile(text, "fanuc", true);
  ASSERT_FALSE(compiled.program.text.empty());
  EXPECT_NE(compiled.program.text.find("IF [#2 GE 2.3313] THEN #3000=1"), std::string::npos)
      << compiled.program.text;
  for (double diameter : {4.664, 4.7, 8.0}) {
    ExecutionRequest execution;
    execution.text = compiled.program.text;
    execution.passing = ParameterPassing::MacroArguments;
    execution.callable = true;
    execution.parameters.push_back({"diameter", 1, diameter});
    ProgramExecution executed = findTargetInfo("fanuc")->execute(execution);
    ASSERT_TRUE(executed.failure) << diameter;
    EXPECT_NE(executed.failure->message.find("THE TOOL RADIUS MUST BE BELOW 2.3313"),
              std::string::npos)
        << executed.failure->message;
    for (const ExecutedMove& move : executed.path.moves) {
      EXPECT_TRUE(move.rapid) << "it cut before the alarm at " << diameter;
    }
  }
}

// Constant geometry: the S-profile's curve with its weights written out.
const char* constantNurbs(const std::string& weights) {
  static std::string text;
  text = "part s(depth = 1) {\n  units mm\n  tool 1 diameter=10 spindle=3000 feed=300\n"
         "  safe z=5\n  let P = [(25,50), (42.8735,24.1467), (70.5832,72.3597), "
         "(86.608,165.3624), (112.4532,38.3852), (132.4671,35.1148), (175,150)]\n"
         "  curve nurbs(order=4, points=P, weights=" +
         weights + ") tolerance=0.01\n}\n";
  return text.c_str();
}

TEST(MacroControllerLoops, SProfileFigures) {
  Compiled compiled = compile(exampleText("s_profile.cdl"), "m80");
  ASSERT_FALSE(compiled.program.text.empty());
  EXPECT_LE(compiled.program.statistics.variables, 40);
  // 60, and the set-up blocks: G54, G05 P10000 on and G05 P0 off, the
  // retract G91 G28 Z0. and G90; the alarm for a w6 that is not positive;
  // and since the two spans w6 moves take a step computed at each point
  // (rational_span_walk.cpp: 4.5 times fewer points at w6 = 8 than one
  // count per span), 36 blocks in each of their loops. About the
  // hand-written macro program's 135 blocks (REFERENCE-CASES.md).
  EXPECT_LE(compiled.program.statistics.blocks, 136);
  EXPECT_EQ(compiled.program.text.find("#["), std::string::npos) << "no tables";
  // w6 stays editable: the program reads it.
  EXPECT_NE(compiled.program.text.find("#3*"), std::string::npos);
}

TEST(MacroControllerLoops, SpiralFigures) {
  Compiled compiled = compile(exampleText("archimedean_spiral.cdl"), "fanuc");
  ASSERT_FALSE(compiled.program.text.empty());
  // The hand-written macro of the reference case: 0.38 KB.
  EXPECT_LE(compiled.program.statistics.bytesWithoutComments, 380u);
  EXPECT_NE(compiled.program.text.find("#1=1."), std::string::npos);
  EXPECT_NE(compiled.program.text.find("#2=2."), std::string::npos);
}

// The operations the controller ran in the loops per point they cut, not
// counting the one test of each loop's condition that ends it.
double operationsPerPoint(const std::string& text, const std::string& target) {
  VerificationReport report = run(text, target, {});
  EXPECT_TRUE(report.operations);
  if (!report.operations) {
    return 0;
  }
  Compiled compiled = compile(text, target);
  std::size_t loops = 0;
  for (std::size_t at = compiled.program.text.find("WHILE"); at != std::string::npos;
       at = compiled.program.text.find("WHILE", at + 1)) {
    ++loops;
  }
  EXPECT_GT(report.operations->feedMoves, 100u);
  return static_cast<double>(report.operations->operations.total() - loops) /
         static_cast<double>(report.operations->feedMoves);
}

TEST(MacroControllerLoops, PolynomialSpanCostsAtMostFifteenOperationsAPoint) {
  EXPECT_LE(operationsPerPoint(constantNurbs("[1,1,1,1,1,1,1]"), "m80"), 15.0);
}

TEST(MacroControllerLoops, RationalSpanCostsAtMostTwentyFourOperationsAPoint) {
  // One rational cubic span (clamped, four control points).
  const char* text = "part r(depth = 1) {\n  units mm\n  tool 1 diameter=10 feed=300\n"
                     "  safe z=5\n  curve nurbs(order=4, points=[(0,0), (30,80), (90,-40), "
                     "(120,30)], weights=[1,2.5,0.6,1.4]) tolerance=0.01\n}\n";
  EXPECT_LE(operationsPerPoint(text, "fanuc"), 24.0);
}

TEST(MacroControllerLoops, ConstantGeometryHasCompileTimeStepCounts) {
  Compiled compiled = compile(constantNurbs("[1,1,1,1,1,3,1]"), "fanuc");
  ASSERT_FALSE(compiled.program.text.empty());
  // Every loop bound is a literal: nothing about the curve is left to compute.
  std::istringstream lines(compiled.program.text);
  std::string line;
  int loops = 0;
  while (std::getline(lines, line)) {
    if (line.starts_with("WHILE")) {
      ++loops;
      EXPECT_EQ(line.find("LE #"), std::string::npos) << line;
    }
  }
  EXPECT_EQ(loops, 4); // one per knot span
}

TEST(MacroControllerLoops, ToleranceBelowTheIncrementRoundingIsAnError) {
  std::string text = exampleText("archimedean_spiral.cdl");
  text.replace(text.find("tolerance=0.005"), 15, "tolerance=0.0005");
  std::unique_ptr<CheckedPart> part = checkPart(text, {});
  ASSERT_TRUE(part);
  std::optional<ir::Function> function =
      ir::lowerPart(*part->program, *part->program->selectedPart, part->diagnostics,
                    macroLoweringOptions(*findControllerProfile("fanuc"), false));
  EXPECT_FALSE(function);
  EXPECT_TRUE(part->diagnostics.hasErrors());
}

} // namespace
} // namespace cncc::backends
