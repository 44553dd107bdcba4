// Mitsubishi M70/M80/M800 and Fanuc Custom Macro B programs that evaluate
// the part on the controller: IR loops become WHILE [..] DOm .. ENDm, IR
// values become controller variables (ir::allocateVariables) or inline
// bracket expressions, part parameters stay editable variables. One printer
// serves both controllers; the ControllerProfile says what differs.
//
// Layout: `%`, `O<number>`, a comment table of every variable the program
// uses (part parameters first, with defaults), the safety line, the
// parameters' defaults, the tables, tool and spindle, the moves, `M30` (a
// main program) or `M99` (a macro called with `G65 P<number> A.. B..`, the
// call given in the header), `%`. A program that exceeds a limit of the
// profile is refused with the limit and the count named.
#pragma once

#include "cncc/backends/controller_profile.h"
#include "cncc/backends/line_spans.h"
#include "cncc/backends/machine_setup.h"
#include "cncc/ir/ir.h"
#include "cncc/ir/lowering_options.h"
#include "cncc/ir/register_allocation.h"

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace cncc::backends {

struct MacroProgramOptions {
  int programNumber = 1000;
  std::string sourceName; // for the header comment, e.g. "s_profile.cdl"
  std::string partName;
  bool inches = false;
  bool callable = false;           // --macro: ends M99, parameters are G65 arguments
  bool parametersInCommon = false; // --params=common: parameters in retained common variables
  MachineSetup setup = builtinMachineSetup("fanuc");
};

struct MacroProgramStatistics {
  int variables = 0;                    // distinct variables the program uses
  int blocks = 0;                       // lines between the `%` lines
  std::size_t bytes = 0;                // the whole text
  std::size_t bytesWithoutComments = 0; // without comments and comment-only lines
};

// What a variable of the program holds, for source maps: "parameter
// holes", "loop index", "work value", ..., and the CDL statements of the
// values it holds.
struct VariableMeaning {
  std::string meaning;
  std::vector<frontend::SourceSpan> spans;
};

struct MacroProgram {
  std::string text;                // empty when errors is not
  std::vector<std::string> errors; // each names the limit and the count
  MacroProgramStatistics statistics;
  // Where each line of `text` was printed from (an invalid span: the part's
  // header, before any statement).
  LineOrigins lineOrigins;
  std::map<int, VariableMeaning> variables; // by variable number
};

// Where the part parameters go: G65 argument locals in letter order
// (#1=A, #2=B, #3=C, #4=I, ...), or the first retained common variables.
// Fewer variables than parameters is reported in `errors`.
std::vector<int> macroParameterVariables(std::size_t parameterCount,
                                         const ControllerProfile& profile, bool inCommon,
                                         std::vector<std::string>& errors);

// What the register allocator is told about this controller.
ir::AllocationOptions macroAllocationOptions(const ControllerProfile& profile,
                                             std::vector<int> parameterVariables);

// How to lower a part for this controller: the curve loops run on the
// controller (LoweringOptions::controllerLoops), its least input increment
// (IS-B: 0.001 mm, 0.0001 inch) counted in each cut's tolerance budget.
ir::LoweringOptions macroLoweringOptions(const ControllerProfile& profile, bool inches);

// The passes the macro printers (this one, LinuxCNC's and Heidenhain's) take
// their IR after, as LoweringOptions::passesBeforePrinting:
// drop-pass-depths (a pass loop they run says no depth), expand-whole-powers
// (a ^ 2 as a * a: their EXP[LN[a]*2] or power function alarms for a <= 0)
// and fold-finite, since their controllers alarm where a value is not finite.
std::vector<std::string> macroPassesBeforePrinting();

// Prints the function as it is: whatever is folded was folded by the passes
// before printing (macroPassesBeforePrinting).
MacroProgram writeMacroProgram(const ir::Function& function, const ControllerProfile& profile,
                               const MacroProgramOptions& options);

// Counts of a program text: blocks, bytes, bytes without comments (`( ... )`,
// and LinuxCNC's `;` to the end of the line).
MacroProgramStatistics measureMacroProgram(const std::string& text);

} // namespace cncc::backends
