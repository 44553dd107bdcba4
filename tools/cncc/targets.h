// Compiling for the targets `-t` accepts, each described once in its
// backend folder (cncc/backends/target_info.h): the driver lowers the part
// as the target's TargetInfo says, runs it on the host when it asks, has it
// printed and writes the program. It asks the table, never a target's name.
#pragma once

#include "atomic_output_file.h"
#include "driver_options.h"

#include "cncc/backends/executed_path.h"
#include "cncc/backends/macro_program.h"
#include "cncc/backends/target_info.h"
#include "cncc/frontend/diagnostics.h"
#include "cncc/frontend/sema.h"
#include "cncc/lowering/lowering.h"

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::driver {

// What a backend is given: the checked program (its selected part is the one
// to compile), the options, where to report and where to write.
struct BackendRequest {
  const frontend::CheckedProgram& program;
  const frontend::SourceManager& sources;
  const DriverOptions& options;
  frontend::DiagnosticEngine& diagnostics;
  AtomicOutputFile& output;
  // When given, the backend puts here where each line it wrote comes from
  // (for --source-map).
  backends::LineOrigins* lineOrigins = nullptr;
  // And, on the macro targets, what each variable holds.
  std::map<int, backends::VariableMeaning>* variables = nullptr;
};

// The request's part compiled for its target: lowered, optimised and given
// the target's passes, run on the host when the target asks, printed, and
// written to the request's output; problems go to the request's diagnostics.
void compileForTarget(const BackendRequest& request);

// What the options and the part tell target `target` (its profile
// resolved), the program going to `outputPath`.
backends::TargetSettings targetSettings(const backends::TargetInfo& target,
                                        const DriverOptions& options,
                                        const frontend::PartItem& part,
                                        const std::string& outputPath = "-");

// How `target` lowers `part`: its own options, with what the machine set-up
// has (extended work offsets, through-spindle coolant) and the limits of
// the controller and the machine.
ir::LoweringOptions targetLoweringOptions(const backends::TargetInfo& target,
                                          const frontend::PartItem& part,
                                          const DriverOptions& options);

// The selected part lowered with the request's target's options, its IR
// verified, then optimised as the options ask, then given the target's
// passes before printing; nullopt when no part is selected or after a
// diagnostic.
std::optional<ir::LoweredPart> lowerForTarget(const BackendRequest& request);

// The selected part lowered for the request's target (and optimised,
// unless -O0) and run on the host: by the LLVM JIT when `native` and its
// module loads (jit_module.h), else by the IR interpreter; `cuts`, when
// given, receives the part's cut table. Nullopt after a diagnostic. What
// --stats measures.
std::optional<ir::ToolPath> hostToolPath(const BackendRequest& request, bool native = false,
                                         std::vector<ir::CutGeometry>* cuts = nullptr);

// The target `-t` names in the options; an internal error when there is
// none (the command line checks the name).
const backends::TargetInfo& optionsTarget(const DriverOptions& options);

} // namespace cncc::driver
