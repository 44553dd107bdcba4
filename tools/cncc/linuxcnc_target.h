// The `linuxcnc` target: the part as a LinuxCNC program whose o-word loops
// evaluate the curve on the controller, its parameters named globals.
#pragma once

#include "targets.h"

namespace cncc::driver {

void linuxcncBackend(const BackendRequest& request);

} // namespace cncc::driver
