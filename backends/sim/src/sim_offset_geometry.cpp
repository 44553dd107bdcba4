#include "cncc/backends/sim_offset_geometry.h"

#include <cmath>
#include <numbers>

namespace cncc::backends::sim {

namespace {

// Directions closer than this (sine of the angle) are taken as tangent.
constexpr double tangentTolerance = 1e-9;

// An offset block extended without end: a line through `point` along
// `direction`, or a circle.
struct OffsetCurve {
  bool circle = false;
  Vector2 point;     // line
  Vector2 direction; // line, unit
  Vector2 centre;    // circle
  double radius = 0; // circle
};

OffsetCurve offsetCurve(const PlaneElement& element, double offset) {
  OffsetCurve curve;
  if (element.arc) {
    curve.circle = true;
    curve.centre = element.centre;
    curve.radius = offsetArcRadius(element, offset);
    return curve;
  }
  curve.direction = startTangent(element);
  curve.point = element.start + offset * leftNormal(curve.direction);
  return curve;
}

std::vector<Vector2> intersectLines(const OffsetCurve& a, const OffsetCurve& b) {
  double denominator = cross(a.direction, b.direction);
  if (std::abs(denominator) < tangentTolerance) {
    return {};
  }
  double along = cross(b.point - a.point, b.direction) / denominator;
  return {a.point + along * a.direction};
}

std::vector<Vector2> intersectLineCircle(const OffsetCurve& line, const OffsetCurve& circle) {
  Vector2 toCentre = circle.centre - line.point;
  double along = dot(toCentre, line.direction);
  Vector2 closest = line.point + along * line.direction;
  double distance = length(circle.centre - closest);
  if (distance > circle.radius * (1 + 1e-12)) {
    return {};
  }
  double half = std::sqrt(std::max(0.0, circle.radius * circle.radius - distance * distance));
  return {closest + half * line.direction, closest - half * line.direction};
}

std::vector<Vector2> intersectCircles(const OffsetCurve& a, const OffsetCurve& b) {
  Vector2 between = b.centre - a.centre;
  double distance = length(between);
  if (distance < 1e-12 || distance > (a.radius + b.radius) * (1 + 1e-12) ||
      distance < std::abs(a.radius - b.radius) * (1 - 1e-12)) {
    return {};
  }
  double along = (distance * distance + a.radius * a.radius - b.radius * b.radius) / (2 * distance);
  double half = std::sqrt(std::max(0.0, a.radius * a.radius - along * along));
  Vector2 unit = (1 / distance) * between;
  Vector2 foot = a.centre + along * unit;
  return {foot + half * leftNormal(unit), foot - half * leftNormal(unit)};
}

// The intersection of the two offset blocks nearest the programmed corner.
std::optional<Vector2> nearestIntersection(const PlaneElement& before, const PlaneElement& after,
                                           double offset) {
  OffsetCurve a = offsetCurve(before, offset);
  OffsetCurve b = offsetCurve(after, offset);
  std::vector<Vector2> candidates;
  if (!a.circle && !b.circle) {
    candidates = intersectLines(a, b);
  } else if (a.circle && b.circle) {
    candidates = intersectCircles(a, b);
  } else {
    candidates = a.circle ? intersectLineCircle(b, a) : intersectLineCircle(a, b);
  }
  std::optional<Vector2> nearest;
  for (Vector2 candidate : candidates) {
    if (!nearest || length(candidate - before.end) < length(*nearest - before.end)) {
      nearest = candidate;
    }
  }
  return nearest;
}

} // namespace

double dot(Vector2 a, Vector2 b) {
  return a.x * b.x + a.y * b.y;
}

double cross(Vector2 a, Vector2 b) {
  return a.x * b.y - a.y * b.x;
}

double length(Vector2 a) {
  return std::hypot(a.x, a.y);
}

Vector2 leftNormal(Vector2 a) {
  return {-a.y, a.x};
}

namespace {

Vector2 unit(Vector2 a) {
  double size = length(a);
  return size > 0 ? (1 / size) * a : Vector2{};
}

Vector2 arcTangent(const PlaneElement& element, Vector2 point) {
  Vector2 counterclockwise = unit(leftNormal(point - element.centre));
  return element.clockwise ? -1.0 * counterclockwise : counterclockwise;
}

} // namespace

Vector2 startTangent(const PlaneElement& element) {
  return element.arc ? arcTangent(element, element.start) : unit(element.end - element.start);
}

Vector2 endTangent(const PlaneElement& element) {
  return element.arc ? arcTangent(element, element.end) : unit(element.end - element.start);
}

double offsetArcRadius(const PlaneElement& element, double offset) {
  return element.clockwise ? element.radius() + offset : element.radius() - offset;
}

std::optional<std::vector<Vector2>> offsetCorner(const PlaneElement& before,
                                                 const PlaneElement& after, double offset) {
  Vector2 corner = before.end;
  Vector2 incoming = endTangent(before);
  Vector2 outgoing = startTangent(after);
  Vector2 endOfBefore = corner + offset * leftNormal(incoming);
  Vector2 startOfAfter = corner + offset * leftNormal(outgoing);
  double turn = cross(incoming, outgoing);
  double along = dot(incoming, outgoing);
  if (std::abs(turn) <= tangentTolerance && along > 0) {
    return std::vector<Vector2>{endOfBefore}; // tangent: the offsets meet
  }
  bool inner = offset * turn > 0;
  if (inner || (along >= 0 && std::abs(turn) > tangentTolerance)) {
    std::optional<Vector2> meeting = nearestIntersection(before, after, offset);
    if (!meeting) {
      return std::nullopt;
    }
    return std::vector<Vector2>{*meeting};
  }
  // An outer corner sharper than 90 degrees, or a reversal.
  double distance = std::abs(offset);
  std::vector<Vector2> points;
  if (before.arc) {
    points.push_back(endOfBefore);
  }
  points.push_back(endOfBefore + distance * incoming);
  points.push_back(startOfAfter - distance * outgoing);
  if (after.arc) {
    points.push_back(startOfAfter);
  }
  return points;
}

std::optional<TransitionArc> transitionArc(const PlaneElement& before, const PlaneElement& after,
                                           double offset) {
  Vector2 corner = before.end;
  Vector2 incoming = endTangent(before);
  Vector2 outgoing = startTangent(after);
  double turn = cross(incoming, outgoing);
  bool parallel = std::abs(turn) <= tangentTolerance;
  bool along = dot(incoming, outgoing) > 0;
  if ((parallel && along) || (!parallel && offset * turn > 0)) {
    return std::nullopt;
  }
  // Left of the path the tool turns right round the corner (or reverses): clockwise.
  return TransitionArc{corner + offset * leftNormal(incoming),
                       corner + offset * leftNormal(outgoing), corner, offset > 0};
}

double arcSweep(Vector2 start, Vector2 end, Vector2 centre, bool clockwise) {
  double from = std::atan2(start.y - centre.y, start.x - centre.x);
  double to = std::atan2(end.y - centre.y, end.x - centre.x);
  double sweep = (clockwise ? from - to : to - from) * 180.0 / std::numbers::pi;
  while (sweep < 0) {
    sweep += 360.0;
  }
  while (sweep >= 360.0) {
    sweep -= 360.0;
  }
  return sweep;
}

} // namespace cncc::backends::sim
