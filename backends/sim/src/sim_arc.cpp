// G02/G03 in the G17 plane: centre from I J (incremental from the start) or
// from R (negative R: the arc over 180 degrees), helical when Z moves.
#include "sim_machine.h"

#include <fmt/format.h>

#include <cmath>

namespace cncc::backends::sim {

namespace {

// The centre of the arc of radius |radius| from `start` to `end`; R > 0 takes
// the arc of at most 180 degrees.
Point3 centreFromRadius(const Block& block, Point3 start, Point3 end, double radius, bool clockwise,
                        double tolerance) {
  double dx = end.x - start.x;
  double dy = end.y - start.y;
  double chord = std::hypot(dx, dy);
  if (chord == 0) {
    failInBlock(block, "an R arc cannot end where it starts; a full circle needs I and J");
  }
  double half = chord / 2;
  double magnitude = std::abs(radius);
  if (half - magnitude > tolerance) {
    failInBlock(block, fmt::format("R{} is shorter than half the chord ({})", radius, half));
  }
  double height = magnitude > half ? std::sqrt(magnitude * magnitude - half * half) : 0;
  // The centre lies left of the chord for a short counterclockwise arc.
  bool left = !clockwise;
  if (radius < 0) {
    left = !left;
  }
  double side = left ? 1 : -1;
  Point3 centre;
  centre.x = (start.x + end.x) / 2 - side * height * dy / chord;
  centre.y = (start.y + end.y) / 2 + side * height * dx / chord;
  centre.z = start.z;
  return centre;
}

} // namespace

void Machine::moveArc(const Block& block, int motion, Point3 target,
                      const std::map<char, double>& axes) {
  if (!modal_.feed) {
    failInBlock(block, fmt::format("G0{} without a feed: no F has been commanded", motion));
  }
  if (axes.count('K') > 0) {
    failInBlock(block, "K is not a centre word in the G17 plane");
  }
  bool centreWords = axes.count('I') + axes.count('J') > 0;
  bool radiusWord = axes.count('R') > 0;
  if (centreWords == radiusWord) {
    failInBlock(block, centreWords ? "an arc takes I J or R, not both"
                                   : fmt::format("G0{} without I, J or R", motion));
  }
  bool clockwise = motion == 2;
  Point3 start = modal_.position;
  Point3 centre;
  if (radiusWord) {
    centre = centreFromRadius(block, start, target, roundToIncrement(axes.at('R')), clockwise,
                              profile_.arcRadiusTolerance);
  } else {
    auto offset = [&](char letter) {
      auto found = axes.find(letter);
      return found == axes.end() ? 0.0 : roundToIncrement(found->second);
    };
    double offsetX = offset('I');
    double offsetY = offset('J');
    rotateVector(offsetX, offsetY); // I and J turn with G68
    centre = {start.x + offsetX, start.y + offsetY, start.z};
  }
  double startRadius = std::hypot(start.x - centre.x, start.y - centre.y);
  double endRadius = std::hypot(target.x - centre.x, target.y - centre.y);
  if (startRadius < increment() / 2) {
    failInBlock(block, "the arc's centre is its start point");
  }
  double tolerance =
      modal_.inches ? profile_.arcRadiusTolerance / 25.4 : profile_.arcRadiusTolerance;
  if (std::abs(startRadius - endRadius) > tolerance) {
    failInBlock(block, fmt::format("the end point is {:.4f} from the centre, the start {:.4f}: "
                                   "more than the {} the controller allows",
                                   endRadius, startRadius, tolerance));
  }
  output({clockwise ? ExecutedEvent::Kind::ClockwiseArc : ExecutedEvent::Kind::CounterclockwiseArc,
          start, target, centre, *modal_.feed, 0, block.line},
         block);
  modal_.position = target;
}

} // namespace cncc::backends::sim
