#include "cncc/ir/tool_path.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace cncc::ir {

namespace {

constexpr double fullTurn = 2 * std::numbers::pi;

MachineEvent feedTo(double x, double y, double z, double feed) {
  MachineEvent event;
  event.kind = MachineEvent::Kind::Feed;
  event.x = x;
  event.y = y;
  event.z = z;
  event.feed = feed;
  return event;
}

struct Position {
  double x = 0, y = 0, z = 0;
};

} // namespace

int arcChordCount(double startX, double startY, const MachineEvent& arc, double maximumSagitta) {
  double startRadius = std::hypot(startX - arc.centreX, startY - arc.centreY);
  double endRadius = std::hypot(arc.x - arc.centreX, arc.y - arc.centreY);
  double radius = std::max(startRadius, endRadius);
  double sweep = arcSweep(startX, startY, arc);
  // A chord of angle a has sagitta r (1 - cos(a / 2)).
  double stepLimit =
      maximumSagitta >= radius ? std::numbers::pi / 2 : 2 * std::acos(1 - maximumSagitta / radius);
  double chords = std::ceil(sweep / stepLimit);
  // NaN (a coordinate that is no number) gives one chord, not a bad cast.
  return static_cast<int>(chords >= 1 ? std::min(chords, maximumChordsPerArc) : 1.0);
}

void appendArcChords(double startX, double startY, double startZ, const MachineEvent& arc,
                     double maximumSagitta, std::vector<MachineEvent>& out) {
  Position start{startX, startY, startZ};
  double startRadius = std::hypot(start.x - arc.centreX, start.y - arc.centreY);
  double endRadius = std::hypot(arc.x - arc.centreX, arc.y - arc.centreY);
  double sweep = arcSweep(start.x, start.y, arc);
  int count = arcChordCount(start.x, start.y, arc, maximumSagitta);
  double direction = arc.clockwise ? -1 : 1;
  double startAngle = std::atan2(start.y - arc.centreY, start.x - arc.centreX);
  for (int index = 1; index < count; ++index) {
    double fraction = static_cast<double>(index) / count;
    double r = startRadius + (endRadius - startRadius) * fraction;
    double angle = startAngle + direction * sweep * fraction;
    out.push_back(feedTo(arc.centreX + r * std::cos(angle), arc.centreY + r * std::sin(angle),
                         start.z + (arc.z - start.z) * fraction, arc.feed));
  }
  out.push_back(feedTo(arc.x, arc.y, arc.z, arc.feed));
}

double arcSweep(double startX, double startY, const MachineEvent& arc, double closing) {
  if (std::hypot(arc.x - startX, arc.y - startY) <= closing) {
    return fullTurn;
  }
  double startAngle = std::atan2(startY - arc.centreY, startX - arc.centreX);
  double endAngle = std::atan2(arc.y - arc.centreY, arc.x - arc.centreX);
  double sweep = arc.clockwise ? startAngle - endAngle : endAngle - startAngle;
  sweep = std::fmod(sweep, fullTurn);
  if (sweep <= 0) {
    sweep += fullTurn;
  }
  return sweep;
}

double flattenedEventCount(const ToolPath& path, double maximumSagitta) {
  double count = 0;
  Position position;
  for (const MachineEvent& event : path.events) {
    count += event.kind == MachineEvent::Kind::Arc
                 ? arcChordCount(position.x, position.y, event, maximumSagitta)
                 : 1;
    if (isMove(event)) {
      position = {event.x, event.y, event.z};
    }
  }
  return count;
}

ToolPath flattenArcs(const ToolPath& path, double maximumSagitta) {
  ToolPath out;
  out.events.reserve(path.events.size());
  Position position;
  for (const MachineEvent& event : path.events) {
    if (event.kind == MachineEvent::Kind::Arc) {
      appendArcChords(position.x, position.y, position.z, event, maximumSagitta, out.events);
    } else {
      out.events.push_back(event);
    }
    if (isMove(event)) {
      position = {event.x, event.y, event.z};
    }
  }
  return out;
}

} // namespace cncc::ir
