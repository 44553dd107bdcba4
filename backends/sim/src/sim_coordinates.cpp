// The coordinate systems a program may set over the work offset: G52 local
// coordinates (a shift), G68 rotation in the XY plane and G15/G16 polar
// coordinates. modal_.position is always in work coordinates; a block's
// words are read in program coordinates and converted:
//
//   work = shift + centre + rotation(program - centre)
//
// with the rotation's centre given in the local system. With G16 (G90 only)
// X is a radius and Y an angle around the local origin.
#include "sim_machine.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace cncc::backends::sim {

namespace {

double radians(double degrees) {
  return degrees * std::numbers::pi / 180.0;
}

} // namespace

bool Machine::CoordinateSystem::isPlain() const {
  return shift.x == 0 && shift.y == 0 && shift.z == 0 && !rotated && !polar;
}

Point3 Machine::toWork(Point3 program) const {
  const CoordinateSystem& system = modal_.coordinates;
  Point3 work = program;
  if (system.rotated) {
    double angle = radians(system.angle);
    double dx = program.x - system.centreX;
    double dy = program.y - system.centreY;
    work.x = system.centreX + dx * std::cos(angle) - dy * std::sin(angle);
    work.y = system.centreY + dx * std::sin(angle) + dy * std::cos(angle);
  }
  work.x += system.shift.x;
  work.y += system.shift.y;
  work.z += system.shift.z;
  return work;
}

Point3 Machine::toProgram(Point3 work) const {
  const CoordinateSystem& system = modal_.coordinates;
  Point3 program{work.x - system.shift.x, work.y - system.shift.y, work.z - system.shift.z};
  if (system.rotated) {
    double angle = radians(-system.angle);
    double dx = program.x - system.centreX;
    double dy = program.y - system.centreY;
    program.x = system.centreX + dx * std::cos(angle) - dy * std::sin(angle);
    program.y = system.centreY + dx * std::sin(angle) + dy * std::cos(angle);
  }
  return program;
}

void Machine::rotateVector(double& x, double& y) const {
  if (!modal_.coordinates.rotated) {
    return;
  }
  double angle = radians(modal_.coordinates.angle);
  double rotatedX = x * std::cos(angle) - y * std::sin(angle);
  y = x * std::sin(angle) + y * std::cos(angle);
  x = rotatedX;
}

Point3 Machine::programmedTarget(const Block& block, const std::map<char, double>& axes) const {
  Point3 current = toProgram(modal_.position);
  Point3 target = current;
  double* coordinates[] = {&target.x, &target.y, &target.z};
  for (int axis = 0; axis < 3; ++axis) {
    char letter = "XYZ"[axis];
    auto found = axes.find(letter);
    if (found == axes.end()) {
      continue;
    }
    double amount = roundToIncrement(found->second);
    *coordinates[axis] = modal_.absolute ? amount : roundToIncrement(*coordinates[axis] + amount);
  }
  if (modal_.coordinates.polar && (axes.count('X') > 0 || axes.count('Y') > 0)) {
    if (!modal_.absolute) {
      failInBlock(block, "G16 polar coordinates with G91 are not simulated");
    }
    // What the block does not give comes from the current point, in polar form.
    double radius =
        axes.count('X') > 0 ? roundToIncrement(axes.at('X')) : std::hypot(current.x, current.y);
    double angle = axes.count('Y') > 0 ? axes.at('Y')
                                       : std::atan2(current.y, current.x) * 180 / std::numbers::pi;
    target.x = radius * std::cos(radians(angle));
    target.y = radius * std::sin(radians(angle));
  }
  Point3 work = toWork(target);
  return {roundToIncrement(work.x), roundToIncrement(work.y), roundToIncrement(work.z)};
}

// G52 X Y Z: the local origin in work coordinates; G52 X0 Y0 Z0 cancels.
void Machine::setLocalShift(const Block& block, const std::map<char, double>& axes) {
  if (!modal_.absolute) {
    failInBlock(block, "G52 with G91 is not simulated");
  }
  if (modal_.coordinates.rotated || modal_.coordinates.polar || compensation_.isOn()) {
    failInBlock(block, "G52 while G68, G16 or G41/G42 is on is not simulated");
  }
  Point3& shift = modal_.coordinates.shift;
  double* coordinates[] = {&shift.x, &shift.y, &shift.z};
  for (int axis = 0; axis < 3; ++axis) {
    char letter = "XYZ"[axis];
    auto found = axes.find(letter);
    if (found != axes.end()) {
      *coordinates[axis] = roundToIncrement(found->second);
    } else if (*coordinates[axis] != 0) {
      // Whether an axis left out keeps its shift differs between sources.
      failInBlock(block, fmt::format("G52 without {} while the local {} shift is {:g}: give {} "
                                     "too",
                                     letter, letter, *coordinates[axis], letter));
    }
  }
  for (const auto& [letter, value] : axes) {
    if (letter != 'X' && letter != 'Y' && letter != 'Z') {
      failInBlock(block, fmt::format("G52 takes X, Y and Z, not {}", letter));
    }
  }
}

// G68 X Y R: rotation by R degrees (counterclockwise) around X Y, given in
// the local system (the current point without X Y).
void Machine::setRotation(const Block& block, const std::map<char, double>& axes) {
  if (!modal_.absolute) {
    failInBlock(block, "G68 with G91 (an incremental angle) is not simulated");
  }
  if (axes.count('R') == 0) {
    failInBlock(block, "G68 without R: the default angle is a parameter");
  }
  if (compensation_.isOn() || modal_.cycle.code) {
    failInBlock(block, "G68 while G41/G42 or a drilling cycle is on is not simulated");
  }
  for (const auto& [letter, value] : axes) {
    if (letter != 'X' && letter != 'Y' && letter != 'R') {
      failInBlock(block, fmt::format("G68 takes X, Y and R in the G17 plane, not {}", letter));
    }
  }
  modal_.coordinates.rotated = false; // the centre is read in the unrotated system
  Point3 current = toProgram(modal_.position);
  modal_.coordinates.centreX = axes.count('X') > 0 ? roundToIncrement(axes.at('X')) : current.x;
  modal_.coordinates.centreY = axes.count('Y') > 0 ? roundToIncrement(axes.at('Y')) : current.y;
  modal_.coordinates.angle = axes.at('R');
  modal_.coordinates.rotated = true;
}

} // namespace cncc::backends::sim
