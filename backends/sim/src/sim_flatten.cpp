// The executed path as a polyline the deviation measurements can read.
#include "cncc/backends/virtual_controller.h"

namespace cncc::backends::sim {

ir::ToolPath executedToolPath(const ExecutedPath& path) {
  ir::ToolPath out;
  for (const ExecutedEvent& event : path.events) {
    ir::MachineEvent flat;
    switch (event.kind) {
    case ExecutedEvent::Kind::Rapid:
    case ExecutedEvent::Kind::Feed:
      flat.kind = event.kind == ExecutedEvent::Kind::Rapid ? ir::MachineEvent::Kind::Rapid
                                                           : ir::MachineEvent::Kind::Feed;
      flat.x = event.end.x;
      flat.y = event.end.y;
      flat.z = event.end.z;
      flat.feed = event.feed;
      out.events.push_back(flat);
      break;
    case ExecutedEvent::Kind::ClockwiseArc:
    case ExecutedEvent::Kind::CounterclockwiseArc:
      flat.kind = ir::MachineEvent::Kind::Arc;
      flat.x = event.end.x;
      flat.y = event.end.y;
      flat.z = event.end.z;
      flat.centreX = event.centre.x;
      flat.centreY = event.centre.y;
      flat.clockwise = event.kind == ExecutedEvent::Kind::ClockwiseArc;
      flat.feed = event.feed;
      out.events.push_back(flat);
      break;
    case ExecutedEvent::Kind::ToolChange:
      flat.kind = ir::MachineEvent::Kind::Tool;
      flat.number = event.number;
      out.events.push_back(flat);
      break;
    case ExecutedEvent::Kind::Spindle:
      flat.kind = ir::MachineEvent::Kind::Spindle;
      flat.number = event.number;
      out.events.push_back(flat);
      break;
    }
  }
  return out;
}

ir::ToolPath flattenPath(const ExecutedPath& path, double maximumSagitta) {
  return ir::flattenArcs(executedToolPath(path), maximumSagitta);
}

} // namespace cncc::backends::sim
