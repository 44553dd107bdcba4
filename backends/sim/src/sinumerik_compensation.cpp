#include "sinumerik_compensation.h"

#include <fmt/format.h>

#include <cmath>

namespace cncc::backends::sinumerik {

namespace {

using sim::Vector2;

// Directions closer than this (sine of the angle) are one direction.
constexpr double tangentTolerance = 1e-9;
// Sweeps this close to 0 or 360 degrees are a point or a full circle.
constexpr double sweepTolerance = 1e-6;

bool samePoint(Vector2 a, Vector2 b) {
  return a.x == b.x && a.y == b.y;
}

} // namespace

void CutterCompensation::select(bool left, double radius, int line) {
  if (state_ == State::On || state_ == State::Retracting) {
    if (left != left_ || radius != radius_) {
      throw CompensationError(line, "changing G41/G42 or the cutting edge while compensating "
                                    "is not modelled; cancel with G40 first");
    }
    return;
  }
  left_ = left;
  radius_ = radius;
  offset_ = left ? radius : -radius;
  state_ = State::Approaching;
}

void CutterCompensation::cancel() {
  if (state_ == State::Approaching) {
    state_ = State::Off;
  } else if (state_ == State::On) {
    state_ = State::Retracting;
  }
}

void CutterCompensation::add(const PlaneMove& move) {
  const sim::PlaneElement& element = move.element;
  if (state_ == State::Approaching) {
    if (element.arc) {
      throw CompensationError(move.line, "tool radius compensation approaches on an arc: the "
                                         "first move after G41/G42 must be a G0 or G1");
    }
    held_ = move;
    heldIsApproach_ = true;
    tool_ = element.start;
    state_ = State::On;
    return;
  }
  if (state_ == State::Retracting) {
    if (element.arc) {
      throw CompensationError(move.line, "G40 retracts on an arc: the move must be a G0 or G1");
    }
    if (heldIsApproach_) {
      throw CompensationError(move.line,
                              "G40 right after the approach is not modelled: no block was "
                              "compensated");
    }
    emitHeld(held_->element.end + offset_ * sim::leftNormal(sim::endTangent(held_->element)));
    emitLine(move, element.end);
    held_.reset();
    state_ = State::Off;
    return;
  }
  if (heldIsApproach_) {
    emitHeld(element.start + offset_ * sim::leftNormal(sim::startTangent(element)));
  } else {
    Corner corner = cornerBetween(*held_, move);
    emitHeld(corner.end);
    if (corner.transition) {
      emitArc(*corner.transition, corner.transition->element.end, corner.transition->element.centre,
              corner.transition->element.clockwise);
    }
  }
  held_ = move;
  heldIsApproach_ = false;
}

void CutterCompensation::finish(int line) const {
  if (state_ != State::Off) {
    throw CompensationError(line, "the program ends with tool radius compensation on: cancel it "
                                  "with G40 on a move");
  }
}

// Inside the corner the offsets meet where they cross (the Fanuc corner
// does the same); outside, G450 runs a circle of the tool radius about the
// programmed corner from one offset to the other.
CutterCompensation::Corner CutterCompensation::cornerBetween(const PlaneMove& before,
                                                             const PlaneMove& after) const {
  Vector2 corner = before.element.end;
  Vector2 incoming = sim::endTangent(before.element);
  Vector2 outgoing = sim::startTangent(after.element);
  Vector2 endOfBefore = corner + offset_ * sim::leftNormal(incoming);
  double turn = sim::cross(incoming, outgoing);
  bool tangent = std::abs(turn) <= tangentTolerance && sim::dot(incoming, outgoing) > 0;
  if (tangent) {
    return {endOfBefore, std::nullopt};
  }
  if (offset_ * turn > 0) { // inside
    std::optional<std::vector<Vector2>> meeting =
        sim::offsetCorner(before.element, after.element, offset_);
    if (!meeting || meeting->size() != 1) {
      throw CompensationError(after.line,
                              fmt::format("the compensated paths of line {} and this block do "
                                          "not meet: the tool radius {:g} is too large for the "
                                          "corner",
                                          before.line, radius_));
    }
    return {meeting->front(), std::nullopt};
  }
  PlaneMove transition = after;
  transition.element.arc = true;
  transition.element.start = endOfBefore;
  transition.element.end = corner + offset_ * sim::leftNormal(outgoing);
  transition.element.centre = corner;
  transition.element.clockwise = offset_ > 0; // the path turns right round a corner on its left
  return {endOfBefore, transition};
}

// Runs the held block from the tool's point to `to`, refusing what would
// cut into the part (interference).
void CutterCompensation::emitHeld(Vector2 to) {
  const PlaneMove& held = *held_;
  const sim::PlaneElement& element = held.element;
  if (heldIsApproach_ || !element.arc) {
    if (!heldIsApproach_ && sim::dot(to - tool_, element.end - element.start) < 0) {
      throw CompensationError(held.line,
                              fmt::format("the compensated move runs against the programmed "
                                          "one: the tool radius {:g} is too large here "
                                          "(contour violation)",
                                          radius_));
    }
    emitLine(held, to);
    return;
  }
  double radius = sim::offsetArcRadius(element, offset_);
  if (radius <= 1e-9) {
    throw CompensationError(held.line,
                            fmt::format("the arc of radius {:g} is smaller than the tool radius "
                                        "{:g} on its inside",
                                        element.radius(), radius_));
  }
  double programmed =
      samePoint(element.start, element.end)
          ? 360
          : sim::arcSweep(element.start, element.end, element.centre, element.clockwise);
  double compensated = sim::arcSweep(tool_, to, element.centre, element.clockwise);
  if (std::abs(compensated + 360 - programmed) < std::abs(compensated - programmed)) {
    compensated += 360;
  }
  if (std::abs(compensated - programmed) > 180) {
    throw CompensationError(held.line,
                            fmt::format("the compensated arc turns the other way: the tool "
                                        "radius {:g} is too large here (contour violation)",
                                        radius_));
  }
  if (compensated < sweepTolerance) {
    emitLine(held, to);
    return;
  }
  emitArc(held, to, element.centre, element.clockwise);
}

void CutterCompensation::emitLine(const PlaneMove& model, Vector2 to) {
  if (samePoint(to, tool_)) {
    return;
  }
  PlaneMove line = model;
  line.element = {false, false, tool_, to, {}};
  sink_(line);
  tool_ = to;
}

void CutterCompensation::emitArc(const PlaneMove& model, Vector2 to, Vector2 centre,
                                 bool clockwise) {
  PlaneMove arc = model;
  arc.element = {true, clockwise, tool_, to, centre};
  sink_(arc);
  tool_ = to;
}

} // namespace cncc::backends::sinumerik
