// The executed path as a polyline the deviation measurements can read.
#include "cncc/backends/virtual_controller.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace cncc::backends::sim {

namespace {

// More chords than this for one arc would only come from a nonsense radius.
constexpr double maximumChordsPerArc = 4'000'000;

ir::MachineEvent feedTo(double x, double y, double z, double feed) {
  ir::MachineEvent event;
  event.kind = ir::MachineEvent::Kind::Feed;
  event.x = x;
  event.y = y;
  event.z = z;
  event.feed = feed;
  return event;
}

// The swept angle, in (0, 2 pi]: an arc that ends where it starts is a full
// circle.
double sweptAngle(const ExecutedEvent& arc) {
  double startAngle = std::atan2(arc.start.y - arc.centre.y, arc.start.x - arc.centre.x);
  double endAngle = std::atan2(arc.end.y - arc.centre.y, arc.end.x - arc.centre.x);
  double sweep = arc.kind == ExecutedEvent::Kind::CounterclockwiseArc ? endAngle - startAngle
                                                                      : startAngle - endAngle;
  constexpr double fullTurn = 2 * std::numbers::pi;
  sweep = std::fmod(sweep, fullTurn);
  if (sweep <= 0) {
    sweep += fullTurn;
  }
  return sweep;
}

void appendArc(const ExecutedEvent& arc, double maximumSagitta, ir::ToolPath& out) {
  double startRadius = std::hypot(arc.start.x - arc.centre.x, arc.start.y - arc.centre.y);
  double endRadius = std::hypot(arc.end.x - arc.centre.x, arc.end.y - arc.centre.y);
  double radius = std::max(startRadius, endRadius);
  double sweep = sweptAngle(arc);
  // A chord of angle a has sagitta r (1 - cos(a / 2)).
  double stepLimit =
      maximumSagitta >= radius ? std::numbers::pi / 2 : 2 * std::acos(1 - maximumSagitta / radius);
  double chords = std::clamp(std::ceil(sweep / stepLimit), 1.0, maximumChordsPerArc);
  int count = static_cast<int>(chords);
  double direction = arc.kind == ExecutedEvent::Kind::CounterclockwiseArc ? 1 : -1;
  double startAngle = std::atan2(arc.start.y - arc.centre.y, arc.start.x - arc.centre.x);
  for (int index = 1; index < count; ++index) {
    double fraction = static_cast<double>(index) / count;
    // Controllers move from the start radius to the end radius evenly.
    double r = startRadius + (endRadius - startRadius) * fraction;
    double angle = startAngle + direction * sweep * fraction;
    out.events.push_back(feedTo(arc.centre.x + r * std::cos(angle),
                                arc.centre.y + r * std::sin(angle),
                                arc.start.z + (arc.end.z - arc.start.z) * fraction, arc.feed));
  }
  out.events.push_back(feedTo(arc.end.x, arc.end.y, arc.end.z, arc.feed));
}

} // namespace

ir::ToolPath flattenPath(const ExecutedPath& path, double maximumSagitta) {
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
      appendArc(event, maximumSagitta, out);
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

} // namespace cncc::backends::sim
