// One function per command of `cncc`. Each returns the process exit code:
// 0 success, 1 errors in the input (any error diagnostic), 2 wrong usage.
// A new command (verify, sim, plot, fmt, lsp) is a new function here, a
// Command value and its options in driver_options.cpp.
#pragma once

#include "driver_options.h"

namespace cncc::driver {

// cncc FILE -t TARGET [-o OUT]
int runCompile(const DriverOptions& options);
// cncc FILE --emit=tokens|ast [-o OUT]
int runEmit(const DriverOptions& options);
// cncc check FILE...
int runCheck(const DriverOptions& options);
// cncc --list-diagnostics
int runListDiagnostics();

// Runs the command `options` names.
int runCommand(const DriverOptions& options);

} // namespace cncc::driver
