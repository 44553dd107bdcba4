// LinuxCNC's interpreter (Debian package linuxcnc-uspace), two ways: as a
// library, its Python module `gcode`, which hands every value over as a
// double, and as the standalone program `rs274 -g FILE`, which prints four
// decimals. `cncc verify -t linuxcnc` and the tests run a LinuxCNC program
// through them; both print canonical calls, read by readLinuxcncCanon
// (linuxcnc_canon.h).
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace cncc::backends {

// The rs274 executable on PATH; nullopt when LinuxCNC is not installed.
std::optional<std::string> findRs274();

// A tool table (`T5 P5 D0 ;`) with every tool the program names in a `T`
// or `H` word: rs274 refuses `T5 M6` or `G43 H5` for a tool its table does
// not have. `radii` (in the program's units, inches with `inches`) gives
// the entries that `G41 D<n>` reads their diameter from; rs274 keeps its
// table in inches.
std::string rs274ToolTable(std::string_view program, const std::map<int, double>& radii = {},
                           bool inches = false);

// rs274 runs with every work offset's Z at minus this (mm), so that the
// machine's Z0 (`G53 G0 Z0`, the retract at the end) is this far above the
// work's zero, as on a machine, rather than at it; its canonical calls then
// show the retract as a SET_G5X_OFFSET and a traverse to that height.
inline constexpr double rs274ReferenceHeight = 254;
// The parameter file that sets those offsets.
std::string rs274WorkOffsets();

struct Rs274Run {
  int exitCode = -1;  // -1: it did not finish (killed after the time limit)
  std::string canon;  // standard output: the canonical calls
  std::string errors; // standard error
};

// Writes `program` and `toolTable` to a fresh temporary directory and runs
// `rs274 -t TABLE -g PROGRAM`, for at most `seconds` (a program that loops
// for ever is stopped). One run at a time across processes: concurrent runs
// were seen to read each other's tool table.
Rs274Run runRs274(const std::string& rs274, const std::string& program,
                  const std::string& toolTable, int seconds = 60);

// The Python that runs LinuxCNC's module: $CNCC_LINUXCNC_PYTHON, else
// Debian's /usr/bin/python3, for which the package builds it.
std::string gcodeModulePython();

struct GcodeModuleRun {
  int exitCode = -1;         // 0 ran to the end, 1 an interpreter error, -1 killed
  bool missing = false;      // no Python, or it cannot import the module
  bool tooManyCalls = false; // stopped at the maximum number of calls
  std::string canon;         // the canonical calls, one a line
  std::string errors;        // standard error: the interpreter's message
};

// Runs `program` through LinuxCNC's interpreter as a library: the script
// linuxcnc_canon_moves.py (embedded in cncc, written to a fresh temporary
// directory with the tool table and the work offsets rs274 gets) run by
// gcodeModulePython(). It prints the canonical calls as rs274 does but at
// full double precision (17 significant digits), lengths in the program's
// units (inches with `inches`). A run is stopped after `seconds`, and after
// `maximumCalls` calls.
GcodeModuleRun runGcodeModule(const std::string& program, const std::string& toolTable, bool inches,
                              int seconds = 60, std::size_t maximumCalls = 0 /* no limit */);

} // namespace cncc::backends
