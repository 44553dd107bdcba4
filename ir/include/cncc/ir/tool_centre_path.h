// Where the tool's centre goes when the program has the controller offset
// it (the `compensation` op, G41/G42 D..): the programmed moves between a
// compensation on and the linear move after its `compensation off`, run as
// a Fanuc control runs cutter radius compensation C with start-up and
// cancel of type A.
//
//   start-up: the first move after `compensation left|right` is a line from
//             the uncompensated position to the start of the offset path;
//   offset:   the moves after it, lines and arcs in one plane, offset by the
//             register's radius (geom::offsetOfPieces: an arc about a convex
//             corner, the offsets cut back to their crossing at a concave one);
//   corner:   a `corner.arc` (G39) between two offset moves goes round
//             their corner on that arc, as the offset does at a convex
//             corner;
//   cancel:   the first move after `compensation off` is a line from the end
//             of the offset path to its uncompensated end point.
#pragma once

#include "cncc/ir/tool_path.h"

namespace cncc::ir {

// The path with every compensated stretch replaced by the tool centre's
// moves; a path without compensation is returned as it is. Throws
// InterpreterError (interpreter.h), as a control alarms, for a compensated
// stretch it cannot run: a move out of the plane, a start-up or cancel that
// is not a line, compensation still on at the end, an offset that does not
// exist (a tool too large for an arc or a corner).
ToolPath toolCentrePath(const ToolPath& programmed);

} // namespace cncc::ir
