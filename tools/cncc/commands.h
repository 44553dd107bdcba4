// One function per command of `cncc`. Each returns the process exit code:
// 0 success, 1 errors in the input (any error diagnostic), 2 wrong usage.
// A new command (verify, sim, plot, fmt, lsp) is a new function here, a
// Command value and its options in driver_options.cpp.
#pragma once

#include "driver_options.h"
#include "source_map.h"

#include "cncc/backends/path_statistics.h"
#include "cncc/ir/passes.h"
#include "targets.h"

#include <span>
#include <stdexcept>
#include <vector>

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
// cncc plot FILE [-o OUT.svg] [-t TARGET] (plot_command.cpp)
int runPlot(const DriverOptions& options);
// The cuts' deviations of a measured part, as `measured` gets them.
void collectCutDeviations(const backends::PathStatistics& statistics,
                          std::span<const ir::CutGeometry> cuts,
                          std::vector<MeasuredCutDeviation>* measured);

// After a compile with --stats: measures what the target wrote and prints
// the statistics to stderr (stats_command.cpp); each cut's deviation goes to
// `measured` when given. Returns the exit code.
int printStatistics(const BackendRequest& request,
                    std::vector<MeasuredCutDeviation>* measured = nullptr);

// cncc opt FILE.ir [--passes=a,b] (opt_command.cpp)
int runOptimize(const DriverOptions& options);
// Runs the passes the options ask for (the default pipeline unless -O0 or
// --passes), printing as --print-after asks; throws InternalError when the
// result does not verify.
void optimise(ir::Function& function, const DriverOptions& options);
// Then the target's passes before printing (LoweringOptions::
// passesBeforePrinting), at -O0 too, printing as --print-after asks; throws
// InternalError for an unknown name or a result that does not verify.
void runPassesBeforePrinting(ir::Function& function, const ir::LoweringOptions& lowering,
                             const DriverOptions& options);
// What --print-after asks: prints the function after the named pass (or
// every pass) on standard error; empty without it.
ir::AfterPassCallback printAfterCallback(const DriverOptions& options);

// cncc sim PROGRAM -t fanuc|m80 [-a A3.] [-o OUT] (sim_command.cpp)
int runSimulate(const DriverOptions& options);

// cncc verify FILE -t TARGET [-D NAME=VALUE ...] (verify_command.cpp)
int runVerify(const DriverOptions& options);
// `cncc where PROGRAM LINE|Nnnnn`: the CDL source of a program line, from the
// program's source map. 0 found, 1 an unreadable or mismatched map or line.
int runWhere(const DriverOptions& options);
// Whether `cncc verify` can run target `name`'s programs.
bool canVerify(std::string_view name);

// The name of the file at `path`, without its folders.
std::string fileName(const std::string& path);
// --stats of a target measured by running its program on the virtual
// controller (m80, fanuc): the report of verify, on stderr.
int printVerifiedStatistics(const BackendRequest& request,
                            std::vector<MeasuredCutDeviation>* measured = nullptr);

// Runs the command `options` names.
int runCommand(const DriverOptions& options);

} // namespace cncc::driver
