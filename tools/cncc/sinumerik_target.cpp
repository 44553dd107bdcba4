#include "sinumerik_target.h"

#include "commands.h"
#include "machine_options.h"
#include "targets.h"

#include "cncc/backends/sinumerik_controller.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/verifier.h"

#include <fmt/format.h>

#include <utility>

namespace cncc::driver {

namespace {

std::string fileStem(const std::string& path) {
  std::size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  return name.substr(0, name.find('.'));
}

backends::SinumerikOptions sinumerikOptionsFor(const BackendRequest& request) {
  const frontend::PartItem& part = *request.program.selectedPart;
  backends::SinumerikOptions options;
  const std::string& input = request.options.inputs.front();
  std::size_t slash = input.find_last_of('/');
  options.sourceName = slash == std::string::npos ? input : input.substr(slash + 1);
  options.partName = part.name;
  std::string output = request.output.path();
  options.programName = output.empty() || output == "-" ? part.name : fileStem(output);
  options.inches = ir::partUnits(part) == ir::PartUnits::Inches;
  options.subprograms = request.options.subprograms;
  options.setup = machineSetup(request.options);
  return options;
}

ir::SplineEnds splineEndsOf(const std::string& ends) {
  return ends == "natural" ? ir::SplineEnds::Natural
         : ends == "auto"  ? ir::SplineEnds::Auto
                           : ir::SplineEnds::Automatic;
}

} // namespace

ir::LoweringOptions sinumerikLoweringOptions(const frontend::PartItem&,
                                             const DriverOptions& options) {
  backends::SinumerikOptions sinumerik;
  sinumerik.transitions = splineEndsOf(options.splineEnds);
  return backends::sinumerikLoweringOptions(sinumerik);
}

std::optional<SinumerikCompilation> compileForSinumerik(const BackendRequest& request) {
  std::optional<ir::LoweredPart> lowered = lowerForTarget(request);
  if (!lowered) {
    return std::nullopt;
  }
  const frontend::PartItem* part = request.program.selectedPart;
  ir::ToolPath path;
  try {
    path = ir::interpret(lowered->function);
  } catch (const ir::InterpreterError& error) {
    request.diagnostics.report(frontend::DiagnosticKind::ProgramTooLarge, part->nameSpan,
                               fmt::format("the part cannot be run on the host: {}", error.what()));
    return std::nullopt;
  }
  backends::SinumerikProgram program = backends::writeSinumerik(
      path, lowered->function.tables, lowered->cuts.size(), sinumerikOptionsFor(request));
  return SinumerikCompilation{std::move(program), std::move(lowered->cuts)};
}

backends::ExecutedProgram executeSinumerik(const backends::SinumerikProgram& program) {
  backends::sinumerik::SinumerikRun run = backends::sinumerik::runSinumerikProgram(program.text);
  if (run.error) {
    throw InternalError(
        fmt::format("the virtual Sinumerik cannot run the program: {}", run.error->what()));
  }
  backends::ExecutedProgram executed;
  executed.text = program.text;
  executed.blocks = backends::countProgramBlocks(program.text);
  executed.path = backends::sinumerik::executedPathOf(run, program.cutOfLine);
  return executed;
}

namespace {

// With --stats: how each cut's spline blocks were found (a NURBS as it is,
// reparametrised or re-fitted), before the measured statistics.
void printSplineBlocks(const BackendRequest& request, const std::vector<ir::CutGeometry>& cuts) {
  std::string text;
  for (std::size_t i = 0; i < cuts.size(); ++i) {
    if (!cuts[i].splineBlocks.empty()) {
      text += fmt::format("  cut {}: {}\n", i + 1, cuts[i].splineBlocks);
    }
  }
  if (request.options.stats && !text.empty()) {
    fmt::print(stderr, "spline blocks of part {}:\n{}", request.program.selectedPart->name, text);
  }
}

} // namespace

void sinumerikBackend(const BackendRequest& request) {
  std::optional<SinumerikCompilation> compiled = compileForSinumerik(request);
  if (compiled) {
    printSplineBlocks(request, compiled->cuts);
    writeProgram(request, compiled->program.text, std::move(compiled->program.lineOrigins));
  }
}

} // namespace cncc::driver
