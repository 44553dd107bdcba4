// Running a target's program text to find the path it executes: what
// `cncc verify` measures. A target that can be verified names its executor
// in its TargetInfo (target_info.h): the macro targets run in the virtual
// controller with the part parameters given as the operator gives them
// (runMacroProgram), gcode runs there as plain G-code, jit's tool path is
// read back, the others run in their controllers' readers.
#pragma once

#include "cncc/backends/controller_profile.h"
#include "cncc/backends/executed_path.h"
#include "cncc/backends/sim_operation_count.h"
#include "cncc/ir/tool_path.h"

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::backends {

// How the operator gives a program that keeps its part parameters
// symbolic their values (without recompiling it).
enum class ParameterPassing {
  None,            // computed on the host: the program holds the values already
  EditedDefaults,  // the program sets `#n=default` near its top: those lines are edited
  MacroArguments,  // a macro (ends M99) called by G65 P.. with one argument per parameter
  CommonVariables, // common variables set before the program runs
};

struct ParameterValue {
  std::string name;
  int variable = 0; // the variable the program reads it from
  double value = 0;
};

struct ExecutionRequest {
  std::string text;    // the program as the target wrote it
  std::string profile; // the controller profile (empty: the target's default)
  // A machine file's profile, which replaces `profile` when given.
  std::optional<ControllerProfile> machineProfile;
  ParameterPassing passing = ParameterPassing::None;
  // Only the parameters the operator sets; the others keep their defaults.
  std::vector<ParameterValue> parameters;
  bool callable = false; // the program ends with M99: it runs as if called by G65
  // The machine writes comments as the source has them (lower case too).
  bool lowerCaseComments = false;
  // The tool radius in each offset register the program's G41/G42 read.
  std::map<int, double> toolRadii;
  // The radius of each tool, by its number, that the program compensates
  // with, for a control that takes it from the tool's data: a Sinumerik's
  // G41/G42 read the active tool's cutting edge, a TNC's RL/RR its tool table.
  std::map<int, double> radiiOfTools;
};

// The controller refused the program: the message names its line.
struct ControllerFailure {
  int line = 0; // 1-based in the text the controller ran; 0: no line
  std::string message;
  std::string lineText;
};

struct ProgramExecution {
  std::string text;     // what ran (the request's, with the edits the operator made)
  ExecutedPath path;    // feed moves without cuts: assignCuts gives them theirs
  double increment = 0; // the least increment the controller rounds coordinates to
  std::optional<ControllerFailure> failure;
  std::optional<sim::LoopOperationCounts> operations; // programs with loops
  std::optional<std::size_t> variables;               // distinct #n the program names
  std::vector<std::string> notes; // how it ran, where the output should say (a fallback)
};

using ProgramExecutor = ProgramExecution (*)(const ExecutionRequest& request);

// A run that failed before the controller read a block (line 0) or at `line`.
ProgramExecution failedExecution(std::string text, int line, std::string message);

// The radius each of the path's cutter radius compensations is for, by the
// offset register it reads (what ExecutionRequest::toolRadii gives), or
// (`byTool`) by the number of the tool in use (ExecutionRequest::radiiOfTools).
std::map<int, double> compensationRadii(const ir::ToolPath& path, bool byTool);

// The line `number` (1-based) of a program's text; empty past its end.
std::string programLine(std::string_view text, int number);

// The program in the virtual macro controller with `profile`.
ProgramExecution runOnController(const ExecutionRequest& request, const ControllerProfile& profile);
// In the profile the request names (its machine profile, else `profile`,
// else `defaultProfile`).
ProgramExecution runMacroProgram(const ExecutionRequest& request, std::string_view defaultProfile);

} // namespace cncc::backends
