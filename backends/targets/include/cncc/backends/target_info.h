// The targets `-t` takes. Each is described once, by a TargetInfo in its
// backend folder (say macro/src/macro_targets.cpp), and registered by one
// line of targets/src/registered_targets.def: how it lowers a part, how it prints the
// lowered part, what else it takes, and how its programs run for `verify`,
// `--stats` and `sim`. The driver asks this table, never a target's name.
#pragma once

#include "cncc/backends/controller_profile.h"
#include "cncc/backends/executed_path.h"
#include "cncc/backends/line_spans.h"
#include "cncc/backends/machine_setup.h"
#include "cncc/backends/macro_program.h"
#include "cncc/backends/program_execution.h"
#include "cncc/backends/tnc_profile.h"
#include "cncc/ir/cut_geometry.h"
#include "cncc/ir/ir.h"
#include "cncc/ir/lowering_options.h"
#include "cncc/ir/tool_path.h"

#include <cstddef>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::backends {

// What a compile tells its target: the part, where the program goes and
// what the command line and the machine file ask of it.
struct TargetSettings {
  std::string sourceName; // the input file's name, without its folders
  std::string partName;
  bool inches = false;          // the part's units
  std::string outputPath = "-"; // "-": standard output
  MachineSetup setup;           // the machine file's, else the target's built-in one
  // The profile the program is printed for: the machine file's or
  // --profile's, else the target's default (TargetInfo::controllerProfile,
  // or tnc640 for a target with tncProfiles); null for the others.
  const ControllerProfile* controllerProfile = nullptr;
  const TncProfile* tncProfile = nullptr;
  bool arcs = false;                  // --arcs
  bool macroCall = false;             // --macro: a G65-callable macro ending M99
  bool parametersInCommon = false;    // --params=common
  bool subprograms = false;           // Sinumerik --subprograms
  std::string splineEnds = "tangent"; // Sinumerik --spline-ends
};

// The settings' program number from the output file's name (O1000, o1000.ngc)
// or `otherwise`.
int programNumberOf(const TargetSettings& settings, int otherwise);

// What a target prints: the lowered part after its passes (its cut table
// too), and when the target asks for it (TargetInfo::hostRun) the tool path
// of its run on the host.
struct PrintInput {
  ir::Function& function;
  const ir::ToolPath* hostPath = nullptr;
  const TargetSettings& settings;
};

struct PrintedProgram {
  std::string text;
  LineOrigins lineOrigins;
  // Why the part cannot be printed (it does not fit the controller, say),
  // each reported at the part; nothing is written when there are any.
  std::vector<std::string> problems;
  std::map<int, VariableMeaning> variables; // what each #n holds (macro targets)
  std::string statistics;                   // shown by --stats before the measured figures
};

// `errors` of a printer as problems: "the part does not fit LIMIT: ERROR".
std::vector<std::string> doesNotFit(std::string_view limit, const std::vector<std::string>& errors);

// How `sim` runs a program in a reader of the target's own.
struct OwnReaderSettings {
  const TncProfile* tncProfile = nullptr; // --profile, for a target with TNC profiles
  std::map<int, double> toolRadii;        // --tool-radius and the machine file's
  double chordError = 1e-4;               // splines and arcs as chords within this
};

struct OwnProgramRun {
  ir::ToolPath path;
  std::optional<ControllerFailure> failure; // the run stopped here
};

// How the driver runs a lowered part on the host before printing it.
enum class HostRun {
  None,        // the target prints the IR
  Interpreted, // by the IR interpreter
  Native,      // by the LLVM JIT when it is built, else the interpreter
};

struct TargetInfo {
  std::string_view name;        // what `-t` takes
  std::string_view description; // one line, for --help
  ir::LoweringOptions (*lowering)(const TargetSettings& settings) = nullptr;
  PrintedProgram (*print)(const PrintInput& input) = nullptr;
  HostRun hostRun = HostRun::None;
  // Takes --arcs (arcs=true): prints planar curves as fitted arcs. The jit's
  // tool path is points, so it does not.
  bool fittedArcs = true;
  // Takes --subprograms and --spline-ends (the Sinumerik spline options).
  bool splineOptions = false;
  // A program that reads the part parameters from the controller's
  // variables: the controller profile it is printed for unless --profile
  // says otherwise; `sim`, `--profile` and `--params` need one.
  std::string_view controllerProfile = {};
  // --profile names a TNC profile (tnc640, itnc530) for it.
  bool tncProfiles = false;
  // The built-in machine set-up its programs start and end with
  // (builtinMachineSetup), which a machine file (`--machine`) may replace;
  // empty: machine files are not for it.
  std::string_view machineSetup = {};
  // Prints `comp=controller` cuts with the controller's cutter radius
  // compensation (G41/G42 D.., G40).
  bool cutterCompensation = false;
  // Computed on the host: its program and execution for a tool path, for
  // --stats (throws ExecutionMismatch when they disagree).
  ExecutedProgram (*hostProgram)(const TargetSettings& settings,
                                 const ir::ToolPath& path) = nullptr;
  // Runs a program the target printed, for `verify`; null: not verifiable.
  ProgramExecutor execute = nullptr;
  // A program that keeps the part parameters in variables of a kind of its
  // own (Heidenhain's Q), set at its top: the variable of each of `count`,
  // which `verify -D` edits there.
  std::vector<int> (*parameterVariables)(std::size_t count,
                                         const TargetSettings& settings) = nullptr;
  // `sim` runs its programs in a reader of its own (not the macro
  // controller's, so none of -a, --strict, --peck-retract, --peck-clearance).
  OwnProgramRun (*runOwnProgram)(const std::string& text,
                                 const OwnReaderSettings& settings) = nullptr;
};

// Every registered target, in the order --help lists them.
std::span<const TargetInfo* const> allTargetInfos();
// Null when no target is called `name`.
const TargetInfo* findTargetInfo(std::string_view name);
// "m80, fanuc, ..." in the registry's order: every target, or those `which`
// holds for.
std::string targetNameList(bool (*which)(const TargetInfo& target) = nullptr);

} // namespace cncc::backends
