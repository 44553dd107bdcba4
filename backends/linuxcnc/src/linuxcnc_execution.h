// A LinuxCNC program run for `verify`: through LinuxCNC's interpreter as
// the Python module `gcode` where it imports, else its program rs274.
#pragma once

#include "cncc/backends/program_execution.h"

namespace cncc::backends {

ProgramExecution runLinuxcnc(const ExecutionRequest& request);

} // namespace cncc::backends
