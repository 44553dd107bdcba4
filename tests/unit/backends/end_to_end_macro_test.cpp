// Every example, every part, on m80 and fanuc: compiled once with its
// defaults as the macro backends compile it, then run on the virtual
// controller with the defaults and with other parameter values set as the
// operator sets them (the lines that set them edited, or G65 arguments for
// a callable macro), and measured against the true curves of the part with
// those values (verifyProgram, as `cncc verify` does). Every cut must keep
// to its tolerance and the controller must accept the program.
#include "target_compile.h"

#include "cncc/backends/controller_profile.h"
#include "cncc/backends/macro_program.h"
#include "cncc/backends/target_info.h"
#include "cncc/backends/verification.h"
#include "cncc/backends/virtual_controller.h"
#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/verifier.h"
#include "cncc/lowering/lowering.h"

#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <map>
#include <memory>
#include <ostream>
#include <string>

namespace cncc::backends {
namespace {

using Parameters = frontend::ParameterDefines;

struct MacroCase {
  std::string file;
  std::string part; // empty: the file's only part
  Parameters parameters;
  std::string target;
  bool callable = false; // --macro: the values as G65 arguments
};

void PrintTo(const MacroCase& test, std::ostream* out) {
  *out << test.file << (test.part.empty() ? "" : " -p " + test.part) << " -t " << test.target
       << (test.callable ? " --macro" : "");
  for (const auto& [name, value] : test.parameters) {
    *out << " -D " << name << "=" << value;
  }
}

using testing::CheckedExample;

// The case's example (or a test part given by its path in the source tree)
// checked with `defines`.
std::unique_ptr<CheckedExample> checkExample(const MacroCase& test, const Parameters& defines) {
  std::string path = test.file.starts_with("tests/") ? test.file : "examples/" + test.file;
  return testing::checkSource(path, test.part, defines);
}

// The program the macro target prints for the part's defaults, compiled
// through its TargetInfo as `cncc FILE -t TARGET [--macro]` compiles it.
std::optional<std::string> macroProgram(const CheckedExample& example, const MacroCase& test) {
  const TargetInfo& target = *findTargetInfo(test.target);
  TargetSettings settings = testing::defaultSettings(target, *example.program->selectedPart);
  settings.sourceName = test.file.substr(test.file.rfind('/') + 1);
  settings.macroCall = test.callable;
  std::optional<testing::TargetCompilation> compiled =
      testing::compileThroughTarget(target, example, settings);
  if (!compiled || !compiled->printed.problems.empty()) {
    return std::nullopt;
  }
  return compiled->printed.text;
}

std::vector<ParameterValue> parameterValues(const frontend::PartItem& part, const MacroCase& test) {
  std::vector<std::string> errors;
  std::vector<int> variables = macroParameterVariables(
      part.parameters.size(), *findControllerProfile(test.target), false, errors);
  EXPECT_TRUE(errors.empty());
  std::vector<ParameterValue> values;
  for (std::size_t i = 0; i < part.parameters.size() && i < variables.size(); ++i) {
    auto found = test.parameters.find(std::string(part.parameters[i].name));
    if (found != test.parameters.end()) {
      values.push_back({found->first, variables[i], found->second});
    }
  }
  EXPECT_EQ(values.size(), test.parameters.size()) << "a parameter the part does not have";
  return values;
}

// The case's program, compiled for the defaults, run with the case's
// values and measured against the part with those values.
struct CaseRun {
  VerificationReport report;
  std::vector<ir::CutGeometry> cuts;
  std::string summary;
};

std::optional<CaseRun> runCase(const MacroCase& test) {
  std::unique_ptr<CheckedExample> compiled = checkExample(test, {});
  std::unique_ptr<CheckedExample> truth = checkExample(test, test.parameters);
  if (!compiled || !truth) {
    return std::nullopt;
  }
  std::optional<std::string> text = macroProgram(*compiled, test);
  frontend::DiagnosticEngine diagnostics;
  std::optional<ir::LoweredPart> lowered =
      ir::lowerPartWithCuts(*truth->program, *truth->program->selectedPart, diagnostics);
  if (!text || !lowered) {
    ADD_FAILURE() << "the part does not compile";
    return std::nullopt;
  }
  ExecutedPath reference = executedPathOfToolPath(ir::interpret(lowered->function));

  ExecutionRequest execution;
  execution.text = *text;
  execution.passing =
      test.callable ? ParameterPassing::MacroArguments : ParameterPassing::EditedDefaults;
  execution.callable = test.callable;
  execution.parameters = parameterValues(*truth->program->selectedPart, test);
  StatisticsOptions options;
  options.unit =
      ir::partUnits(*truth->program->selectedPart) == ir::PartUnits::Inches ? "in" : "mm";
  CaseRun run;
  run.cuts = lowered->function.cuts;
  run.report = verifyProgram({test.target, findTargetInfo(test.target)->execute,
                              std::move(execution), std::move(reference), lowered->function.cuts},
                             options);
  run.summary = formatVerification(run.report, options);
  return run;
}

class MacroEndToEnd : public ::testing::TestWithParam<MacroCase> {};

TEST_P(MacroEndToEnd, KeepsEveryCutWithinItsTolerance) {
  std::optional<CaseRun> run = runCase(GetParam());
  ASSERT_TRUE(run);
  const VerificationReport& report = run->report;
  const std::string& summary = run->summary;

  ASSERT_FALSE(report.failure) << summary;
  EXPECT_TRUE(report.missedCuts.empty()) << summary;
  EXPECT_EQ(report.stray.count, 0u) << summary;
  ASSERT_EQ(report.statistics.cuts.size(), run->cuts.size());
  for (const CutDeviation& cut : report.statistics.cuts) {
    // NaN: samples= or spacing= chose the points, and the part promises no
    // tolerance; the cut must still lie on the part's path (stray above).
    double tolerance = run->cuts[cut.cut].tolerance;
    if (!std::isnan(tolerance)) {
      EXPECT_LE(cut.maxDeviation, tolerance) << "cut " << cut.cut + 1 << "\n" << summary;
    }
  }
  EXPECT_TRUE(report.passed()) << summary;
}

class MacroFixedParameters : public ::testing::TestWithParam<MacroCase> {};

// The program was compiled with these parameters' defaults built in (loop
// counts, sampled curves): edited, it must stop with the alarm that names
// one of them rather than cut a part for the defaults.
TEST_P(MacroFixedParameters, RaisesTheAlarmInsteadOfCuttingTheDefaultPart) {
  const MacroCase& test = GetParam();
  std::optional<CaseRun> run = runCase(test);
  ASSERT_TRUE(run);
  ASSERT_TRUE(run->report.failure) << run->summary;
  const std::string& message = run->report.failure->message;
  EXPECT_NE(message.find("alarm 3001"), std::string::npos) << message;
  bool named = false;
  for (const auto& [name, value] : test.parameters) {
    std::string upper;
    for (char c : name) {
      upper += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    }
    named = named || message.find(upper + " IS FIXED AT") != std::string::npos;
  }
  EXPECT_TRUE(named) << message;
  EXPECT_FALSE(run->report.passed());
}

// Each example and part with its defaults and other parameter sets: `sets`
// keep to every tolerance; `fixed` edit parameters the controller cannot
// recompute, and the program must refuse them with its alarm (every
// example keeps its parameters editable; a test part shows the alarm).
struct ExampleParameters {
  std::string file;
  std::string part;
  std::vector<Parameters> sets;
  std::vector<Parameters> fixed;
};

const std::vector<ExampleParameters>& exampleParameters() {
  static const std::vector<ExampleParameters> examples = {
      {"archimedean_spiral.cdl", "", {{}, {{"a", 3}, {"b", 0.5}}, {{"a", 0.5}, {"b", 4}}}, {}},
      {"bolt_circle.cdl",
       "",
       {{}, {{"holes", 8}, {"pcd", 100}}, {{"hole", 12}, {"depth", 4.5}, {"step", 2}}},
       {}},
      {"cam_profile.cdl",
       "",
       {{}, {{"base", 25}, {"lift", 5}}, {{"base", 18}, {"lift", 10}, {"top_end", 2.5}}},
       {}},
      {"helix_bore.cdl",
       "bore_plate_mm",
       {{},
        {{"bore_diameter", 10}, {"depth", 6}},
        {{"depth", 12}, {"pitch", 1}},
        {{"depth", 7}, {"pitch", 2}}},
       {}},
      {"helix_bore.cdl",
       "bore_plate_inch",
       {{}, {{"bore_diameter", 0.4375}}, {{"depth", 0.5}, {"pitch", 0.05}}},
       {}},
      {"polar_contour.cdl", "", {{}, {{"depth", 3}}, {{"depth", 9}}}, {}},
      {"rosette_plate.cdl",
       "",
       {{},
        {{"petals", 8}, {"holes", 6}},
        {{"petals", 4}, {"hole", 5}, {"finish", 0}},
        {{"petals", 2}, {"holes", 0}, {"finish", 1}}},
       {}},
      // w6 from 0.3 to 1000: the spans it weighs take a step computed at
      // each point (rational_span_walk.cpp), which keeps the tolerance at any.
      {"s_profile.cdl",
       "",
       {{}, {{"w6", 0.3}}, {{"w6", 1}}, {{"w6", 8}}, {{"w6", 1000}}, {{"depth", 2}, {"step", 0.5}}},
       {}},
      {"tests/unit/backends/parts/fixed_loop_bound.cdl",
       "",
       {{}, {{"depth", 3}}},
       {{{"count", 4}}, {{"count", 2}, {"depth", 1}}}},
  };
  return examples;
}

// Every set on both targets, and a callable macro given the last set with
// parameters as G65 arguments.
std::vector<MacroCase> macroCases(std::vector<Parameters> ExampleParameters::*which) {
  std::vector<MacroCase> cases;
  for (const ExampleParameters& example : exampleParameters()) {
    const std::vector<Parameters>& sets = example.*which;
    if (sets.empty()) {
      continue;
    }
    for (const char* target : {"m80", "fanuc"}) {
      for (const Parameters& set : sets) {
        cases.push_back({example.file, example.part, set, target, false});
      }
      if (!sets.back().empty()) {
        cases.push_back({example.file, example.part, sets.back(), target, true});
      }
    }
  }
  return cases;
}

std::string caseName(const ::testing::TestParamInfo<MacroCase>& info) {
  const MacroCase& test = info.param;
  std::string stem = test.file.substr(test.file.rfind('/') + 1);
  std::string name = stem.substr(0, stem.find('.')) + "_" + test.part + "_" + test.target +
                     (test.callable ? "_macro" : "");
  for (const auto& [parameter, value] : test.parameters) {
    name += "_" + parameter + std::to_string(static_cast<int>(value * 10000));
  }
  for (char& c : name) {
    c = std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  }
  return name + "_" + std::to_string(info.index);
}

// The circular and helical moves the controller executes: the helices of
// helix_bore, whose turns (depth / pitch) are parameters, in half-turn
// blocks, at most two per turn; each floor circle in one block; the bolt
// circle's holes one block per pass.
std::size_t executedArcs(const MacroCase& test) {
  std::unique_ptr<CheckedExample> example = checkExample(test, test.parameters);
  if (!example) {
    return 0;
  }
  std::optional<std::string> program = macroProgram(*example, test);
  if (!program) {
    return 0;
  }
  sim::SimulationResult run = sim::simulateProgram(*program, *findControllerProfile(test.target));
  EXPECT_FALSE(run.error) << run.error->what();
  std::size_t arcs = 0;
  for (const sim::ExecutedEvent& event : run.path.events) {
    arcs += event.kind == sim::ExecutedEvent::Kind::ClockwiseArc ||
                    event.kind == sim::ExecutedEvent::Kind::CounterclockwiseArc
                ? 1
                : 0;
  }
  return arcs;
}

TEST(NativeArcs, HelicesInHalfTurnsAndCirclesInOneBlockOnTheController) {
  for (const char* target : {"fanuc", "m80"}) {
    // 3 holes: 6 turns as 12 half turns, and a floor circle.
    EXPECT_EQ(executedArcs({"helix_bore.cdl", "bore_plate_mm", {}, target}), 3u * (12 + 1));
    // 3.5 turns as 7 half turns.
    EXPECT_EQ(
        executedArcs({"helix_bore.cdl", "bore_plate_mm", {{"depth", 7}, {"pitch", 2}}, target}),
        3u * (7 + 1));
    // 6 holes of 3 passes, then 8 holes of 2 passes (4.5 mm in steps of 2.5).
    EXPECT_EQ(executedArcs({"bolt_circle.cdl", "", {}, target}), 6u * 3);
    EXPECT_EQ(executedArcs(
                  {"bolt_circle.cdl", "", {{"holes", 8}, {"depth", 4.5}, {"step", 2.5}}, target}),
              8u * 2);
  }
}

INSTANTIATE_TEST_SUITE_P(Examples, MacroEndToEnd,
                         ::testing::ValuesIn(macroCases(&ExampleParameters::sets)), caseName);
INSTANTIATE_TEST_SUITE_P(Examples, MacroFixedParameters,
                         ::testing::ValuesIn(macroCases(&ExampleParameters::fixed)), caseName);

} // namespace
} // namespace cncc::backends
