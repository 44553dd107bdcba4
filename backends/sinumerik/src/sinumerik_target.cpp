// The `sinumerik` target: the part run on the host, its cuts as Sinumerik
// spline blocks (or G1 chords), as one .MPF program.
#include "registered_targets.h"

#include "cncc/backends/sinumerik_controller.h"
#include "cncc/backends/sinumerik_writer.h"

#include <fmt/format.h>

namespace cncc::backends {

namespace {

std::string fileStem(const std::string& path) {
  std::size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  return name.substr(0, name.find('.'));
}

ir::SplineEnds splineEndsOf(const std::string& ends) {
  return ends == "natural" ? ir::SplineEnds::Natural
         : ends == "auto"  ? ir::SplineEnds::Auto
                           : ir::SplineEnds::Automatic;
}

// The host computes the tool path; method=aspline/bspline/cspline are the
// controller's splines, so no spline-as-chords warning.
ir::LoweringOptions sinumerikLowering(const TargetSettings& settings) {
  SinumerikOptions sinumerik;
  sinumerik.transitions = splineEndsOf(settings.splineEnds);
  ir::LoweringOptions lowering = sinumerikLoweringOptions(sinumerik);
  lowering.arcsOnEveryCut = settings.arcs;
  lowering.keepLoops = true; // written out by unroll-host-control
  return lowering;
}

SinumerikOptions sinumerikOptionsFor(const TargetSettings& settings) {
  SinumerikOptions options;
  options.sourceName = settings.sourceName;
  options.partName = settings.partName;
  const std::string& output = settings.outputPath;
  options.programName = output.empty() || output == "-" ? settings.partName : fileStem(output);
  options.inches = settings.inches;
  options.subprograms = settings.subprograms;
  options.setup = settings.setup;
  return options;
}

// How each cut's spline blocks were found (a NURBS as it is, reparametrised
// or re-fitted), for --stats.
std::string splineBlocksReport(const std::string& partName,
                               const std::vector<ir::CutGeometry>& cuts) {
  std::string text;
  for (std::size_t i = 0; i < cuts.size(); ++i) {
    if (!cuts[i].splineBlocks.empty()) {
      text += fmt::format("  cut {}: {}\n", i + 1, cuts[i].splineBlocks);
    }
  }
  return text.empty() ? text : fmt::format("spline blocks of part {}:\n{}", partName, text);
}

PrintedProgram printSinumerikProgram(const PrintInput& input) {
  SinumerikProgram program =
      writeSinumerik(*input.hostPath, input.function.tables, input.function.cuts.size(),
                     sinumerikOptionsFor(input.settings));
  PrintedProgram printed;
  printed.text = std::move(program.text);
  printed.lineOrigins = std::move(program.lineOrigins);
  printed.statistics = splineBlocksReport(input.settings.partName, input.function.cuts);
  return printed;
}

// The virtual Sinumerik's run, for `sim`: a rapid to where every axis is
// first known, then its moves (splines and arcs already in chords).
OwnProgramRun runSinumerikForSim(const std::string& text, const OwnReaderSettings& settings) {
  sinumerik::SinumerikRunOptions options;
  options.sampleTolerance = settings.chordError;
  options.toolRadii = settings.toolRadii; // by tool number
  sinumerik::SinumerikRun run = sinumerik::runSinumerikProgram(text, options);
  OwnProgramRun result;
  if (run.error) {
    // The message starts "[NAME, ]line N: ", which the location says already.
    std::string message = run.error->what();
    std::size_t after = message.find(": ");
    result.failure = ControllerFailure{
        run.error->line(), after == std::string::npos ? message : message.substr(after + 2), ""};
    return result;
  }
  ir::MachineEvent start;
  start.x = run.start.x();
  start.y = run.start.y();
  start.z = run.start.z();
  result.path.events.push_back(start);
  for (const sinumerik::ExecutedSinumerikMove& move : run.moves) {
    ir::MachineEvent event;
    bool rapid = move.kind == sinumerik::MotionKind::Rapid;
    event.kind = rapid ? ir::MachineEvent::Kind::Rapid : ir::MachineEvent::Kind::Feed;
    event.x = move.end.x();
    event.y = move.end.y();
    event.z = move.end.z();
    event.feed = rapid ? 0 : move.feed;
    result.path.events.push_back(event);
  }
  return result;
}

// A Sinumerik program in the virtual Sinumerik; it prints 5 decimals.
ProgramExecution runSinumerik(const ExecutionRequest& request) {
  ProgramExecution execution;
  execution.text = request.text;
  execution.increment = 1e-5;
  sinumerik::SinumerikRunOptions options;
  options.toolRadii = request.radiiOfTools;
  sinumerik::SinumerikRun run = sinumerik::runSinumerikProgram(request.text, options);
  if (run.error) {
    execution.failure = ControllerFailure{run.error->line(), run.error->what(),
                                          programLine(request.text, run.error->line())};
    return execution;
  }
  execution.path = sinumerik::executedPathOf(run, {});
  return execution;
}

} // namespace

const TargetInfo sinumerikTarget = {
    .name = "sinumerik",
    .description = "Siemens Sinumerik program: BSPLINE and A/B/C spline blocks",
    .lowering = sinumerikLowering,
    .print = printSinumerikProgram,
    .hostRun = HostRun::Interpreted,
    .splineOptions = true,
    .machineSetup = "sinumerik",
    .cutterCompensation = true,
    .execute = runSinumerik,
    .runOwnProgram = runSinumerikForSim,
};

} // namespace cncc::backends
