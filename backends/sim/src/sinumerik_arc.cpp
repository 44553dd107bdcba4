#include "sinumerik_arc.h"

#include "cncc/ir/tool_path.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace cncc::backends::sinumerik {

namespace {

// How far an arc's end may lie off its circle ($MN_..._CIRCLE_ERROR, mm).
constexpr double arcEndTolerance = 0.01;

// The centre of the arc of radius |radius| from `start` to `end`; a positive
// radius takes the arc of at most 180 degrees.
std::optional<Eigen::Vector2d> centreFromRadius(const ProgrammedArc& arc, std::string& problem) {
  Eigen::Vector2d start = arc.start.head<2>();
  Eigen::Vector2d chord = arc.end.head<2>() - start;
  double length = chord.norm();
  double radius = *arc.radius;
  if (length == 0) {
    problem = "a CR= arc cannot end where it starts; a full circle needs I and J";
    return std::nullopt;
  }
  double half = length / 2;
  if (half - std::abs(radius) > arcEndTolerance) {
    problem = fmt::format("CR={:g} is shorter than half the chord ({:g})", radius, half);
    return std::nullopt;
  }
  double height = std::abs(radius) > half ? std::sqrt(radius * radius - half * half) : 0;
  // The centre lies left of the chord for a short counterclockwise arc.
  bool left = arc.clockwise == (radius < 0);
  Eigen::Vector2d normal(-chord.y() / length, chord.x() / length);
  return start + chord / 2 + (left ? height : -height) * normal;
}

} // namespace

std::vector<Eigen::Vector3d> arcChordPoints(const ProgrammedArc& arc, double tolerance,
                                            std::size_t maximumPoints, std::string& problem) {
  if (arc.radius && (arc.centre[0] || arc.centre[1])) {
    problem = "a G2/G3 block takes I J or CR=, not both";
    return {};
  }
  if (!arc.radius && !arc.centre[0] && !arc.centre[1]) {
    problem = "a G2/G3 block without I, J or CR= (its centre)";
    return {};
  }
  if (arc.turns < 0 || arc.turns > 999) {
    problem = fmt::format("TURN={}: the turns are 0 to 999", arc.turns);
    return {};
  }
  Eigen::Vector2d centre;
  if (arc.radius) {
    std::optional<Eigen::Vector2d> found = centreFromRadius(arc, problem);
    if (!found) {
      return {};
    }
    centre = *found;
  } else {
    centre = arc.start.head<2>() +
             Eigen::Vector2d(arc.centre[0].value_or(0.0), arc.centre[1].value_or(0.0));
  }
  double startRadius = (arc.start.head<2>() - centre).norm();
  double endRadius = (arc.end.head<2>() - centre).norm();
  if (!(startRadius > 0) || !(std::abs(endRadius - startRadius) <= arcEndTolerance)) {
    problem = fmt::format("the arc's end is {:g} from its centre, its start {:g} (alarm 14040: "
                          "error in end point of circle)",
                          endRadius, startRadius);
    return {};
  }
  ir::MachineEvent last;
  last.kind = ir::MachineEvent::Kind::Arc;
  last.centreX = centre.x();
  last.centreY = centre.y();
  last.clockwise = arc.clockwise;
  last.x = arc.end.x();
  last.y = arc.end.y();
  // The Z of a helix spreads over every turn, the full ones first.
  double sweep = ir::arcSweep(arc.start.x(), arc.start.y(), last);
  double total = sweep + 2 * std::numbers::pi * arc.turns;
  double dropPerRadian = (arc.end.z() - arc.start.z()) / total;
  // A chord of angle a sags by r (1 - cos(a / 2)).
  double chordAngle =
      tolerance < startRadius ? 2 * std::acos(1 - tolerance / startRadius) : std::numbers::pi;
  double chordsNeeded = total / chordAngle + arc.turns + 1;
  if (!(chordsNeeded <= static_cast<double>(maximumPoints))) {
    problem = fmt::format("this arc needs {:.0f} chords within {:g}, more than the {} points "
                          "left of the path's limit",
                          chordsNeeded, tolerance, maximumPoints);
    return {};
  }
  std::vector<ir::MachineEvent> chords;
  Eigen::Vector3d from = arc.start;
  for (int turn = 0; turn < arc.turns; ++turn) {
    ir::MachineEvent circle = last;
    circle.x = from.x();
    circle.y = from.y();
    circle.z = from.z() + dropPerRadian * 2 * std::numbers::pi;
    ir::appendArcChords(from.x(), from.y(), from.z(), circle, tolerance, chords);
    from.z() = circle.z;
  }
  last.z = arc.end.z();
  ir::appendArcChords(from.x(), from.y(), from.z(), last, tolerance, chords);
  std::vector<Eigen::Vector3d> points;
  for (const ir::MachineEvent& chord : chords) {
    points.emplace_back(chord.x, chord.y, chord.z);
  }
  return points;
}

} // namespace cncc::backends::sinumerik
