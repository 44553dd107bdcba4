// Hand-made tool paths and cuts with deviations, lengths and times known in
// closed form, shared by the report tests.
#pragma once

#include "cncc/geom/line_arc_curves.h"
#include "cncc/ir/tool_path.h"
#include "cncc/lowering/lowering.h"

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

namespace cncc::report_test {

inline ir::MachineEvent rapid(double x, double y, double z) {
  ir::MachineEvent event;
  event.kind = ir::MachineEvent::Kind::Rapid;
  event.x = x, event.y = y, event.z = z;
  return event;
}

inline ir::MachineEvent feed(double x, double y, double z, double rate) {
  ir::MachineEvent event = rapid(x, y, z);
  event.kind = ir::MachineEvent::Kind::Feed;
  event.feed = rate;
  return event;
}

inline ir::MachineEvent cutBegin(std::size_t index) {
  ir::MachineEvent event;
  event.kind = ir::MachineEvent::Kind::CutBegin;
  event.number = static_cast<double>(index);
  return event;
}

// A quarter circle of radius 10 about the origin, from (10, 0) to (0, 10).
inline ir::CutGeometry quarterCircle(double tolerance) {
  ir::CutGeometry cut;
  cut.curve =
      std::make_shared<geom::ArcCurve>(Eigen::Vector2d(0, 0), 10.0, 0.0, std::numbers::pi / 2);
  cut.tolerance = tolerance;
  return cut;
}

// The sagitta of a chord over `angle` of a circle of radius 10: the largest
// distance between chord and arc.
inline double sagitta(double angle) {
  return 10.0 * (1.0 - std::cos(angle / 2.0));
}

// Cut 0 follows the quarter circle with two chords (45 degrees each) at
// feed 200 after a plunge of 6 at feed 100; cut 1 follows it with four chords
// (22.5 degrees each) at feed 400 after the same plunge. Each cut starts
// with a rapid over its start and ends with a 6 mm rapid retract.
inline ir::ToolPath twoCutPath() {
  const double r = 10.0;
  ir::ToolPath path;
  path.events.push_back(rapid(r, 0, 5));
  path.events.push_back(cutBegin(0));
  path.events.push_back(feed(r, 0, -1, 100));
  for (int k = 1; k <= 2; ++k) {
    double angle = k * std::numbers::pi / 4;
    path.events.push_back(feed(r * std::cos(angle), r * std::sin(angle), -1, 200));
  }
  path.events.push_back(rapid(0, r, 5));
  path.events.push_back(cutBegin(1));
  path.events.push_back(rapid(r, 0, 5));
  path.events.push_back(feed(r, 0, -1, 100));
  for (int k = 1; k <= 4; ++k) {
    double angle = k * std::numbers::pi / 8;
    path.events.push_back(feed(r * std::cos(angle), r * std::sin(angle), -1, 400));
  }
  path.events.push_back(rapid(0, r, 5));
  return path;
}

} // namespace cncc::report_test
