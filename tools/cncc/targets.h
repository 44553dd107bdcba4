// The targets `-t` accepts, each described once: its backend, how it lowers,
// what else it takes and can do. The driver asks the table, never a target's
// name. A target is known (its name is valid) before its backend exists; a
// backend makes it available by filling in `backend`.
#pragma once

#include "atomic_output_file.h"
#include "driver_options.h"

#include "cncc/backends/executed_path.h"
#include "cncc/backends/gcode_writer.h"
#include "cncc/backends/macro_program.h"
#include "cncc/frontend/diagnostics.h"
#include "cncc/frontend/sema.h"
#include "cncc/lowering/lowering.h"

#include <map>
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
  // When given, the backend puts here where each line it wrote comes from
  // (for --source-map).
  backends::LineOrigins* lineOrigins = nullptr;
  // And, on the macro targets, what each variable holds.
  std::map<int, backends::VariableMeaning>* variables = nullptr;
};

// Writes a printed program to the request's output, with --annotate's
// comments, and gives its line origins to the request (for --source-map).
void writeProgram(const BackendRequest& request, std::string_view text,
                  backends::LineOrigins lineOrigins);

// A printer's result: each of its `errors` reported at the part as not
// fitting `controller` (the limit it names), else the program written.
// Whether it was written.
bool writeProgramIfItFits(const BackendRequest& request, std::string_view controller,
                          const std::vector<std::string>& errors, std::string_view text,
                          backends::LineOrigins lineOrigins);

// Writes the program; problems go to the request's diagnostics.
using BackendFunction = void (*)(const BackendRequest& request);
// How the target lowers a part: what its backend lowers with, and what
// `--emit=ir -t TARGET` shows.
using LoweringFunction = ir::LoweringOptions (*)(const frontend::PartItem& part,
                                                 const DriverOptions& options);

// A host-computed target's program for the tool path the IR gave, and the
// path its execution makes (what --stats measures).
using HostProgramFunction = backends::ExecutedProgram (*)(const BackendRequest& request,
                                                          const ir::ToolPath& path);

// Runs the program `text` read from `path` (`sim`); the exit code.
using OwnProgramReader = int (*)(const DriverOptions& options, const std::string& path,
                                 const std::string& text);

using ParameterVariablesFunction = std::vector<int> (*)(std::size_t count,
                                                        const DriverOptions& options);

struct Target {
  std::string_view name;        // what `-t` takes
  std::string_view description; // one line, for --help
  BackendFunction backend;      // null until the backend exists
  LoweringFunction lowering;
  // Takes --arcs: prints planar curves as fitted G02/G03 arcs.
  bool fittedArcs = false;
  // Takes --subprograms and --spline-ends (the Sinumerik spline options).
  bool splineOptions = false;
  // A program that reads the part parameters from the controller's
  // variables: the controller profile it is printed for unless --profile
  // says otherwise; `sim`, `--profile` and `--params` need one.
  std::string_view controllerProfile = {};
  // Computed on the host: its program and execution, for --stats.
  HostProgramFunction hostProgram = nullptr;
  // A program that keeps the part parameters in variables of a kind of its
  // own (Heidenhain's Q), set at its top: the variable of each, which
  // `verify -D` edits there.
  ParameterVariablesFunction parameterVariables = nullptr;
  // Prints `comp=controller` cuts with the controller's cutter radius
  // compensation (G41/G42 D.., G40).
  bool cutterCompensation = false;
  // `sim` runs its program in a reader of its own (not the macro
  // controller's, so none of -a, --strict, --peck-retract, --peck-clearance).
  OwnProgramReader ownProgramReader = nullptr;
  // --profile names a TNC profile (tnc640, itnc530) for it, not a macro
  // controller's.
  bool tncProfiles = false;

  bool available() const { return backend != nullptr; }
  // How it lowers the part: `lowering`, with what the target's machine
  // set-up has (extended work offsets, through-spindle coolant).
  ir::LoweringOptions loweringOptions(const frontend::PartItem& part,
                                      const DriverOptions& options) const;
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
// The selected part lowered with the request's target's options, its IR
// verified, then optimised as the options ask, then given the target's
// passes before printing; nullopt when no part is selected or after a
// diagnostic.
std::optional<ir::LoweredPart> lowerForTarget(const BackendRequest& request);

std::optional<ir::ToolPath> hostToolPath(const BackendRequest& request, bool native = false,
                                         std::vector<ir::CutGeometry>* cuts = nullptr);

// How the gcode target prints the request's part (also what --stats measures).
backends::GcodeOptions gcodeOptionsFor(const BackendRequest& request);

std::span<const Target> allTargets();
const Target* findTarget(std::string_view name);
// "m80, fanuc, ..." in table order, for messages and --help: every target,
// or those `which` holds for.
std::string targetNameList(bool (*which)(const Target& target) = nullptr);

} // namespace cncc::driver
