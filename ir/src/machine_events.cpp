// The machine events the interpreter records for an arc block and for a
// setting (interpreter.h).
#include "cncc/ir/interpreter.h"

#include <fmt/format.h>

#include <cmath>

namespace cncc::ir {

namespace {

// How far an arc's end may lie off its circle, in the part's units: what a
// controller allows by default (ControllerProfile::arcRadiusTolerance), so
// that arcs whose numbers are rounded to the printed grid run as printed.
constexpr double arcRadiusTolerance = 0.005;

} // namespace

MachineEvent arcMove(const std::array<double, 3>& start, ArcTurn turn, double x, double y, double z,
                     double i, double j, double feed) {
  MachineEvent event;
  event.kind = MachineEvent::Kind::Arc;
  event.x = x;
  event.y = y;
  event.z = z;
  event.centreX = start[0] + i;
  event.centreY = start[1] + j;
  event.feed = feed;
  event.clockwise = turn == ArcTurn::Clockwise;
  double startRadius = std::hypot(i, j);
  double endRadius = std::hypot(x - event.centreX, y - event.centreY);
  if (!(startRadius > arcRadiusTolerance) ||
      !(std::abs(endRadius - startRadius) <= arcRadiusTolerance)) {
    throw InterpreterError(fmt::format("an arc from ({:g}, {:g}) to ({:g}, {:g}) has radius {:g} "
                                       "at its start and {:g} at its end",
                                       start[0], start[1], x, y, startRadius, endRadius));
  }
  return event;
}

MachineEvent settingEvent(Opcode opcode, double number, std::uint32_t index) {
  MachineEvent event;
  event.number = number;
  switch (opcode) {
  case Opcode::Origin:
    event.kind = MachineEvent::Kind::Origin;
    event.offsetRegister = index;
    break;
  case Opcode::Coolant:
    event.kind = MachineEvent::Kind::Coolant;
    event.number = index;
    break;
  case Opcode::Home:
    event.kind = MachineEvent::Kind::Home;
    break;
  case Opcode::Compensation:
    event.kind = MachineEvent::Kind::Compensation;
    event.offsetRegister = index;
    break;
  default:
    event.kind = MachineEvent::Kind::Contouring;
    break;
  }
  return event;
}

} // namespace cncc::ir
