#include "targets.h"

#include "source_map.h"

#include "commands.h"
#include "heidenhain_target.h"
#include "jit_module.h"
#include "linuxcnc_target.h"
#include "machine_options.h"
#include "macro_targets.h"
#include "own_program_readers.h"
#include "sinumerik_target.h"

#include "cncc/backends/gcode_writer.h"
#include "cncc/backends/machine_file.h"
#include "cncc/backends/tool_path_csv.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/verifier.h"
#include "cncc/lowering/lowering.h"

#include <fmt/format.h>

#include <cmath>
#include <optional>

namespace cncc::driver {

namespace {

void gcodeBackend(const BackendRequest& request) {
  std::optional<ir::ToolPath> path = hostToolPath(request, false);
  if (!path) {
    return;
  }
  backends::GcodeProgram program = backends::writeGcodeProgram(*path, gcodeOptionsFor(request));
  writeProgram(request, program.text, std::move(program.lineOrigins));
}

// The tool path as CSV, or an error at the part where it has too many rows.
std::optional<std::string> toolPathCsv(const BackendRequest& request, const ir::ToolPath& path) {
  try {
    return backends::writeToolPathCsv(path);
  } catch (const backends::ToolPathTooLarge& tooLarge) {
    request.diagnostics.report(frontend::DiagnosticKind::ProgramTooLarge,
                               request.program.selectedPart->nameSpan,
                               fmt::format("the part is too large to print: {}", tooLarge.what()));
    return std::nullopt;
  }
}

void jitBackend(const BackendRequest& request) {
  std::optional<ir::ToolPath> path = hostToolPath(request, true);
  std::optional<std::string> csv = path ? toolPathCsv(request, *path) : std::nullopt;
  if (csv) {
    request.output.write(*csv);
  }
}

// The gcode target's program for a tool path, run by the G-code reader.
backends::ExecutedProgram gcodeProgram(const BackendRequest& request, const ir::ToolPath& path) {
  backends::GcodeOptions options = gcodeOptionsFor(request);
  std::string text = backends::writeGcode(path, options);
  backends::ExecutedPath executed = backends::executeGcode(text, path, options.decimals);
  std::size_t blocks = backends::countProgramBlocks(text);
  return {std::move(text), blocks, std::move(executed)};
}

// The jit target's program is the tool path as CSV; a block is a row, and
// what runs is its rows (arcs in the CSV's chords). Throws ToolPathTooLarge.
backends::ExecutedProgram jitProgram(const BackendRequest&, const ir::ToolPath& path) {
  std::string text = backends::writeToolPathCsv(path);
  std::size_t rows = backends::countProgramBlocks(text) - 1; // without the header
  return {std::move(text), rows,
          backends::executedPathOfToolPath(path, backends::toolPathCsvArcSagitta)};
}

constexpr Target targetTable[] = {
    {.name = "m80",
     .description = "Mitsubishi M70/M80/M800 macro program (parameters stay editable)",
     .backend = m80Backend,
     .lowering = m80LoweringOptions,
     .fittedArcs = true,
     .controllerProfile = "m80",
     .cutterCompensation = true},
    {.name = "fanuc",
     .description = "Fanuc Custom Macro B program (parameters stay editable)",
     .backend = fanucBackend,
     .lowering = fanucLoweringOptions,
     .fittedArcs = true,
     .controllerProfile = "fanuc",
     .cutterCompensation = true},
    {.name = "sinumerik",
     .description = "Siemens Sinumerik program: BSPLINE and A/B/C spline blocks",
     .backend = sinumerikBackend,
     .lowering = sinumerikLoweringOptions,
     .splineOptions = true,
     .cutterCompensation = true,
     .ownProgramReader = simulateSinumerikProgram},
    {.name = "gcode",
     .description = "plain G-code: G00/G01 and G02/G03 blocks computed on the host",
     .backend = gcodeBackend,
     .lowering = gcodeLoweringOptions,
     .fittedArcs = true,
     .hostProgram = gcodeProgram,
     .cutterCompensation = true},
    {.name = "linuxcnc",
     .description = "LinuxCNC program with o-word loops and parameters",
     .backend = linuxcncBackend,
     .lowering = linuxcncLoweringOptions,
     .fittedArcs = true,
     .cutterCompensation = true,
     .ownProgramReader = simulateLinuxcncProgram},
    {.name = "heidenhain",
     .description = "Heidenhain TNC conversational program with Q parameters (parameters stay "
                    "editable)",
     .backend = heidenhainBackend,
     .lowering = heidenhainLoweringOptions,
     .fittedArcs = true,
     .parameterVariables = heidenhainParameterQ,
     .cutterCompensation = true,
     .ownProgramReader = simulateTncProgram,
     .tncProfiles = true},
    {.name = "jit",
     .description = "run the part on the host and print the tool path",
     .backend = jitBackend,
     .lowering = jitLoweringOptions,
     .hostProgram = jitProgram},
};

} // namespace

std::optional<ir::LoweredPart> lowerForTarget(const BackendRequest& request) {
  const frontend::PartItem* part = request.program.selectedPart;
  if (part == nullptr) {
    return std::nullopt;
  }
  ir::LoweringOptions lowering =
      findTarget(request.options.target)->loweringOptions(*part, request.options);
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

std::optional<ir::ToolPath> hostToolPath(const BackendRequest& request, bool native,
                                         std::vector<ir::CutGeometry>* cuts) {
  std::optional<ir::LoweredPart> lowered = lowerForTarget(request);
  if (!lowered) {
    return std::nullopt;
  }
  if (cuts != nullptr) {
    *cuts = std::move(lowered->cuts);
  }
  const frontend::PartItem* part = request.program.selectedPart;
  ir::Function* function = &lowered->function;
  try {
    // `native`: compiled by the LLVM JIT, which runs as the interpreter does.
    if (native) {
      if (std::optional<ir::ToolPath> path = runOnJit(*function)) {
        return path;
      }
    }
    return ir::interpret(*function);
  } catch (const ir::InterpreterError& error) {
    request.diagnostics.report(frontend::DiagnosticKind::ProgramTooLarge, part->nameSpan,
                               fmt::format("the part cannot be run on the host: {}", error.what()));
    return std::nullopt;
  }
}

bool writeProgramIfItFits(const BackendRequest& request, std::string_view controller,
                          const std::vector<std::string>& errors, std::string_view text,
                          backends::LineOrigins lineOrigins) {
  for (const std::string& error : errors) {
    request.diagnostics.report(frontend::DiagnosticKind::ProgramTooLarge,
                               request.program.selectedPart->nameSpan,
                               fmt::format("the part does not fit {}: {}", controller, error));
  }
  if (!errors.empty()) {
    return false;
  }
  writeProgram(request, text, std::move(lineOrigins));
  return true;
}

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

// The printed coordinates are rounded to the printed decimals (the CSV of
// jit has 6): the chords leave that rounding room inside the tolerance.
ir::LoweringOptions gcodeLoweringOptions(const frontend::PartItem&,
                                         const DriverOptions& driverOptions) {
  ir::LoweringOptions options;
  options.coordinateIncrement = std::pow(10.0, -backends::GcodeOptions{}.decimals);
  options.arcBlocks = true;
  options.arcsOnEveryCut = driverOptions.arcs;
  return options;
}

ir::LoweringOptions jitLoweringOptions(const frontend::PartItem&, const DriverOptions&) {
  ir::LoweringOptions options;
  options.coordinateIncrement = std::pow(10.0, -backends::toolPathCsvDecimals);
  return options;
}

backends::GcodeOptions gcodeOptionsFor(const BackendRequest& request) {
  const frontend::PartItem& part = *request.program.selectedPart;
  backends::GcodeOptions options;
  options.programNumber = backends::programNumberFromFileName(request.output.path()).value_or(1);
  const std::string& input = request.options.inputs.front();
  std::size_t slash = input.find_last_of('/');
  options.sourceName = slash == std::string::npos ? input : input.substr(slash + 1);
  options.partName = part.name;
  options.inches = ir::partUnits(part) == ir::PartUnits::Inches;
  options.setup = machineSetup(request.options);
  return options;
}

ir::LoweringOptions Target::loweringOptions(const frontend::PartItem& part,
                                            const DriverOptions& options) const {
  ir::LoweringOptions lowered = lowering(part, options);
  const backends::MachineSetup& setup = machineSetup(options);
  lowered.maximumExtendedWorkOffset =
      setup.extendedWorkOffset.empty() ? 0 : setup.maximumExtendedWorkOffset;
  lowered.throughSpindleCoolant = !setup.coolantThrough.empty();
  lowered.targetName = std::string(name);
  lowered.cutterCompensation = cutterCompensation;
  // Every program's numbers stay within the controller profile's range (the
  // conservative Fanuc one for the targets without a macro profile of their
  // own, whose --profile, if any, names another kind; jit's tool path is for
  // a controller too).
  lowered.largestNumber =
      controllerProfile.empty() && !machineProfile(options)
          ? backends::findControllerProfile("fanuc")->maximumCoordinate
          : driver::controllerProfile(options, controllerProfile).maximumCoordinate;
  if (options.machine) {
    lowered.maximumFeed = options.machine->maximumFeed;
    lowered.maximumSpindleSpeed = options.machine->maximumSpindleSpeed;
  }
  return lowered;
}

std::span<const Target> allTargets() {
  return targetTable;
}

const Target* findTarget(std::string_view name) {
  for (const Target& target : targetTable) {
    if (target.name == name) {
      return &target;
    }
  }
  return nullptr;
}

std::string targetNameList(bool (*which)(const Target& target)) {
  std::string names;
  for (const Target& target : targetTable) {
    if (which != nullptr && !which(target)) {
      continue;
    }
    names += names.empty() ? "" : ", ";
    names += target.name;
  }
  return names;
}

} // namespace cncc::driver
