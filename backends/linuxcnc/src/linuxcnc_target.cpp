// The `linuxcnc` target: the part as a LinuxCNC program whose o-word loops
// evaluate the curve on the controller, its parameters named globals.
#include "linuxcnc_execution.h"
#include "registered_targets.h"

#include "cncc/backends/linuxcnc_controller.h"
#include "cncc/backends/linuxcnc_program.h"
#include "cncc/backends/macro_program.h"

namespace cncc::backends {

namespace {

// The controller runs the curve loops; LinuxCNC computes in doubles, so no
// input increment takes from the tolerance.
ir::LoweringOptions linuxcncLowering(const TargetSettings& settings) {
  ir::LoweringOptions lowering;
  lowering.controllerLoops = true;
  lowering.literalSignificantDigits = linuxcncSignificantDigits;
  // The program's literals have 5 decimals (6 in inches).
  lowering.coordinateIncrement = settings.inches ? 1e-6 : 1e-5;
  // LinuxCNC's TOLERANCE_CONCAVE_CORNER: cutter compensation takes corners
  // below it as tangent (seen in rs274's compensated moves).
  lowering.compensationTangentAngle = 0.05;
  lowering.passesBeforePrinting = macroPassesBeforePrinting();
  lowering.arcsOnEveryCut = settings.arcs;
  return lowering;
}

PrintedProgram printLinuxcncProgram(const PrintInput& input) {
  LinuxcncProgramOptions options;
  options.sourceName = input.settings.sourceName;
  options.partName = input.settings.partName;
  options.inches = input.settings.inches;
  options.callable = input.settings.macroCall;
  options.setup = input.settings.setup;
  options.blendTolerance = linuxcncBlendTolerance(input.function.cuts);
  LinuxcncProgram program = writeLinuxcncProgram(input.function, options);
  PrintedProgram printed;
  printed.problems = doesNotFit("LinuxCNC", program.errors);
  printed.text = std::move(program.text);
  printed.lineOrigins = std::move(program.lineOrigins);
  return printed;
}

// The virtual LinuxCNC's run, for `sim`.
OwnProgramRun runLinuxcncForSim(const std::string& text, const OwnReaderSettings& settings) {
  sim::LinuxcncRunOptions options;
  options.toolRadii = settings.toolRadii; // by tool number (G41/G42 D<tool>)
  sim::LinuxcncRun run = sim::runLinuxcncProgram(text, options);
  OwnProgramRun result;
  if (run.error) {
    result.failure = ControllerFailure{run.error->line(), run.error->what(), run.error->lineText()};
  } else {
    result.path = sim::executedToolPath(sim::executedPathOf(run));
  }
  return result;
}

} // namespace

const TargetInfo linuxcncTarget = {
    .name = "linuxcnc",
    .description = "LinuxCNC program with o-word loops and parameters",
    .lowering = linuxcncLowering,
    .print = printLinuxcncProgram,
    .machineSetup = "linuxcnc",
    .cutterCompensation = true,
    .execute = runLinuxcnc,
    .runOwnProgram = runLinuxcncForSim,
};

} // namespace cncc::backends
