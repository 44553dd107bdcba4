// A part compiled in tests as `cncc FILE -t TARGET` compiles it, through
// nothing but the target's TargetInfo: lowered, optimised, given the
// target's passes, run on the host where the target asks, printed.
#pragma once

#include "cncc/backends/controller_profile.h"
#include "cncc/backends/target_info.h"
#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/verifier.h"
#include "cncc/lowering/lowering.h"

#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <optional>
#include <string>

namespace cncc::testing {

// The checked part; the program stays alive because the cut curves
// evaluate its expressions.
struct CheckedExample {
  frontend::SourceManager sources;
  frontend::DiagnosticEngine diagnostics;
  std::optional<frontend::CheckedProgram> program;
};

// The source at `path` (from the source tree's root) checked with the
// values `defines`, its part `part` selected (empty: its only one).
inline std::unique_ptr<CheckedExample> checkSource(const std::string& path,
                                                   const std::string& part = {},
                                                   const frontend::ParameterDefines& defines = {}) {
  auto checked = std::make_unique<CheckedExample>();
  std::optional<frontend::FileId> file =
      checked->sources.loadFile(std::string(CNCC_SOURCE_DIR) + "/" + path);
  if (!file) {
    ADD_FAILURE() << "cannot read " << path;
    return nullptr;
  }
  frontend::CheckOptions options;
  options.importPaths = {CNCC_STDLIB_DIR};
  options.requirePart = true;
  options.partName = part;
  options.defines = defines;
  checked->program = frontend::checkProgram(checked->sources, *file, options, checked->diagnostics);
  if (checked->diagnostics.hasErrors() || checked->program->selectedPart == nullptr) {
    ADD_FAILURE() << path << " does not check";
    return nullptr;
  }
  return checked;
}

// examples/`name` checked, its part `part` selected (empty: its only one).
inline std::unique_ptr<CheckedExample> checkExample(const std::string& name,
                                                    const std::string& part = {}) {
  return checkSource("examples/" + name, part);
}

// The settings a compile without options gives `target` for `part`.
inline backends::TargetSettings defaultSettings(const backends::TargetInfo& target,
                                                const frontend::PartItem& part) {
  backends::TargetSettings settings;
  settings.sourceName = "part.cdl";
  settings.partName = part.name;
  settings.inches = ir::partUnits(part) == ir::PartUnits::Inches;
  settings.setup = backends::builtinMachineSetup(target.machineSetup);
  if (!target.controllerProfile.empty()) {
    settings.controllerProfile = backends::findControllerProfile(target.controllerProfile);
  }
  if (target.tncProfiles) {
    settings.tncProfile = backends::findTncProfile("tnc640");
  }
  return settings;
}

struct TargetCompilation {
  ir::LoweredPart lowered; // after the target's passes
  ir::ToolPath programmed; // the final IR run by the interpreter
  backends::PrintedProgram printed;
};

// `settings`: what the command line asks (none: defaultSettings).
inline std::optional<TargetCompilation>
compileThroughTarget(const backends::TargetInfo& target, const CheckedExample& checked,
                     std::optional<backends::TargetSettings> given = std::nullopt) {
  const frontend::PartItem& part = *checked.program->selectedPart;
  backends::TargetSettings settings = given ? *given : defaultSettings(target, part);
  ir::LoweringOptions lowering = target.lowering(settings);
  lowering.cutterCompensation = target.cutterCompensation;
  frontend::DiagnosticEngine diagnostics;
  std::optional<ir::LoweredPart> lowered =
      ir::lowerPartWithCuts(*checked.program, part, diagnostics, lowering);
  if (!lowered) {
    ADD_FAILURE() << "the part does not lower";
    return std::nullopt;
  }
  ir::runDefaultPipeline(lowered->function);
  EXPECT_TRUE(ir::runPasses(lowered->function, lowering.passesBeforePrinting, {}));
  std::vector<std::string> problems = ir::verifyFunction(lowered->function);
  EXPECT_TRUE(problems.empty()) << problems.front();
  TargetCompilation compiled{std::move(*lowered), {}, {}};
  compiled.programmed = ir::interpret(compiled.lowered.function);
  const ir::ToolPath* hostPath =
      target.hostRun != backends::HostRun::None ? &compiled.programmed : nullptr;
  compiled.printed = target.print({compiled.lowered.function, hostPath, settings});
  EXPECT_TRUE(compiled.printed.problems.empty()) << compiled.printed.problems.front();
  return compiled;
}

} // namespace cncc::testing
