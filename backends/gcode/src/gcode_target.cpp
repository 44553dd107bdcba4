// The `gcode` target: the part run on the host, printed as plain G-code
// (G00/G01, and G02/G03 where the cut is an arc or asks for fitted arcs).
#include "registered_targets.h"

#include "cncc/backends/gcode_writer.h"

#include <cmath>

namespace cncc::backends {

namespace {

// The controller the program is checked on: Fanuc's reader at the 4
// decimals the gcode target prints (0.0001 mm).
ControllerProfile gcodeReaderProfile() {
  ControllerProfile profile = *findControllerProfile("fanuc");
  profile.coordinateDecimals = GcodeOptions{}.decimals;
  profile.leastInputIncrement = std::pow(10.0, -GcodeOptions{}.decimals);
  return profile;
}

// The printed coordinates are rounded to the printed decimals: the chords
// leave that rounding room inside the tolerance. At 4 decimals the reader's
// significant digits leave 9999.9999 as the largest coordinate (and centre
// offset of a fitted arc).
ir::LoweringOptions gcodeLowering(const TargetSettings& settings) {
  ControllerProfile reader = gcodeReaderProfile();
  ir::LoweringOptions options;
  options.coordinateIncrement = reader.leastInputIncrement;
  options.largestCoordinate =
      (std::pow(10.0, reader.significantDigits) - 1) * reader.leastInputIncrement;
  options.arcsOnEveryCut = settings.arcs;
  options.keepLoops = true; // written out by unroll-host-control
  return options;
}

GcodeOptions gcodeOptionsFor(const TargetSettings& settings) {
  GcodeOptions options;
  options.programNumber = programNumberOf(settings, 1);
  options.sourceName = settings.sourceName;
  options.partName = settings.partName;
  options.inches = settings.inches;
  options.setup = settings.setup;
  return options;
}

PrintedProgram printGcode(const PrintInput& input) {
  GcodeProgram program = writeGcodeProgram(*input.hostPath, gcodeOptionsFor(input.settings));
  PrintedProgram printed;
  printed.text = std::move(program.text);
  printed.lineOrigins = std::move(program.lineOrigins);
  return printed;
}

// The program for a tool path, run by the G-code reader.
ExecutedProgram gcodeProgram(const TargetSettings& settings, const ir::ToolPath& path) {
  GcodeOptions options = gcodeOptionsFor(settings);
  std::string text = writeGcode(path, options);
  ExecutedPath executed = executeGcode(text, path, options.decimals);
  std::size_t blocks = countProgramBlocks(text);
  return {std::move(text), blocks, std::move(executed)};
}

// Plain G-code on a controller that takes the 4 decimals the gcode target
// prints (0.0001 mm).
ProgramExecution runGcode(const ExecutionRequest& request) {
  ExecutionRequest plain = request;
  plain.passing = ParameterPassing::None;
  return runOnController(plain, gcodeReaderProfile());
}

} // namespace

const TargetInfo gcodeTarget = {
    .name = "gcode",
    .description = "plain G-code: G00/G01 and G02/G03 blocks computed on the host",
    .lowering = gcodeLowering,
    .print = printGcode,
    .hostRun = HostRun::Interpreted,
    .machineSetup = "gcode",
    .cutterCompensation = true,
    .hostProgram = gcodeProgram,
    .execute = runGcode,
};

} // namespace cncc::backends
