// The path LinuxCNC's standalone interpreter reports: `rs274 -g FILE` prints
// one canonical machining call per line,
//
//      22 N..... STRAIGHT_FEED(3.0000, 135.0000, -1.0000, 0.0000, 0.0000, 0.0000)
//
// and this reads the moves back: STRAIGHT_TRAVERSE and STRAIGHT_FEED (X, Y,
// Z first), SET_FEED_RATE, and ARC_FEED in the XY plane (end X and Y, centre
// X and Y, turns: positive counterclockwise, end Z), which becomes chords
// within `arcChordError` of the arc. rs274 prints 4 decimals in the
// program's units. Other calls are skipped; NURBS_FEED, which rs274 prints
// without its control points, and malformed moves throw ExecutionMismatch.
#pragma once

#include "cncc/backends/executed_path.h"

#include <string_view>

namespace cncc::backends {

// rs274's interpreter starts at the origin: `start` is (0, 0, 0). No move
// has a cut (the canonical calls do not say). Throws PathTooLargeToMeasure
// before the path has more than `maximumMoves` moves.
ExecutedPath readLinuxcncCanon(std::string_view canon, double arcChordError = 1e-5,
                               double maximumMoves = maximumMeasuredPoints);

} // namespace cncc::backends
