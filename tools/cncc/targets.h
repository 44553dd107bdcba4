// The targets `-t` accepts. A target is known (its name is valid) before its
// backend exists; a backend makes it available by filling in `backend`.
#pragma once

#include "atomic_output_file.h"
#include "driver_options.h"

#include "cncc/backends/gcode_writer.h"
#include "cncc/frontend/diagnostics.h"
#include "cncc/frontend/sema.h"
#include "cncc/ir/lowering.h"

#include <optional>
#include <span>
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
};

// Writes the program; problems go to the request's diagnostics.
using BackendFunction = void (*)(const BackendRequest& request);
// How the target lowers a part: what its backend lowers with, and what
// `--emit=ir -t TARGET` shows.
using LoweringFunction = ir::LoweringOptions (*)(const frontend::PartItem& part,
                                                 const DriverOptions& options);

struct Target {
  std::string_view name;        // what `-t` takes
  std::string_view description; // one line, for --help
  BackendFunction backend;      // null until the backend exists
  LoweringFunction lowering;

  bool available() const { return backend != nullptr; }
};

// How the host-side targets (gcode, jit) lower a part.
ir::LoweringOptions gcodeLoweringOptions(const frontend::PartItem& part,
                                         const DriverOptions& options);
ir::LoweringOptions jitLoweringOptions(const frontend::PartItem& part,
                                       const DriverOptions& options);

// The selected part lowered so (and optimised, unless -O0) and run on the
// host: by the LLVM JIT when `native` and its module loads (jit_module.h),
// else by the IR interpreter; `cuts`, when given, receives the part's cut
// table. Nullopt after a diagnostic; IR that does not verify is an internal
// error. What the gcode and jit targets print, and what --stats measures.
std::optional<ir::ToolPath> hostToolPath(const BackendRequest& request, bool native = false,
                                         std::vector<ir::CutGeometry>* cuts = nullptr);

// How the gcode target prints the request's part (also what --stats measures).
backends::GcodeOptions gcodeOptionsFor(const BackendRequest& request);

std::span<const Target> allTargets();
const Target* findTarget(std::string_view name);
// "m80, fanuc, ..." in table order, for messages and --help.
std::string targetNameList();

} // namespace cncc::driver
