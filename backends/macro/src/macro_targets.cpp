// The controller-side macro targets: `m80` and `fanuc` print the part as a
// macro program that evaluates the curve on the controller.
#include "registered_targets.h"

#include "cncc/backends/macro_program.h"

#include <fmt/format.h>

namespace cncc::backends {

namespace {

// The controller runs the curve loops, within the budget the profile's
// increment leaves; method=nurbs as G06.2 blocks.
ir::LoweringOptions macroLowering(const TargetSettings& settings) {
  ir::LoweringOptions lowering = macroLoweringOptions(*settings.controllerProfile, settings.inches);
  lowering.nurbsBlocks = true;
  lowering.arcsOnEveryCut = settings.arcs;
  return lowering;
}

PrintedProgram printMacroProgram(const PrintInput& input) {
  const TargetSettings& settings = input.settings;
  MacroProgramOptions options;
  options.programNumber = programNumberOf(settings, 1000);
  options.sourceName = settings.sourceName;
  options.partName = settings.partName;
  options.inches = settings.inches;
  options.callable = settings.macroCall;
  options.parametersInCommon = settings.parametersInCommon;
  options.setup = settings.setup;
  const ControllerProfile& profile = *settings.controllerProfile;
  MacroProgram program = writeMacroProgram(input.function, profile, options);
  PrintedProgram printed;
  printed.problems = doesNotFit(fmt::format("the {} profile", profile.name), program.errors);
  printed.text = std::move(program.text);
  printed.lineOrigins = std::move(program.lineOrigins);
  printed.variables = std::move(program.variables);
  return printed;
}

ProgramExecution runM80(const ExecutionRequest& request) {
  return runMacroProgram(request, "m80");
}

ProgramExecution runFanuc(const ExecutionRequest& request) {
  return runMacroProgram(request, "fanuc");
}

} // namespace

const TargetInfo m80Target = {
    .name = "m80",
    .description = "Mitsubishi M70/M80/M800 macro program (parameters stay editable)",
    .lowering = macroLowering,
    .print = printMacroProgram,
    .controllerProfile = "m80",
    .machineSetup = "m80",
    .cutterCompensation = true,
    .execute = runM80,
};

const TargetInfo fanucTarget = {
    .name = "fanuc",
    .description = "Fanuc Custom Macro B program (parameters stay editable)",
    .lowering = macroLowering,
    .print = printMacroProgram,
    .controllerProfile = "fanuc",
    .machineSetup = "fanuc",
    .cutterCompensation = true,
    .execute = runFanuc,
};

} // namespace cncc::backends
