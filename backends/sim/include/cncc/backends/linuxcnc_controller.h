// The virtual controller in LinuxCNC's dialect: reads a LinuxCNC program
// (o-word subroutines and loops, numbered and named parameters, `[ ]`
// expressions, G0-G3 with helical turns) and runs it as LinuxCNC's
// interpreter does, recording the moves in the form of LinuxCNC's canonical
// calls (a traverse, a feed, an arc with its turns). backends/sim/README.md
// lists what is read; anything else is an error naming the line.
#pragma once

#include "cncc/backends/virtual_controller.h"

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::backends::sim {

// One move as LinuxCNC's canonical calls give it (STRAIGHT_TRAVERSE,
// STRAIGHT_FEED, ARC_FEED), or a tool change or a spindle speed.
struct LinuxcncMove {
  enum class Kind { Traverse, Feed, Arc, ToolChange, Spindle };
  Kind kind = Kind::Traverse;
  Point3 start{}, end{};
  Point3 centre{};   // Arc: in the XY plane (z is the start's)
  int turns = 0;     // Arc: as ARC_FEED counts them, positive counterclockwise
  double feed = 0;   // Feed, Arc: per minute in the program's units
  double number = 0; // ToolChange: the tool; Spindle: rpm, 0 when stopped
  int line = 0;      // the block that commanded it
};

struct LinuxcncRunOptions {
  // The safety net against endless loops: blocks executed in all.
  std::size_t stepLimit = 10'000'000;
  // The tool table's radii by tool number, read by `G41/G42 D<tool>` (a
  // tool not given here is an error); `G41.1/G42.1 D<diameter>` needs none.
  std::map<int, double> toolRadii;
};

struct LinuxcncRun {
  std::vector<LinuxcncMove> moves;   // up to the end, or up to the error
  std::vector<std::string> messages; // (debug, ...) and (print, ...), formatted
  bool inches = false;               // G20 at the end
  std::size_t blocksExecuted = 0;
  std::optional<SimulationError> error; // the first error, if any
};

// Reads and runs a LinuxCNC program. Never throws for a bad program: the
// error is in the result.
LinuxcncRun runLinuxcncProgram(std::string_view text, const LinuxcncRunOptions& options = {});

// The moves as the virtual controller's path (for flattenPath): an arc of
// several turns becomes one full circle per extra turn, then the arc to its
// end, its Z spread over them by angle.
ExecutedPath executedPathOf(const LinuxcncRun& run);

} // namespace cncc::backends::sim
