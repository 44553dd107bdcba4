// The machine events the interpreter records for an effect op, an arc
// block and a setting (interpreter.h).
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

MachineEvent climbEvent(const std::array<double, 3>& from, double z) {
  MachineEvent event;
  event.kind = MachineEvent::Kind::Rapid;
  event.x = from[0];
  event.y = from[1];
  event.z = z;
  event.alongZ = true;
  return event;
}

MachineEvent effectEvent(const Instruction& instruction, const std::array<double, 4>& operands) {
  MachineEvent event;
  switch (instruction.opcode) {
  case Opcode::Rapid:
  case Opcode::Feed:
    event.kind =
        instruction.opcode == Opcode::Rapid ? MachineEvent::Kind::Rapid : MachineEvent::Kind::Feed;
    event.x = operands[0];
    event.y = operands[1];
    event.z = operands[2];
    event.feed = instruction.opcode == Opcode::Feed ? operands[3] : 0;
    return event;
  case Opcode::Spindle:
    event.kind = MachineEvent::Kind::Spindle;
    event.number = operands[0];
    return event;
  case Opcode::Tool:
    event.kind = MachineEvent::Kind::Tool;
    event.number = instruction.number;
    event.diameter = operands[0];
    event.offsetRegister = instruction.index;
    return event;
  case Opcode::Origin:
  case Opcode::Coolant:
  case Opcode::Contouring:
  case Opcode::Home:
  case Opcode::Compensation:
    return settingEvent(instruction.opcode, instruction.number, instruction.index);
  case Opcode::CutBegin:
    event.kind = MachineEvent::Kind::CutBegin;
    event.number = instruction.index;
    return event;
  case Opcode::CornerArc:
    event.kind = MachineEvent::Kind::CornerArc;
    event.x = operands[0];
    event.y = operands[1];
    return event;
  case Opcode::PassBegin:
    event.kind = MachineEvent::Kind::Comment;
    event.text = passDepthComment(operands[0]);
    return event;
  default:
    event.kind = MachineEvent::Kind::Comment;
    event.text = instruction.text;
    return event;
  }
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
