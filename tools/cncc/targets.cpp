#include "targets.h"

#include "source_map.h"

#include "commands.h"
#include "jit_module.h"
#include "machine_options.h"

#include "cncc/backends/machine_file.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/verifier.h"
#include "cncc/lowering/lowering.h"

#include <fmt/format.h>

#include <algorithm>
#include <optional>

namespace cncc::driver {

namespace {

// Writes a printed program to the request's output, with --annotate's
// comments, and gives its line origins to the request (for --source-map).
void writeProgram(const BackendRequest& request, std::string_view text,
                  backends::LineOrigins lineOrigins) {
  if (request.options.annotate) {
    std::string annotated = annotatedProgram(text, lineOrigins.lines, request.program,
                                             request.sources, machineSetup(request.options));
    request.output.write(annotated);
  } else {
    request.output.write(text);
  }
  if (request.lineOrigins != nullptr) {
    *request.lineOrigins = std::move(lineOrigins);
  }
}

// The lowered function run on the host (`native`: compiled by the LLVM JIT,
// which runs as the interpreter does); nullopt after a diagnostic.
std::optional<ir::ToolPath> runOnHost(const BackendRequest& request, const ir::Function& function,
                                      bool native) {
  try {
    if (native) {
      if (std::optional<ir::ToolPath> path = runOnJit(function)) {
        return path;
      }
    }
    return ir::interpret(function);
  } catch (const ir::InterpreterError& error) {
    request.diagnostics.report(frontend::DiagnosticKind::ProgramTooLarge,
                               request.program.selectedPart->nameSpan,
                               fmt::format("the part cannot be run on the host: {}", error.what()));
    return std::nullopt;
  }
}

} // namespace

const backends::TargetInfo& optionsTarget(const DriverOptions& options) {
  const backends::TargetInfo* target = backends::findTargetInfo(options.target);
  if (target == nullptr) {
    throw InternalError(fmt::format("no target '{}'", options.target));
  }
  return *target;
}

backends::TargetSettings targetSettings(const backends::TargetInfo& target,
                                        const DriverOptions& options,
                                        const frontend::PartItem& part,
                                        const std::string& outputPath) {
  backends::TargetSettings settings;
  settings.sourceName = fileName(options.inputs.front());
  settings.partName = part.name;
  settings.inches = ir::partUnits(part) == ir::PartUnits::Inches;
  settings.outputPath = outputPath;
  settings.setup = machineSetup(options);
  if (!target.controllerProfile.empty()) {
    settings.controllerProfile = &controllerProfile(options, target.controllerProfile);
  }
  if (target.tncProfiles) {
    settings.tncProfile = &tncProfile(options);
  }
  settings.arcs = options.arcs;
  settings.macroCall = options.macroCall;
  settings.parametersInCommon = options.parametersInCommon;
  settings.subprograms = options.subprograms;
  settings.splineEnds = options.splineEnds;
  return settings;
}

ir::LoweringOptions targetLoweringOptions(const backends::TargetInfo& target,
                                          const frontend::PartItem& part,
                                          const DriverOptions& options) {
  backends::TargetSettings settings = targetSettings(target, options, part);
  ir::LoweringOptions lowered = target.lowering(settings);
  const backends::MachineSetup& setup = settings.setup;
  lowered.maximumExtendedWorkOffset =
      setup.extendedWorkOffset.empty() ? 0 : setup.maximumExtendedWorkOffset;
  lowered.throughSpindleCoolant = !setup.coolantThrough.empty();
  lowered.targetName = std::string(target.name);
  lowered.cutterCompensation = target.cutterCompensation;
  // Every program's numbers stay within the controller profile's range: the
  // target's, else the machine file's, else the conservative Fanuc one (for
  // the targets without a macro profile of their own, whose --profile, if
  // any, names another kind; jit's tool path is for a controller too).
  const backends::ControllerProfile* profile = settings.controllerProfile;
  if (profile == nullptr) {
    profile = options.machine && options.machine->profile
                  ? &*options.machine->profile
                  : backends::findControllerProfile("fanuc");
  }
  lowered.largestNumber = profile->maximumCoordinate;
  if (options.machine) {
    lowered.maximumFeed = options.machine->maximumFeed;
    lowered.maximumSpindleSpeed = options.machine->maximumSpindleSpeed;
  }
  return lowered;
}

std::optional<ir::LoweredPart> lowerForTarget(const BackendRequest& request) {
  const frontend::PartItem* part = request.program.selectedPart;
  if (part == nullptr) {
    return std::nullopt;
  }
  ir::LoweringOptions lowering =
      targetLoweringOptions(optionsTarget(request.options), *part, request.options);
  std::optional<ir::LoweredPart> lowered =
      ir::lowerPartWithCuts(request.program, *part, request.diagnostics, lowering);
  if (!lowered) {
    return std::nullopt;
  }
  std::vector<std::string> problems = ir::verifyFunction(lowered->function);
  if (!problems.empty()) {
    throw InternalError("the lowered IR does not verify: " + problems.front());
  }
  optimise(lowered->function, request.options); // the IR optimiser, unless -O0
  runPassesBeforePrinting(lowered->function, lowering, request.options);
  return lowered;
}

namespace {

// The cut table to measure the part's path against: where some cut has no
// curve (a trip of a `for` unroll-host-control wrote out: the curve the
// front end evaluates for it is not in the IR), the table of the lowering
// that writes the loops out, each trip's cut with its curve; the same cuts
// in the same order.
std::vector<ir::CutGeometry> measuredCuts(const BackendRequest& request,
                                          std::vector<ir::CutGeometry> lowered) {
  if (std::all_of(lowered.begin(), lowered.end(),
                  [](const ir::CutGeometry& cut) { return cut.curve != nullptr; })) {
    return lowered;
  }
  const frontend::PartItem& part = *request.program.selectedPart;
  ir::LoweringOptions options =
      targetLoweringOptions(optionsTarget(request.options), part, request.options);
  options.keepLoops = false;
  frontend::DiagnosticEngine diagnostics(1);
  std::optional<ir::LoweredPart> writtenOut =
      ir::lowerPartWithCuts(request.program, part, diagnostics, options);
  if (!writtenOut || writtenOut->function.cuts.size() != lowered.size()) {
    return lowered;
  }
  return std::move(writtenOut->function.cuts);
}

} // namespace

std::optional<ir::ToolPath> hostToolPath(const BackendRequest& request, bool native,
                                         std::vector<ir::CutGeometry>* cuts) {
  std::optional<ir::LoweredPart> lowered = lowerForTarget(request);
  if (!lowered) {
    return std::nullopt;
  }
  if (cuts != nullptr) {
    *cuts = measuredCuts(request, std::move(lowered->function.cuts));
  }
  return runOnHost(request, lowered->function, native);
}

void compileForTarget(const BackendRequest& request) {
  const backends::TargetInfo& target = optionsTarget(request.options);
  std::optional<ir::LoweredPart> lowered = lowerForTarget(request);
  if (!lowered) {
    return;
  }
  std::optional<ir::ToolPath> hostPath;
  if (target.hostRun != backends::HostRun::None) {
    hostPath = runOnHost(request, lowered->function, target.hostRun == backends::HostRun::Native);
    if (!hostPath) {
      return;
    }
  }
  const frontend::PartItem& part = *request.program.selectedPart;
  backends::TargetSettings settings =
      targetSettings(target, request.options, part, request.output.path());
  backends::PrintedProgram printed =
      target.print({lowered->function, hostPath ? &*hostPath : nullptr, settings});
  for (const std::string& problem : printed.problems) {
    request.diagnostics.report(frontend::DiagnosticKind::ProgramTooLarge, part.nameSpan, problem);
  }
  if (!printed.problems.empty()) {
    return;
  }
  if (request.options.stats && !printed.statistics.empty()) {
    fmt::print(stderr, "{}", printed.statistics);
  }
  writeProgram(request, printed.text, std::move(printed.lineOrigins));
  if (request.variables != nullptr) {
    *request.variables = std::move(printed.variables);
  }
}

} // namespace cncc::driver
