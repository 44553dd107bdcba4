// The `linuxcnc` target: the part as a LinuxCNC program whose o-word loops
// evaluate the curve on the controller, its parameters named globals.
#pragma once

#include "targets.h"

namespace cncc::driver {

void linuxcncBackend(const BackendRequest& request);
// The controller runs the curve loops; LinuxCNC computes in doubles, so no
// input increment takes from the tolerance.
ir::LoweringOptions linuxcncLoweringOptions(const frontend::PartItem& part,
                                            const DriverOptions& options);

} // namespace cncc::driver
