// cncc sim: runs a program on the virtual controller (backends/sim) and
// prints the executed path as CSV, arcs split into fine chords.
#include "atomic_output_file.h"
#include "commands.h"
#include "machine_options.h"

#include "cncc/backends/controller_profile.h"
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

int runSimulate(const DriverOptions& options) {
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
  simulation.toolRadii = options.toolRadii;
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
    fmt::print(stderr, "{}:{}: error: {}\n", path, result.error->line(), result.error->what());
    if (!result.error->lineText().empty()) {
      fmt::print(stderr, "    {}\n", result.error->lineText());
    }
    return 1;
  }
  std::string csv =
      backends::writeToolPathCsv(backends::sim::flattenPath(result.path, options.chordError));
  std::error_code error;
  if (!writeFileAtomically(options.output, csv, error)) {
    fmt::print(stderr, "cncc: error: cannot write '{}': {}\n", options.output, error.message());
    return 1;
  }
  return 0;
}

} // namespace cncc::driver
