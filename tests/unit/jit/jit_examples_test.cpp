// Every part of every example that this version lowers, run by the
// interpreter and the JIT: the same events within 1e-9 mm.
#include "jit_test_support.h"

#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/ir/verifier.h"
#include "cncc/lowering/lowering.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

namespace cncc {
namespace {

struct ExampleParts {
  std::vector<std::string> compared;
  std::vector<std::string> notLowered;
};

// Checks one example and compares each part that lowers.
void compareExample(const std::filesystem::path& path, ExampleParts& parts) {
  frontend::SourceManager sources;
  frontend::DiagnosticEngine diagnostics;
  std::optional<frontend::FileId> file = sources.loadFile(path.string());
  ASSERT_TRUE(file) << "cannot read " << path;
  frontend::CheckOptions options;
  options.importPaths = {CNCC_STDLIB_DIR};
  frontend::CheckedProgram program = frontend::checkProgram(sources, *file, options, diagnostics);
  ASSERT_FALSE(diagnostics.hasErrors()) << path << " does not check";
  ASSERT_FALSE(program.parts.empty()) << path << " has no part";
  for (const frontend::PartItem* part : program.parts) {
    std::string name = path.filename().string() + ":" + std::string(part->name);
    frontend::DiagnosticEngine partDiagnostics;
    std::optional<ir::Function> function = ir::lowerPart(program, *part, partDiagnostics);
    if (!function) {
      parts.notLowered.push_back(name);
      continue;
    }
    ASSERT_TRUE(ir::verifyFunction(*function).empty()) << name;
    EXPECT_TRUE(jit_test::jitMatchesInterpreter(*function)) << name;
    parts.compared.push_back(name);
  }
}

TEST(JitExamples, EveryLoweredExampleMatchesTheInterpreter) {
  std::vector<std::filesystem::path> examples = jit_test::exampleFiles();
  ExampleParts parts;
  for (const std::filesystem::path& example : examples) {
    SCOPED_TRACE(example.string());
    compareExample(example, parts);
  }
  std::string compared;
  for (const std::string& name : parts.compared) {
    compared += " " + name;
  }
  std::string notLowered;
  for (const std::string& name : parts.notLowered) {
    notLowered += " " + name;
  }
  RecordProperty("compared", compared);
  RecordProperty("not_lowered", notLowered);
  // The three of REFERENCE-CASES.md lower today; more join as lowering grows.
  for (const char* expected : {"archimedean_spiral.cdl:archimedean_spiral",
                               "polar_contour.cdl:polar_contour", "s_profile.cdl:s_profile"}) {
    EXPECT_NE(std::find(parts.compared.begin(), parts.compared.end(), expected),
              parts.compared.end())
        << expected << " was not compared";
  }
}

// The same compiled part, run with other parameter values.
TEST(JitExamples, SProfileRunsAgainWithOtherParameters) {
  frontend::SourceManager sources;
  frontend::DiagnosticEngine diagnostics;
  std::optional<frontend::FileId> file =
      sources.loadFile(std::string(CNCC_SOURCE_DIR) + "/examples/s_profile.cdl");
  ASSERT_TRUE(file);
  frontend::CheckOptions options;
  options.importPaths = {CNCC_STDLIB_DIR};
  options.requirePart = true;
  frontend::CheckedProgram program = frontend::checkProgram(sources, *file, options, diagnostics);
  ASSERT_NE(program.selectedPart, nullptr);
  std::optional<ir::Function> function = ir::lowerPart(program, *program.selectedPart, diagnostics);
  ASSERT_TRUE(function);
  backends::CompiledFunction compiled(*function);
  for (double depth : {1.0, 2.5, 6.0}) {
    ir::InterpreterOptions run;
    run.parameters["depth"] = depth;
    run.parameters["w6"] = 2;
    ir::ToolPath expected = ir::interpret(*function, run);
    EXPECT_TRUE(jit_test::samePaths(expected, compiled.run(run))) << "depth " << depth;
  }
}

} // namespace
} // namespace cncc
