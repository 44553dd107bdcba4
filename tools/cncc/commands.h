// One function per command of `cncc`. Each returns the process exit code:
// 0 success, 1 errors in the input (any error diagnostic), 2 wrong usage.
// A new command (verify, sim, plot, fmt, lsp) is a new function here, a
// Command value and its options in driver_options.cpp.
#pragma once

#include "driver_options.h"

#include <stdexcept>

namespace cncc::driver {

// A bug in cncc itself (say, lowered IR that does not verify): main()
// reports it as an internal error, exit 1, and no output file is written.
class InternalError : public std::logic_error {
public:
  using std::logic_error::logic_error;
};

// cncc FILE -t TARGET [-o OUT]
int runCompile(const DriverOptions& options);
// cncc FILE --emit=tokens|ast|ir [-o OUT]
int runEmit(const DriverOptions& options);
// cncc check FILE...
int runCheck(const DriverOptions& options);
// cncc --list-diagnostics
int runListDiagnostics();
// cncc fmt FILE... [--check | -i] (format_and_lsp_commands.cpp)
int runFormat(const DriverOptions& options);
// cncc lsp (format_and_lsp_commands.cpp)
int runLanguageServer();

// Runs the command `options` names.
int runCommand(const DriverOptions& options);

} // namespace cncc::driver
