// The programs `sim` runs in a reader of their target's own, and what they
// share with the macro controllers' run (sim_command.cpp): each returns the
// command's exit code.
#pragma once

#include "driver_options.h"

#include "cncc/ir/tool_path.h"

#include <string>

namespace cncc::driver {

// `text`, the program read from `path`, run; its tool path written to
// --output as CSV.
int simulateSinumerikProgram(const DriverOptions& options, const std::string& path,
                             const std::string& text);
int simulateLinuxcncProgram(const DriverOptions& options, const std::string& path,
                            const std::string& text);
int simulateTncProgram(const DriverOptions& options, const std::string& path,
                       const std::string& text);

// A usage error of `sim` (exit code 2).
int simulateUsageError(const std::string& message);
// A virtual controller's error at its line, with the line (exit code 1).
int reportSimulationError(const std::string& path, int line, const std::string& message,
                          const std::string& lineText);
// The path as CSV to --output, its arcs in chords of the --chord-error.
int writeSimulatedPath(const DriverOptions& options, const ir::ToolPath& path);

} // namespace cncc::driver
