// cncc sim: a program run in the virtual controller of its target (the
// macro controllers' here, a target's own reader where its TargetInfo has
// one), its tool path written as CSV.
#include "atomic_output_file.h"
#include "commands.h"
#include "machine_options.h"
#include "targets.h"

#include "cncc/backends/controller_profile.h"
#include "cncc/backends/tool_path_csv.h"
#include "cncc/backends/virtual_controller.h"

#include <fmt/format.h>

#include <fstream>
#include <sstream>

namespace cncc::driver {

namespace {

std::optional<std::string> readWholeFile(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    return std::nullopt;
  }
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

// A usage error of `sim` (exit code 2).
int simulateUsageError(const std::string& message) {
  fmt::print(stderr, "cncc: error: {}\nRun 'cncc sim --help' for usage.\n", message);
  return 2;
}

// Prints a virtual controller's error at its line, with the line.
int reportSimulationError(const std::string& path, int line, const std::string& message,
                          const std::string& lineText) {
  fmt::print(stderr, "{}:{}: error: {}\n", path, line, message);
  if (!lineText.empty()) {
    fmt::print(stderr, "    {}\n", lineText);
  }
  return 1;
}

// The path as CSV, its arcs in chords of the --chord-error.
int writeSimulatedPath(const DriverOptions& options, const ir::ToolPath& path) {
  std::string csv;
  try {
    csv = backends::writeToolPathCsv(path, options.chordError);
  } catch (const backends::ToolPathTooLarge& tooLarge) {
    fmt::print(stderr, "cncc: error: {}: too large to print\n", tooLarge.what());
    return 1;
  }
  std::error_code error;
  if (!writeFileAtomically(options.output, csv, error)) {
    fmt::print(stderr, "cncc: error: cannot write '{}': {}\n", options.output, error.message());
    return 1;
  }
  return 0;
}

// `text`, read from `path`, run in the target's own reader.
int runOwnReader(const backends::TargetInfo& target, const DriverOptions& options,
                 const std::string& path, const std::string& text) {
  backends::OwnReaderSettings settings;
  // --profile, checked by the command line to be a TNC profile here.
  settings.tncProfile = target.tncProfiles ? &tncProfile(options) : nullptr;
  settings.toolRadii = options.toolRadii;
  settings.chordError = options.chordError;
  backends::OwnProgramRun run = target.runOwnProgram(text, settings);
  if (run.failure) {
    return reportSimulationError(path, run.failure->line, run.failure->message,
                                 run.failure->lineText);
  }
  return writeSimulatedPath(options, run.path);
}

} // namespace

int runSimulate(const DriverOptions& options) {
  const std::string& path = options.inputs.front();
  std::optional<std::string> text = readWholeFile(path);
  if (!text) {
    fmt::print(stderr, "cncc: error: cannot read '{}'\n", path);
    return 1;
  }
  if (const backends::TargetInfo& target = optionsTarget(options); target.runOwnProgram) {
    return runOwnReader(target, options, path, *text);
  }
  const backends::ControllerProfile* profile = &controllerProfile(options, options.target);
  backends::sim::SimulationOptions simulation;
  for (const std::string& argument : options.macroArguments) {
    std::string problem;
    std::optional<backends::sim::MacroArgument> parsed =
        backends::sim::parseMacroArgument(argument, *profile, problem);
    if (!parsed) {
      return simulateUsageError(problem);
    }
    simulation.arguments.push_back(*parsed);
  }
  simulation.runAsMacroCall = !options.macroArguments.empty();
  simulation.reading.strict = options.strictReading;
  simulation.reading.family =
      backends::sim::controllerFamilyOf(optionsTarget(options).controllerProfile);
  // The machine file's registers, with --tool-radius over them.
  if (options.machine) {
    simulation.toolRadii = options.machine->radiusOffsets;
  }
  for (const auto& [registerNumber, radius] : options.toolRadii) {
    simulation.toolRadii[registerNumber] = radius;
  }
  simulation.peckRetract = options.peckRetract;
  simulation.peckClearance = options.peckClearance;
  backends::sim::SimulationResult result =
      backends::sim::simulateProgram(*text, *profile, simulation);
  if (result.error) {
    return reportSimulationError(path, result.error->line(), result.error->what(),
                                 result.error->lineText());
  }
  return writeSimulatedPath(options, backends::sim::executedToolPath(result.path));
}

} // namespace cncc::driver
