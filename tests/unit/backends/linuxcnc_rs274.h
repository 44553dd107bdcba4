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

// LinuxCNC's interpreter as a library: the `gcode` Python module of the
// same package, run by linuxcnc_canon_moves.py beside this file. It prints
// the canonical calls as rs274 does but at full double precision (17
// significant digits), lengths in the program's units (inches with
// `inches`), with the tool table and the work offsets rs274 gets.
struct GcodeModuleRun {
  int exitCode = -1;    // 0 ran to the end, 1 an interpreter error, -1 killed
  bool missing = false; // the module is not installed
  std::string canon;    // standard output
  std::string errors;   // standard error
};
GcodeModuleRun runGcodeModule(const std::string& program, const std::string& toolTable, bool inches,
                              int seconds = 60);

// A LinuxCNC tool table (`T5 P5 D6 ;`) with each tool change of the path
// and its diameter.
std::string toolTableOf(const ir::ToolPath& path);

} // namespace cncc::testing
