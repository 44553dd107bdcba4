// The virtual controller: runs a Fanuc Custom Macro B / Mitsubishi M80
// program the way the controller would (macro statements, variables with
// vacant values, G65 calls, loops, G00/G01/G02/G03 motion with coordinates
// rounded to the least input increment) and records the executed path. It
// judges what the backends print: whatever the profile's controller would
// refuse is an error naming the line, never a guess.
#pragma once

#include "cncc/backends/controller_profile.h"
#include "cncc/backends/sim_program.h"
#include "cncc/ir/tool_path.h"

#include <array>
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::backends::sim {

struct Point3 {
  double x = 0, y = 0, z = 0;
};

// One thing the program made the machine do, in order.
struct ExecutedEvent {
  enum class Kind {
    Rapid,               // G00 to `end`
    Feed,                // G01 to `end`
    ClockwiseArc,        // G02 from `start` to `end` around `centre` (G17: XY)
    CounterclockwiseArc, // G03
    ToolChange,          // M06 with tool `number`
    Spindle,             // spindle speed `number` rpm, 0 when stopped
  };
  Kind kind = Kind::Rapid;
  Point3 start, end;
  Point3 centre;   // arcs; z is the start's
  double feed = 0; // Feed and arcs: per minute, in the program's units
  double number = 0;
  int line = 0; // the block that commanded it
};

struct ExecutedPath {
  std::vector<ExecutedEvent> events;
  bool inches = false; // G20 was in effect at the end
};

// A G65 argument such as `A3.`.
struct MacroArgument {
  char letter = 'A';
  double value = 0;
};

struct SimulationOptions {
  // Run the main program as if called by `G65 P.. <arguments>`: its locals
  // start from the arguments and M99 ends the run.
  bool runAsMacroCall = false;
  std::vector<MacroArgument> arguments;
  // Common variables (#100.., #500..) set before the run, as an operator
  // sets the parameters of a program that reads them there.
  std::map<int, double> commonVariables;
  // The safety net against endless loops: blocks executed in all.
  std::size_t stepLimit = 10'000'000;
  // How the program is read (strict: as the compiler's output must be).
  ReadingRules reading;
  // The tool radius in each offset register, read by `D n` for G41/G42 (a
  // register not given here is an error, not 0).
  std::map<int, double> toolRadii;
  // The parameters of the peck drilling cycles: G73's retract after each
  // peck and G83's clearance above the last depth (Fanuc parameters 5114 and
  // 5115). Unset: G73/G83 are refused rather than guessed.
  std::optional<double> peckRetract;
  std::optional<double> peckClearance;
};

struct SimulationResult {
  ExecutedPath path;                    // what ran up to the end, or the error
  std::optional<SimulationError> error; // the first error, if any
  std::size_t blocksExecuted = 0;
  // How often each block of readProgram's ProgramText ran, by index.
  std::vector<std::size_t> blockExecutions;
  // The common variables (#100.., #500..) the program assigned, as they were
  // at the end: nullopt for vacant.
  std::map<int, std::optional<double>> commonVariables;
};

// Reads and runs `text`. Never throws for a bad program: the error is in
// the result.
SimulationResult simulateProgram(std::string_view text, const ControllerProfile& profile,
                                 const SimulationOptions& options = {});

// Parses `-a` arguments such as "A3." (letter, number with a decimal point);
// nullopt with `problem` set when the text is not one.
std::optional<MacroArgument>
parseMacroArgument(std::string_view text, const ControllerProfile& profile, std::string& problem);

// The path as a polyline: arcs split into chords whose sagitta is at most
// `maximumSagitta` (program units), tool changes and spindle speeds kept.
ir::ToolPath flattenPath(const ExecutedPath& path, double maximumSagitta = 1e-4);
// The path as tool path events, arcs kept as arcs.
ir::ToolPath executedToolPath(const ExecutedPath& path);

} // namespace cncc::backends::sim
