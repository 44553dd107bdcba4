// The parameters whose defaults the lowering builds into the program
// (LoweredPart::fixedParameters): a loop bound and a sampled polar curve's
// radius fix theirs, a sweep depth computed on the controller does not; the
// warning is given for controller-side targets only.
#include "cncc/ir/lowering.h"

#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>

namespace cncc::ir {
namespace {

struct Lowered {
  frontend::SourceManager sources;
  frontend::DiagnosticEngine diagnostics;
  std::optional<frontend::CheckedProgram> program;
  std::optional<LoweredPart> part;
};

std::unique_ptr<Lowered> lower(const std::string& text, bool controllerLoops) {
  auto result = std::make_unique<Lowered>();
  frontend::FileId id = result->sources.addFile("fixed.cdl", text);
  frontend::CheckOptions options;
  options.importPaths = {CNCC_STDLIB_DIR};
  options.requirePart = true;
  result->program = frontend::checkProgram(result->sources, id, options, result->diagnostics);
  EXPECT_FALSE(result->diagnostics.hasErrors());
  LoweringOptions lowering;
  lowering.controllerLoops = controllerLoops;
  lowering.coordinateIncrement = 0.001;
  if (result->program && result->program->selectedPart != nullptr) {
    result->part = lowerPartWithCuts(*result->program, *result->program->selectedPart,
                                     result->diagnostics, lowering);
  }
  EXPECT_TRUE(result->part);
  return result;
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
    curve line(from=(i, 0), to=(i, 5)) sweep depth=depth step=1
  }
  curve polar(r = radius + cos(3*t)*sin(t), t = 0 .. 2*pi) tolerance=0.05
}
)";

TEST(FixedParameters, LoopBoundAndSampledCurveFixTheirParametersOnController) {
  std::unique_ptr<Lowered> result = lower(loopAndPolar, true);
  ASSERT_TRUE(result->part);
  std::vector<std::string> names = fixedNames(*result->part);
  EXPECT_EQ(names, (std::vector<std::string>{"count", "radius"}));
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
  // Without controller loops the sweep's passes are computed here too.
  std::vector<std::string> names = fixedNames(*result->part);
  EXPECT_NE(std::find(names.begin(), names.end(), "depth"), names.end());
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
} // namespace cncc::ir
