// Runs LinuxCNC's standalone interpreter on a program: `rs274 -g FILE`, as
// installed by the Debian package linuxcnc-uspace (.ci/run installs it).
#pragma once

#include "cncc/backends/rs274.h"
#include "cncc/ir/tool_path.h"

#include <optional>
#include <string>

namespace cncc::testing {

using backends::findRs274;
using backends::Rs274Run;
using backends::runRs274;

// Declares `name`, the rs274 to run, or fails the test: the README's set-up
// command and .ci/run install LinuxCNC, so a missing rs274 is a broken
// set-up, not a reason to pass.
#define CNCC_FIND_RS274(name)                                                                      \
  std::optional<std::string> name = ::cncc::testing::findRs274();                                  \
  if (!name) {                                                                                     \
    FAIL() << "rs274 (Debian package linuxcnc-uspace) is not installed";                           \
  }

// LinuxCNC's interpreter as a library (the `gcode` Python module), as
// `cncc verify -t linuxcnc` runs it.
using backends::GcodeModuleRun;
using backends::runGcodeModule;

// A LinuxCNC tool table (`T5 P5 D6 ;`) with each tool change of the path
// and its diameter.
std::string toolTableOf(const ir::ToolPath& path);

} // namespace cncc::testing
