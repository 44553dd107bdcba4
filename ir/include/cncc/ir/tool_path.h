// What a part makes the machine do, in order: the output of the IR
// interpreter and the JIT, and the input of the numeric backends.
#pragma once

#include "cncc/frontend/source_span.h"
#include "cncc/ir/sweep_pass.h"

#include <cstdint>
#include <string>
#include <vector>

namespace cncc::ir {

struct MachineEvent {
  // Origin, Coolant and Contouring are modal settings (ir_ops.def).
  enum class Kind {
    Rapid,
    Feed,
    Arc,
    Home, // Z to the machine's reference (move.home): off the work
    Spindle,
    Tool,
    Origin,
    Coolant,
    Contouring,
    Comment,
    CutBegin,
    Compensation,
    CornerArc // G39 at the corner the last move ended at, towards x, y (a direction)
  };
  Kind kind = Kind::Rapid;
  double x = 0, y = 0, z = 0; // Rapid, Feed, Arc: the target
  // Rapid: along Z alone (move.climb): x and y are where the tool was, which
  // a program need not know (after a tool change), so it writes Z only.
  bool alongZ = false;
  double feed = 0; // Feed, Arc: mm/min
  // Arc: the centre (absolute, in the XY plane) and the turning direction.
  // It starts where the move before it ended; ending there too, it is one
  // full turn. z goes linearly with the angle turned (a helix).
  double centreX = 0, centreY = 0;
  bool clockwise = false;
  // Spindle: rpm; Tool: the tool number; CutBegin: the cut index; Origin:
  // its code (54 .. 59, 54.1); Coolant: its CoolantMode; Contouring: the
  // tolerance (0: off); Compensation: the tool's offset from the programmed
  // path, left of the direction of travel positive (0: off).
  double number = 0;
  double diameter = 0;              // Tool
  std::uint32_t offsetRegister = 0; // Tool: length offset (0: default); Origin 54.1: P;
                                    // Compensation: the radius register (D)
  std::string text;                 // Comment
  // Feed: a chord of a move.spline, its table + 1 (0: none), and whether it
  // is the move's first (spline_move.h).
  std::uint32_t splineTable = 0;
  bool splineStart = false;
  frontend::SourceSpan span; // the instruction's (Instruction::span)
  SweepPass pass;            // the instruction's (Instruction::pass)
};

struct ToolPath {
  std::vector<MachineEvent> events;
};

// Whether the event moves the tool (a rapid, a feed move or an arc): where
// it ends is where the next move starts.
inline bool isMove(const MachineEvent& event) {
  return event.kind == MachineEvent::Kind::Rapid || event.kind == MachineEvent::Kind::Feed ||
         event.kind == MachineEvent::Kind::Arc;
}

// The angle an arc from (startX, startY) to (endX, endY) about the centre
// turns, in (0, 2 pi]: an arc that ends where it starts (within `closing`
// mm) is a full turn.
double arcSweep(double startX, double startY, const MachineEvent& arc, double closing = 1e-9);

// How many chords appendArcChords cuts `arc` from (startX, startY) into.
int arcChordCount(double startX, double startY, const MachineEvent& arc, double maximumSagitta);

// Appends feed moves along `arc` from (startX, startY, startZ) whose chords
// stay within `maximumSagitta` of it, the last one to its end.
void appendArcChords(double startX, double startY, double startZ, const MachineEvent& arc,
                     double maximumSagitta, std::vector<MachineEvent>& out);

// The path with every arc replaced by feed moves whose chords stay within
// `maximumSagitta` of it (the arc's radius goes evenly from its start's to
// its end's, as controllers move). At most `maximumChordsPerArc` per arc.
ToolPath flattenArcs(const ToolPath& path, double maximumSagitta);
// How many events flattenArcs(path, maximumSagitta) has, without making them.
double flattenedEventCount(const ToolPath& path, double maximumSagitta);
inline constexpr double maximumChordsPerArc = 4'000'000;

} // namespace cncc::ir
