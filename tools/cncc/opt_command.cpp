// `cncc opt FILE.ir [--passes=a,b] [--print-after=NAME|all]`: runs IR
// passes on textual IR, for testing the optimiser on hand-written input.
#include "commands.h"

#include "cncc/ir/curve_lap.h"

#include "atomic_output_file.h"
#include "diagnostic_output.h"

#include "cncc/ir/printer.h"
#include "cncc/ir/verifier.h"

#include <fmt/format.h>
#include <fstream>
#include <sstream>

namespace cncc::driver {

namespace {

std::optional<std::string> readText(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    return std::nullopt;
  }
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

} // namespace

ir::AfterPassCallback printAfterCallback(const DriverOptions& options) {
  if (options.printAfter.empty()) {
    return {};
  }
  std::string wanted = options.printAfter;
  return [wanted](std::string_view name, const ir::Function& function) {
    if (wanted == "all" || wanted == name) {
      fmt::print(stderr, "// IR after {}\n{}", name, ir::printFunction(function));
    }
  };
}

void optimise(ir::Function& function, const DriverOptions& options) {
  if (!options.optimise) {
    return;
  }
  if (options.passes.empty()) {
    ir::runDefaultPipeline(function, printAfterCallback(options));
  } else {
    // The names were checked with the command line.
    ir::runPasses(function, options.passes, printAfterCallback(options));
  }
  std::vector<std::string> problems = ir::verifyFunction(function);
  if (!problems.empty()) {
    throw InternalError("the optimised IR does not verify: " + problems.front());
  }
}

void runPassesBeforePrinting(ir::Function& function, const ir::LoweringOptions& lowering,
                             const DriverOptions& options) {
  if (lowering.passesBeforePrinting.empty()) {
    return;
  }
  std::vector<std::string> passes = lowering.passesBeforePrinting;
  if (options.optimise && options.passes.empty()) {
    // What they fold may leave values that are the same, or no longer read.
    passes.insert(passes.end(), {"cse", "dce"});
  }
  std::string unknown;
  if (!ir::runPasses(function, passes, printAfterCallback(options), &unknown)) {
    throw InternalError(fmt::format("the target names an unknown IR pass '{}'", unknown));
  }
  std::vector<std::string> problems = ir::verifyFunction(function);
  if (!problems.empty()) {
    throw InternalError("the IR after the target's passes does not verify: " + problems.front());
  }
}

int runOptimize(const DriverOptions& options) {
  DiagnosticOutput output(options.diagnosticsFormat, options.colour);
  const std::string& path = options.inputs.front();
  std::optional<std::string> text = readText(path);
  if (!text) {
    output.driverError(fmt::format("cannot read '{}'", path));
    return 1;
  }
  ir::ParseError error;
  std::optional<ir::Function> function = ir::parseFunction(*text, error);
  if (!function) {
    output.driverError(fmt::format("{}:{}: {}", path, error.line, error.message));
    return 1;
  }
  std::vector<std::string> problems = ir::verifyFunction(*function);
  if (!problems.empty()) {
    output.driverError(fmt::format("{}: the IR does not verify: {}", path, problems.front()));
    return 1;
  }
  try {
    optimise(*function, options);
  } catch (const ir::CurveLapError& lapError) {
    output.driverError(fmt::format("{}: {}", path, lapError.what()));
    return 1;
  }
  for (const ir::LegalisationWarning& warning : function->warnings) {
    output.driverWarning(fmt::format("{}: {}", path, warning.message)); // IR text has no spans
  }
  std::error_code writeError;
  if (!writeFileAtomically(options.output, ir::printFunction(*function), writeError)) {
    output.driverError(fmt::format("cannot write '{}': {}", options.output, writeError.message()));
    return 1;
  }
  return 0;
}

} // namespace cncc::driver
