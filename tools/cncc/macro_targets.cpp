#include "macro_targets.h"

#include "commands.h"
#include "machine_options.h"

#include "cncc/backends/controller_profile.h"
#include "cncc/backends/gcode_writer.h"
#include "cncc/backends/macro_program.h"
#include "cncc/ir/verifier.h"
#include "cncc/lowering/lowering.h"

#include <fmt/format.h>

#include <optional>

namespace cncc::driver {

namespace {

ir::LoweringOptions macroLowering(const frontend::PartItem& part, const DriverOptions& options,
                                  std::string_view defaultProfile) {
  ir::LoweringOptions lowering = backends::macroLoweringOptions(
      controllerProfile(options, defaultProfile), ir::partUnits(part) == ir::PartUnits::Inches);
  lowering.nurbsBlocks = true;
  lowering.arcsOnEveryCut = options.arcs;
  return lowering;
}

// The lowered, optimised part; nullopt after a diagnostic.
std::optional<ir::Function> loweredPart(const BackendRequest& request) {
  std::optional<ir::LoweredPart> lowered = lowerForTarget(request);
  if (!lowered) {
    return std::nullopt;
  }
  return std::move(lowered->function);
}

void macroBackend(const BackendRequest& request, std::string_view defaultProfile) {
  const backends::ControllerProfile* profile = &controllerProfile(request.options, defaultProfile);
  std::optional<ir::Function> function = loweredPart(request);
  if (!function) {
    return;
  }
  backends::GcodeOptions names = gcodeOptionsFor(request);
  backends::MacroProgramOptions options;
  options.programNumber = backends::programNumberFromFileName(request.output.path()).value_or(1000);
  options.sourceName = names.sourceName;
  options.partName = names.partName;
  options.inches = names.inches;
  options.callable = request.options.macroCall;
  options.parametersInCommon = request.options.parametersInCommon;
  options.setup = machineSetup(request.options);
  backends::MacroProgram program = backends::writeMacroProgram(*function, *profile, options);
  if (writeProgramIfItFits(request, fmt::format("the {} profile", profile->name), program.errors,
                           program.text, std::move(program.lineOrigins))) {
    if (request.variables != nullptr) {
      *request.variables = std::move(program.variables);
    }
  }
}

} // namespace

void m80Backend(const BackendRequest& request) {
  macroBackend(request, "m80");
}

void fanucBackend(const BackendRequest& request) {
  macroBackend(request, "fanuc");
}

ir::LoweringOptions m80LoweringOptions(const frontend::PartItem& part,
                                       const DriverOptions& options) {
  return macroLowering(part, options, "m80");
}

ir::LoweringOptions fanucLoweringOptions(const frontend::PartItem& part,
                                         const DriverOptions& options) {
  return macroLowering(part, options, "fanuc");
}

} // namespace cncc::driver
