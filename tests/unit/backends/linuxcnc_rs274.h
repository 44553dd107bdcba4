// Runs LinuxCNC's standalone interpreter on a program: `rs274 -g FILE`, as
// installed by the Debian package linuxcnc-uspace (.ci/run installs it).
#pragma once

#include "cncc/ir/tool_path.h"

#include <optional>
#include <string>

namespace cncc::testing {

// The rs274 executable on PATH; nullopt when LinuxCNC is not installed.
std::optional<std::string> findRs274();

// Declares `name`, the rs274 to run, or fails the test: the README's set-up
// command and .ci/run install LinuxCNC, so a missing rs274 is a broken
// set-up, not a reason to pass.
#define CNCC_FIND_RS274(name)                                                                      \
  std::optional<std::string> name = ::cncc::testing::findRs274();                                  \
  if (!name) {                                                                                     \
    FAIL() << "rs274 (Debian package linuxcnc-uspace) is not installed";                           \
  }

struct Rs274Run {
  int exitCode = -1;
  std::string canon;  // standard output: the canonical calls
  std::string errors; // standard error
};

// A LinuxCNC tool table (`T5 P5 D6 ;`) with each tool change of the path:
// rs274 refuses `T5 M6` for a tool its table does not have.
std::string toolTableOf(const ir::ToolPath& path);

// Writes `program` and `toolTable` to temporary files and runs
// `rs274 -t TABLE -g PROGRAM`.
Rs274Run runRs274(const std::string& rs274, const std::string& program,
                  const std::string& toolTable = "");

} // namespace cncc::testing
