// A CDL text checked and lowered, for the unit tests: the part as the
// lowering gives it, with the sources and diagnostics it came with.
#pragma once

#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/lowering/lowering.h"

#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <string>

namespace cncc::ir::test_support {

struct LoweredText {
  frontend::SourceManager sources;
  frontend::DiagnosticEngine diagnostics;
  std::optional<frontend::CheckedProgram> program;
  std::optional<LoweredPart> part;
};

// `text` checked as `name` (the standard library on the import path; it
// must check without errors) and its part (or the one named `partName`)
// lowered with `lowering`.
inline std::unique_ptr<LoweredText> lowerText(const std::string& text,
                                              const LoweringOptions& lowering,
                                              const std::string& name = "test.cdl",
                                              const std::string& partName = "") {
  auto result = std::make_unique<LoweredText>();
  frontend::FileId id = result->sources.addFile(name, text);
  frontend::CheckOptions options;
  options.importPaths = {CNCC_STDLIB_DIR};
  options.requirePart = true;
  options.partName = partName;
  result->program = frontend::checkProgram(result->sources, id, options, result->diagnostics);
  EXPECT_FALSE(result->diagnostics.hasErrors());
  if (result->program && result->program->selectedPart != nullptr) {
    result->part = lowerPartWithCuts(*result->program, *result->program->selectedPart,
                                     result->diagnostics, lowering);
  }
  EXPECT_TRUE(result->part);
  return result;
}

} // namespace cncc::ir::test_support
