#include "linuxcnc_target.h"

#include "commands.h"
#include "machine_options.h"
#include "targets.h"

#include "cncc/backends/linuxcnc_program.h"
#include "cncc/backends/macro_program.h"
#include "cncc/ir/verifier.h"
#include "cncc/lowering/lowering.h"

#include <fmt/format.h>

#include <optional>

namespace cncc::driver {

ir::LoweringOptions linuxcncLoweringOptions(const frontend::PartItem& part,
                                            const DriverOptions& options) {
  ir::LoweringOptions lowering;
  lowering.controllerLoops = true;
  lowering.literalSignificantDigits = backends::linuxcncSignificantDigits;
  // The program's literals have 5 decimals (6 in inches).
  lowering.coordinateIncrement = ir::partUnits(part) == ir::PartUnits::Inches ? 1e-6 : 1e-5;
  lowering.arcBlocks = true;
  lowering.arcsOnEveryCut = options.arcs;
  // LinuxCNC's TOLERANCE_CONCAVE_CORNER: cutter compensation takes corners
  // below it as tangent (seen in rs274's compensated moves).
  lowering.compensationTangentAngle = 0.05;
  lowering.passesBeforePrinting = backends::macroPassesBeforePrinting();
  return lowering;
}

void linuxcncBackend(const BackendRequest& request) {
  std::optional<ir::LoweredPart> lowered = lowerForTarget(request);
  if (!lowered) {
    return;
  }
  backends::GcodeOptions names = gcodeOptionsFor(request);
  backends::LinuxcncProgramOptions options;
  options.sourceName = names.sourceName;
  options.partName = names.partName;
  options.inches = names.inches;
  options.callable = request.options.macroCall;
  options.setup = machineSetup(request.options);
  options.blendTolerance = backends::linuxcncBlendTolerance(lowered->cuts);
  backends::LinuxcncProgram program = backends::writeLinuxcncProgram(lowered->function, options);
  writeProgramIfItFits(request, "LinuxCNC", program.errors, program.text,
                       std::move(program.lineOrigins));
}

} // namespace cncc::driver
