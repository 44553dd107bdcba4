// cncc sim: runs a program on a virtual controller (backends/sim: Fanuc/M80,
// LinuxCNC or Sinumerik) and prints the executed path as CSV, arcs and splines split
// into fine chords.
#include "atomic_output_file.h"
#include "commands.h"
#include "machine_options.h"

#include "cncc/backends/controller_profile.h"
#include "cncc/backends/heidenhain_controller.h"
#include "cncc/backends/linuxcnc_controller.h"
#include "cncc/backends/sinumerik_controller.h"
#include "cncc/backends/tool_path_csv.h"
#include "cncc/backends/virtual_controller.h"

#include <fmt/format.h>

#include <fstream>
#include <sstream>

namespace cncc::driver {

namespace {

int usageError(const std::string& message) {
  fmt::print(stderr, "cncc: error: {}\nRun 'cncc sim --help' for usage.\n", message);
  return 2;
}

std::optional<std::string> readWholeFile(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    return std::nullopt;
  }
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

} // namespace

namespace {

// The path as CSV, its arcs in chords of the --chord-error.
int writeCsv(const DriverOptions& options, const ir::ToolPath& path) {
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

// The virtual Sinumerik's run as a tool path: a rapid to where every axis
// is first known, then its moves (splines and arcs already in chords).
int runSinumerik(const DriverOptions& options, const std::string& path, const std::string& text) {
  backends::sinumerik::SinumerikRunOptions settings;
  settings.sampleTolerance = options.chordError;
  settings.toolRadii = options.toolRadii; // --tool-radius: by tool number
  backends::sinumerik::SinumerikRun run = backends::sinumerik::runSinumerikProgram(text, settings);
  if (run.error) {
    // The message starts "[NAME, ]line N: ", which the location says already.
    std::string message = run.error->what();
    std::size_t after = message.find(": ");
    fmt::print(stderr, "{}:{}: error: {}\n", path, run.error->line(),
               after == std::string::npos ? message : message.substr(after + 2));
    return 1;
  }
  ir::ToolPath toolPath;
  ir::MachineEvent start;
  start.x = run.start.x();
  start.y = run.start.y();
  start.z = run.start.z();
  toolPath.events.push_back(start);
  for (const backends::sinumerik::ExecutedSinumerikMove& move : run.moves) {
    ir::MachineEvent event;
    bool rapid = move.kind == backends::sinumerik::MotionKind::Rapid;
    event.kind = rapid ? ir::MachineEvent::Kind::Rapid : ir::MachineEvent::Kind::Feed;
    event.x = move.end.x();
    event.y = move.end.y();
    event.z = move.end.z();
    event.feed = rapid ? 0 : move.feed;
    toolPath.events.push_back(event);
  }
  return writeCsv(options, toolPath);
}

// Prints a virtual controller's error at its line, with the line.
int reportError(const std::string& path, int line, const std::string& message,
                const std::string& lineText) {
  fmt::print(stderr, "{}:{}: error: {}\n", path, line, message);
  if (!lineText.empty()) {
    fmt::print(stderr, "    {}\n", lineText);
  }
  return 1;
}

int runLinuxcnc(const DriverOptions& options, const std::string& path, const std::string& text) {
  backends::sim::LinuxcncRunOptions settings;
  settings.toolRadii = options.toolRadii; // --tool-radius: by tool number (G41/G42 D<tool>)
  backends::sim::LinuxcncRun run = backends::sim::runLinuxcncProgram(text, settings);
  if (run.error) {
    return reportError(path, run.error->line(), run.error->what(), run.error->lineText());
  }
  return writeCsv(options, backends::sim::executedToolPath(backends::sim::executedPathOf(run)));
}

// The virtual TNC's run.
int runHeidenhain(const DriverOptions& options, const std::string& path, const std::string& text) {
  backends::heidenhain::TncRunOptions settings;
  if (!options.profile.empty()) {
    const backends::TncProfile* profile = backends::findTncProfile(options.profile);
    if (profile == nullptr) {
      return usageError(
          fmt::format("--profile {}: the TNC profiles are tnc640 and itnc530", options.profile));
    }
    settings.profile = *profile;
  }
  settings.toolRadii = options.toolRadii;
  backends::heidenhain::TncRun run = backends::heidenhain::runTncProgram(text, settings);
  if (run.error) {
    return reportError(path, run.error->line, run.error->message, run.error->lineText);
  }
  return writeCsv(options, run.path);
}

} // namespace

int runSimulate(const DriverOptions& options) {
  if (options.target == "sinumerik" || options.target == "linuxcnc" ||
      options.target == "heidenhain") {
    const std::string& path = options.inputs.front();
    std::optional<std::string> text = readWholeFile(path);
    if (!text) {
      fmt::print(stderr, "cncc: error: cannot read '{}'\n", path);
      return 1;
    }
    return options.target == "sinumerik"  ? runSinumerik(options, path, *text)
           : options.target == "linuxcnc" ? runLinuxcnc(options, path, *text)
                                          : runHeidenhain(options, path, *text);
  }
  const backends::ControllerProfile* profile = &controllerProfile(options, options.target);
  backends::sim::SimulationOptions simulation;
  for (const std::string& text : options.macroArguments) {
    std::string problem;
    std::optional<backends::sim::MacroArgument> argument =
        backends::sim::parseMacroArgument(text, *profile, problem);
    if (!argument) {
      return usageError(problem);
    }
    simulation.arguments.push_back(*argument);
  }
  simulation.runAsMacroCall = !options.macroArguments.empty();
  simulation.reading.strict = options.strictReading;
  simulation.reading.family = backends::sim::controllerFamilyOf(options.target);
  // The machine file's registers, with --tool-radius over them.
  if (options.machine) {
    simulation.toolRadii = options.machine->radiusOffsets;
  }
  for (const auto& [registerNumber, radius] : options.toolRadii) {
    simulation.toolRadii[registerNumber] = radius;
  }
  simulation.peckRetract = options.peckRetract;
  simulation.peckClearance = options.peckClearance;

  const std::string& path = options.inputs.front();
  std::optional<std::string> text = readWholeFile(path);
  if (!text) {
    fmt::print(stderr, "cncc: error: cannot read '{}'\n", path);
    return 1;
  }
  backends::sim::SimulationResult result =
      backends::sim::simulateProgram(*text, *profile, simulation);
  if (result.error) {
    return reportError(path, result.error->line(), result.error->what(), result.error->lineText());
  }
  return writeCsv(options, backends::sim::executedToolPath(result.path));
}

} // namespace cncc::driver
