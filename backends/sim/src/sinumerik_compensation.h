// Tool radius compensation on the virtual Sinumerik: G41 (tool left of the
// path) and G42 (right) with the radius of the active cutting edge, G40 to
// cancel, G450 at outside corners. Each programmed line or arc in the XY
// plane is held until the next is known, because where its offset ends
// depends on the corner the two make; the geometry is the shared one of
// sim_offset_geometry.h.
//
//   approach (NORM): the first G0/G1 in the plane after G41/G42 runs from
//             the uncompensated position straight to the next block's start
//             offset normal to that block;
//   corners:  inside, the offset blocks meet where they cross; outside, the
//             tool goes round the programmed corner on a transition circle of
//             the tool radius (G450);
//   retract:  the G0/G1 in the plane with G40 starts where the last offset
//             block ends (offset normal to its end) and runs to its
//             uncompensated end point.
//
// Every block from the approach to the retract stays at one Z, with arcs
// given by their centre, without extra turns: what the compiler prints and
// all this models.
#pragma once

#include "cncc/backends/sim_offset_geometry.h"

#include <functional>
#include <optional>
#include <stdexcept>
#include <string>

namespace cncc::backends::sinumerik {

// A line or an arc at height `z`, programmed or as the tool's centre runs it.
struct PlaneMove {
  sim::PlaneElement element;
  double z = 0;
  double feed = 0;
  bool rapid = false;
  int line = 0;     // of its block
  int mainLine = 0; // of the main-program block (the call, inside a subprogram)
};

// What the control alarms with, at the block of `line`.
class CompensationError : public std::runtime_error {
public:
  CompensationError(int line, const std::string& message)
      : std::runtime_error(message), line_(line) {}
  int line() const { return line_; }

private:
  int line_;
};

class CutterCompensation {
public:
  // `sink` takes each move of the tool's centre in order.
  explicit CutterCompensation(std::function<void(const PlaneMove&)> sink)
      : sink_(std::move(sink)) {}

  // G41 (`left`) or G42 with the active edge's radius, from the next move in
  // the plane, in the block of `line`.
  void select(bool left, double radius, int line);
  // G40: the next move in the plane is the retract.
  void cancel();
  // From G41/G42 to the end of the retract every move in the plane passes
  // through add().
  bool engaged() const { return state_ != State::Off; }
  void add(const PlaneMove& move);
  // M30 at `line`: compensation must be off.
  void finish(int line) const;

private:
  enum class State { Off, Approaching, On, Retracting };

  // How the tool goes from one offset block to the next.
  struct Corner {
    sim::Vector2 end;                    // where the offset block before ends
    std::optional<PlaneMove> transition; // the G450 circle round an outside corner
  };

  Corner cornerBetween(const PlaneMove& before, const PlaneMove& after) const;
  void emitHeld(sim::Vector2 to);
  void emitLine(const PlaneMove& model, sim::Vector2 to);
  void emitArc(const PlaneMove& model, sim::Vector2 to, sim::Vector2 centre, bool clockwise);

  std::function<void(const PlaneMove&)> sink_;
  State state_ = State::Off;
  bool left_ = true;
  double radius_ = 0;
  double offset_ = 0; // signed: positive left of the path
  std::optional<PlaneMove> held_;
  bool heldIsApproach_ = false;
  sim::Vector2 tool_; // where the tool's centre is
};

} // namespace cncc::backends::sinumerik
