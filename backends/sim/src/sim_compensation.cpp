#include "sim_compensation.h"

#include "sim_evaluator.h"

#include <fmt/format.h>

#include <cmath>

namespace cncc::backends::sim {

namespace {

bool isMotion(const ExecutedEvent& event) {
  return event.kind == ExecutedEvent::Kind::Rapid || event.kind == ExecutedEvent::Kind::Feed ||
         isArc(event);
}

Vector2 planeOf(const Point3& point) {
  return {point.x, point.y};
}

bool movesInPlane(const ExecutedEvent& event) {
  return isArc(event) || event.start.x != event.end.x || event.start.y != event.end.y;
}

PlaneElement elementOf(const ExecutedEvent& event) {
  PlaneElement element;
  element.arc = isArc(event);
  element.clockwise = event.kind == ExecutedEvent::Kind::ClockwiseArc;
  element.start = planeOf(event.start);
  element.end = planeOf(event.end);
  element.centre = planeOf(event.centre);
  return element;
}

[[noreturn]] void failAtLine(int line, const std::string& text, const std::string& message) {
  throw SimulationError(line, text, message);
}

} // namespace

bool isArc(const ExecutedEvent& event) {
  return event.kind == ExecutedEvent::Kind::ClockwiseArc ||
         event.kind == ExecutedEvent::Kind::CounterclockwiseArc;
}

void RadiusCompensation::start(bool left, double radius, const Block& block) {
  if (state_ == State::On || state_ == State::Cancelling) {
    if (left != left_ || radius != radius_) {
      failInBlock(block, fmt::format("changing {} or the radius while compensating is not "
                                     "simulated; cancel with {} first",
                                     dialect_.on, dialect_.off));
    }
    return;
  }
  left_ = left;
  radius_ = radius;
  offset_ = left ? radius : -radius;
  state_ = State::Starting;
}

void RadiusCompensation::cancel(const Block&) {
  if (state_ == State::Starting) {
    state_ = State::Off;
  } else if (state_ == State::On) {
    state_ = State::Cancelling;
  }
}

void RadiusCompensation::cornerArc(std::optional<Vector2> direction, const Block& block) {
  if (state_ != State::On || !held_ || held_->startUp) {
    failInBlock(block, fmt::format("G39 (corner arc) needs {} on and a compensated move in the "
                                   "plane before it",
                                   dialect_.on));
  }
  if (direction && length(*direction) == 0) {
    failInBlock(block, "G39 I0 J0: the direction after the corner is missing");
  }
  held_->cornerArc = true;
  held_->cornerDirection = direction;
}

// The held block to the offset normal to its end, the arc of G39 about its
// end point, and a line to where the offset `next` starts if the arc ends
// elsewhere (a G39 direction other than the next block's).
void RadiusCompensation::emitCornerArc(const PlaneElement& next, const ExecutedEvent& event) {
  Vector2 corner = held_->element.end;
  Vector2 incoming = endTangent(held_->element);
  Vector2 outgoing = startTangent(next);
  if (held_->cornerDirection) {
    outgoing = (1 / length(*held_->cornerDirection)) * *held_->cornerDirection;
  }
  Vector2 from = corner + offset_ * leftNormal(incoming);
  Vector2 nextStart = next.start + offset_ * leftNormal(startTangent(next));
  double turn = cross(incoming, outgoing);
  constexpr double tangent = 1e-9;
  if (offset_ * turn > tangent || (std::abs(turn) <= tangent && dot(incoming, outgoing) < 0)) {
    failAtLine(held_->line, held_->text,
               "G39 (corner arc) at an inside corner: the arc would overcut the corner");
  }
  emitHeld({from}, event);
  TransitionArc arc{from, corner + offset_ * leftNormal(outgoing), corner, offset_ > 0};
  emitTransitionArc(arc, event);
  if (length(nextStart - tool_) > 0) {
    emitLine(event, nextStart, toolZ_);
  }
}

void RadiusCompensation::add(const ExecutedEvent& event, const Block& block) {
  if (isMotion(event) && movesInPlane(event)) {
    movedInPlane_ = true;
    addInPlane(event, block);
    return;
  }
  if (held_) {
    waiting_.push_back(event); // runs at the corner, once it is known
    return;
  }
  path_.events.push_back(event);
}

void RadiusCompensation::addInPlane(const ExecutedEvent& event, const Block& block) {
  if (state_ == State::Off) {
    path_.events.push_back(event);
    return;
  }
  PlaneElement element = elementOf(event);
  if (state_ == State::Starting) {
    if (isArc(event)) {
      failInBlock(block, "cutter compensation starts on an arc: the start-up move after "
                         "G41/G42 must be a G00 or G01 in the plane");
    }
    held_ = HeldBlock{event, element, true, false, std::nullopt, block.line, block.text};
    tool_ = element.start;
    toolZ_ = event.start.z;
    state_ = State::On;
    return;
  }
  if (state_ == State::Cancelling) {
    if (isArc(event)) {
      failInBlock(block, "G40 cancels on an arc: the cancel move must be a G00 or G01");
    }
    if (held_->cornerArc) {
      failInBlock(block, "G39 (corner arc) before the cancel move is not simulated");
    }
    if (held_->startUp) {
      failInBlock(block, fmt::format("{} right after the start-up move is not simulated: the "
                                     "compensation never reached a block to offset",
                                     dialect_.off));
    }
    Vector2 end = held_->element.end + offset_ * leftNormal(endTangent(held_->element));
    emitHeld({end}, event);
    emitLine(event, element.end, event.end.z);
    held_.reset();
    state_ = State::Off;
    return;
  }
  bool cornerArcAtEnd = cornerArcPending_;
  cornerArcPending_ = false;
  if (held_->cornerArc) {
    emitCornerArc(element, event);
    held_ = HeldBlock{event, element, false, cornerArcAtEnd, std::nullopt, block.line, block.text};
    return;
  }
  std::vector<Vector2> corner;
  std::optional<TransitionArc> arc;
  bool typeAStartUp = held_->startUp && !dialect_.offsetEntry;
  if (!typeAStartUp && dialect_.transitionArcs) {
    arc = transitionArc(held_->element, element, offset_);
  }
  if (arc) {
    emitHeld({arc->start}, event);
    emitTransitionArc(*arc, event);
    held_ = HeldBlock{event, element, false, cornerArcAtEnd, std::nullopt, block.line, block.text};
    return;
  }
  if (typeAStartUp) {
    corner = {element.start + offset_ * leftNormal(startTangent(element))};
  } else if (std::optional<std::vector<Vector2>> points =
                 offsetCorner(held_->element, element, offset_)) {
    corner = std::move(*points);
  } else {
    failInBlock(block, fmt::format("the compensated paths of line {} and this block do not "
                                   "meet: the tool radius {:g} is too large for the corner",
                                   held_->line, radius_));
  }
  emitHeld(corner, event);
  held_ = HeldBlock{event, element, false, cornerArcAtEnd, std::nullopt, block.line, block.text};
}

void RadiusCompensation::emitHeld(const std::vector<Vector2>& corner, const ExecutedEvent& next) {
  if (held_->startUp) {
    emitLine(held_->event, corner.front(), held_->event.end.z);
  } else {
    emitOffsetBlock(corner.front());
  }
  flushWaiting();
  for (std::size_t index = 1; index < corner.size(); ++index) {
    emitLine(next, corner[index], toolZ_);
  }
}

void RadiusCompensation::emitLine(const ExecutedEvent& model, Vector2 to, double z) {
  if (to.x == tool_.x && to.y == tool_.y && z == toolZ_) {
    return; // a corner point the tool is already at
  }
  ExecutedEvent line = model;
  if (isArc(model)) {
    line.kind = ExecutedEvent::Kind::Feed;
  }
  line.start = {tool_.x, tool_.y, toolZ_};
  line.end = {to.x, to.y, z};
  path_.events.push_back(line);
  tool_ = to;
  toolZ_ = z;
}

void RadiusCompensation::emitOffsetBlock(Vector2 to) {
  const HeldBlock& held = *held_;
  const PlaneElement& element = held.element;
  if (!element.arc) {
    if (dot(to - tool_, element.end - element.start) < 0) {
      failAtLine(held.line, held.text,
                 fmt::format("the compensated move runs against the programmed one: the tool "
                             "radius {:g} overcuts here (interference)",
                             radius_));
    }
    emitLine(held.event, to, held.event.end.z);
    return;
  }
  double radius = offsetArcRadius(element, offset_);
  if (radius <= 1e-9) {
    failAtLine(held.line, held.text,
               fmt::format("the arc of radius {:g} is smaller than the tool radius {:g} on its "
                           "inside",
                           element.radius(), radius_));
  }
  double programmed = arcSweep(element.start, element.end, element.centre, element.clockwise);
  if (length(element.end - element.start) == 0) {
    programmed = 360;
  }
  double compensated = arcSweep(tool_, to, element.centre, element.clockwise);
  if (std::abs(compensated + 360 - programmed) < std::abs(compensated - programmed)) {
    compensated += 360;
  }
  if (std::abs(compensated - programmed) > 180) {
    failAtLine(held.line, held.text,
               fmt::format("the compensated arc turns the other way: the tool radius {:g} "
                           "overcuts here (interference)",
                           radius_));
  }
  emitCompensatedArc(to, compensated);
}

// The held arc from the tool's point to `to`, turning `sweep` degrees. Sweeps
// within `sweepTolerance` of 0 or 360 are a point or a full circle: their
// ends differ by rounding only, and an arc whose ends nearly meet would be
// read as a whole turn or none.
void RadiusCompensation::emitCompensatedArc(Vector2 to, double sweep) {
  constexpr double sweepTolerance = 1e-6; // degrees
  const ExecutedEvent& held = held_->event;
  double startZ = held.start.z;
  double endZ = held.end.z;
  if (sweep < sweepTolerance) {
    emitLine(held, to, endZ);
    return;
  }
  ExecutedEvent arc = held;
  if (sweep > 360 - sweepTolerance) {
    // A full circle first, then what the offset adds beyond it.
    double circleZ = sweep > 360 + sweepTolerance ? startZ + (endZ - startZ) * 360 / sweep : endZ;
    arc.start = {tool_.x, tool_.y, toolZ_};
    arc.end = {tool_.x, tool_.y, circleZ};
    path_.events.push_back(arc);
    toolZ_ = circleZ;
    if (sweep <= 360 + sweepTolerance) {
      tool_ = to;
      return;
    }
  }
  arc.start = {tool_.x, tool_.y, toolZ_};
  arc.end = {to.x, to.y, endZ};
  path_.events.push_back(arc);
  tool_ = to;
  toolZ_ = endZ;
}

// Round an outside corner at the feed of the block after it.
void RadiusCompensation::emitTransitionArc(const TransitionArc& arc, const ExecutedEvent& next) {
  if (length(arc.end - tool_) == 0) {
    return;
  }
  ExecutedEvent move = next;
  move.kind =
      arc.clockwise ? ExecutedEvent::Kind::ClockwiseArc : ExecutedEvent::Kind::CounterclockwiseArc;
  move.start = {tool_.x, tool_.y, toolZ_};
  move.end = {arc.end.x, arc.end.y, toolZ_};
  move.centre = {arc.centre.x, arc.centre.y, toolZ_};
  path_.events.push_back(move);
  tool_ = arc.end;
}

void RadiusCompensation::flushWaiting() {
  for (ExecutedEvent event : waiting_) {
    if (isMotion(event)) {
      event.start = {tool_.x, tool_.y, toolZ_};
      event.end.x = tool_.x;
      event.end.y = tool_.y;
      toolZ_ = event.end.z;
    }
    path_.events.push_back(event);
  }
  waiting_.clear();
}

void RadiusCompensation::endOfBlock(const Block& block) {
  bool moved = movedInPlane_;
  movedInPlane_ = false;
  if (cornerArcPending_) {
    failInBlock(block, fmt::format("G39 (corner arc) on this control goes on a compensated move "
                                   "in the plane, with {} on: the arc is at its end",
                                   dialect_.on));
  }
  if (state_ == State::Cancelling && !moved) {
    failInBlock(block, "G40 in a block without an X or Y move while compensating is not "
                       "simulated: write G40 on the lead-out move");
  }
  if (!held_ || moved) {
    blocksWithoutPlaneMotion_ = 0;
    return;
  }
  if (++blocksWithoutPlaneMotion_ >= 2) {
    failInBlock(block, fmt::format("two blocks in a row without an X or Y move while {} is on: "
                                   "how far the control looks ahead differs, so the path is not "
                                   "simulated",
                                   dialect_.on));
  }
}

void RadiusCompensation::finish(const Block& block) const {
  if (state_ == State::On || state_ == State::Cancelling) {
    failInBlock(block, fmt::format("the program ends with cutter compensation on: cancel it with "
                                   "{} on a move",
                                   dialect_.off));
  }
}

} // namespace cncc::backends::sim
