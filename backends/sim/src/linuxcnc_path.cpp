// LinuxCNC's moves as the virtual controller's path: arcs of several turns
// split into full circles and the arc to the end.
#include "cncc/backends/linuxcnc_controller.h"

#include <cmath>
#include <numbers>

namespace cncc::backends::sim {

namespace {

constexpr double fullTurn = 2 * std::numbers::pi;

// The sweep of the arc's last turn (0, 2 pi], in its own direction.
double lastTurnSweep(const LinuxcncMove& arc) {
  double from = std::atan2(arc.start.y - arc.centre.y, arc.start.x - arc.centre.x);
  double to = std::atan2(arc.end.y - arc.centre.y, arc.end.x - arc.centre.x);
  double sweep = arc.turns > 0 ? to - from : from - to;
  sweep = std::fmod(sweep, fullTurn);
  return sweep <= 1e-12 ? sweep + fullTurn : sweep;
}

void addArc(const LinuxcncMove& arc, ExecutedPath& path) {
  ExecutedEvent::Kind kind =
      arc.turns > 0 ? ExecutedEvent::Kind::CounterclockwiseArc : ExecutedEvent::Kind::ClockwiseArc;
  int extraTurns = std::abs(arc.turns) - 1;
  double last = lastTurnSweep(arc);
  double total = last + extraTurns * fullTurn;
  Point3 start = arc.start;
  for (int turn = 1; turn <= extraTurns; ++turn) {
    Point3 end = start;
    end.z = arc.start.z + (arc.end.z - arc.start.z) * (turn * fullTurn / total);
    Point3 centre{arc.centre.x, arc.centre.y, start.z};
    path.events.push_back({kind, start, end, centre, arc.feed, 0, arc.line});
    start = end;
  }
  path.events.push_back(
      {kind, start, arc.end, {arc.centre.x, arc.centre.y, start.z}, arc.feed, 0, arc.line});
}

} // namespace

ExecutedPath executedPathOf(const LinuxcncRun& run) {
  ExecutedPath path;
  path.inches = run.inches;
  for (const LinuxcncMove& move : run.moves) {
    switch (move.kind) {
    case LinuxcncMove::Kind::Traverse:
    case LinuxcncMove::Kind::Feed:
      path.events.push_back({move.kind == LinuxcncMove::Kind::Traverse ? ExecutedEvent::Kind::Rapid
                                                                       : ExecutedEvent::Kind::Feed,
                             move.start,
                             move.end,
                             {},
                             move.feed,
                             0,
                             move.line});
      break;
    case LinuxcncMove::Kind::Arc:
      addArc(move, path);
      break;
    case LinuxcncMove::Kind::ToolChange:
    case LinuxcncMove::Kind::Spindle:
      path.events.push_back({move.kind == LinuxcncMove::Kind::ToolChange
                                 ? ExecutedEvent::Kind::ToolChange
                                 : ExecutedEvent::Kind::Spindle,
                             move.start,
                             move.end,
                             {},
                             0,
                             move.number,
                             move.line});
      break;
    }
  }
  return path;
}

} // namespace cncc::backends::sim
