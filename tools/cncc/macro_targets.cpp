#include "macro_targets.h"

#include "commands.h"

#include "cncc/backends/controller_profile.h"
#include "cncc/backends/gcode_writer.h"
#include "cncc/backends/macro_program.h"
#include "cncc/ir/lowering.h"
#include "cncc/ir/verifier.h"

#include <fmt/format.h>

#include <optional>

namespace cncc::driver {

namespace {

// The lowered, optimised part; nullopt after a diagnostic. `cuts` receives
// the part's cut table (method=nurbs cuts are printed from it).
std::optional<ir::Function> loweredPart(const BackendRequest& request,
                                        const backends::ControllerProfile& profile,
                                        std::vector<ir::CutGeometry>& cuts) {
  const frontend::PartItem* part = request.program.selectedPart;
  if (part == nullptr) {
    return std::nullopt;
  }
  // The controller runs the curve loops, within the budget its increment leaves.
  ir::LoweringOptions lowering =
      backends::macroLoweringOptions(profile, ir::partUnits(*part) == ir::PartUnits::Inches);
  lowering.nurbsBlocks = true; // method=nurbs as G06.2 blocks
  lowering.arcsOnEveryCut = request.options.arcs;
  std::optional<ir::LoweredPart> lowered =
      ir::lowerPartWithCuts(request.program, *part, request.diagnostics, lowering);
  if (!lowered) {
    return std::nullopt;
  }
  cuts = std::move(lowered->cuts);
  std::optional<ir::Function> function = std::move(lowered->function);
  optimise(*function, request.options);
  std::vector<std::string> problems = ir::verifyFunction(*function);
  if (!problems.empty()) {
    throw InternalError("the lowered IR does not verify: " + problems.front());
  }
  return function;
}

void macroBackend(const BackendRequest& request, std::string_view defaultProfile) {
  std::string_view profileName =
      request.options.profile.empty() ? defaultProfile : std::string_view(request.options.profile);
  const backends::ControllerProfile* profile = backends::findControllerProfile(profileName);
  if (profile == nullptr) {
    throw InternalError(fmt::format("unknown controller profile '{}'", profileName));
  }
  std::vector<ir::CutGeometry> cuts;
  std::optional<ir::Function> function = loweredPart(request, *profile, cuts);
  if (!function) {
    return;
  }
  const frontend::PartItem& part = *request.program.selectedPart;
  backends::GcodeOptions names = gcodeOptionsFor(request);
  backends::MacroProgramOptions options;
  options.programNumber = backends::programNumberFromFileName(request.output.path()).value_or(1000);
  options.sourceName = names.sourceName;
  options.partName = names.partName;
  options.inches = names.inches;
  options.callable = request.options.macroCall;
  options.parametersInCommon = request.options.parametersInCommon;
  options.cuts = std::move(cuts);
  backends::MacroProgram program = backends::writeMacroProgram(*function, *profile, options);
  for (const std::string& error : program.errors) {
    request.diagnostics.report(
        frontend::DiagnosticKind::ProgramTooLarge, part.nameSpan,
        fmt::format("the part does not fit the {} profile: {}", profile->name, error));
  }
  if (program.errors.empty()) {
    request.output.write(program.text);
  }
}

} // namespace

void m80Backend(const BackendRequest& request) {
  macroBackend(request, "m80");
}

void fanucBackend(const BackendRequest& request) {
  macroBackend(request, "fanuc");
}

} // namespace cncc::driver
