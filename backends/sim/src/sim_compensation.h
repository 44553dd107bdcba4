// Cutter radius compensation C (G41/G42 with a D register) as Fanuc runs it
// with start-up and cancel type A: every executed event passes through here
// on its way to the path. While compensation is on, a block in the plane is
// held until the next one is known, because where its offset ends depends on
// the corner it makes with the next (sim_offset_geometry.h). Moves without X
// or Y motion between them (a plunge, M codes) run at the corner; more than
// one such block in a row is refused, as the controls' look-ahead differs.
//
//   start-up: the first G00/G01 in the plane after G41/G42 goes from the
//             uncompensated position to its end point offset normal to the
//             next block's start;
//   cancel:   the G00/G01 in the plane with G40 starts where the last offset
//             block ends (offset normal to its end) and goes to its
//             uncompensated end point.
#pragma once

#include "cncc/backends/virtual_controller.h"

#include "cncc/backends/sim_offset_geometry.h"

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace cncc::backends::sim {

// What differs between the controls that run it: the words in messages,
// and how an outside corner is gone round.
struct CompensationDialect {
  std::string on = "G41/G42";
  std::string off = "G40";
  // The Heidenhain TNC's arc about every outside corner (transitionArc)
  // rather than Fanuc's type A.
  bool transitionArcs = false;
  // LinuxCNC's start-up (as rs274 runs it): the entry move goes from where
  // the tool is to where its own offset meets the next move's, the corner
  // between them gone round as any other, rather than Fanuc's type A.
  bool offsetEntry = false;
};

class RadiusCompensation {
public:
  explicit RadiusCompensation(ExecutedPath& path, CompensationDialect dialect = {})
      : path_(path), dialect_(std::move(dialect)) {}

  // G41 (`left`) or G42 with the radius of the D register: a negative radius
  // puts the tool on the other side, as the controls do.
  void start(bool left, double radius, const Block& block);
  // G40.
  void cancel(const Block& block);
  // G39, corner circular interpolation: the corner at the end of the last
  // move in the plane is gone round on an arc of the radius about it, from
  // the offset normal to that move's end to the offset normal to
  // `direction` (Fanuc's `G39 I.. J..`), or to the next move's start when
  // there is none. Refused at an inside corner (the controls overcut there).
  void cornerArc(std::optional<Vector2> direction, const Block& block);
  // Mitsubishi's G39 on a move block: the corner at the end of this block's
  // move in the plane.
  void cornerArcAfterThisBlock() { cornerArcPending_ = true; }
  bool isOn() const { return state_ != State::Off; }
  // 40, 41 or 42, as #4007 reads it.
  int modalCode() const {
    return state_ == State::Off || state_ == State::Cancelling ? 40 : left_ ? 41 : 42;
  }

  // Every event the program executes, in order.
  void add(const ExecutedEvent& event, const Block& block);
  // After each block of address words.
  void endOfBlock(const Block& block);
  // M30/M02: compensation must have been cancelled.
  void finish(const Block& block) const;

private:
  enum class State { Off, Starting, On, Cancelling };

  struct HeldBlock {
    ExecutedEvent event;
    PlaneElement element;
    bool startUp = false;
    // G39 at its end, towards this direction if given (else the next block's).
    bool cornerArc = false;
    std::optional<Vector2> cornerDirection;
    int line = 0; // of its block, for alarms found once the next block is known
    std::string text;
  };

  void addInPlane(const ExecutedEvent& event, const Block& block);
  // Runs the held block to corner[0], the waiting events, then lines through
  // the rest of `corner` at the feed of `next`.
  void emitHeld(const std::vector<Vector2>& corner, const ExecutedEvent& next);
  void emitLine(const ExecutedEvent& model, Vector2 to, double z);
  void emitOffsetBlock(Vector2 to);
  void emitCompensatedArc(Vector2 to, double sweep);
  void emitTransitionArc(const TransitionArc& arc, const ExecutedEvent& next);
  void flushWaiting();
  void emitCornerArc(const PlaneElement& next, const ExecutedEvent& event);

  ExecutedPath& path_;
  CompensationDialect dialect_;
  State state_ = State::Off;
  double offset_ = 0; // signed: positive to the left of the path
  bool left_ = true;
  double radius_ = 0;
  std::optional<HeldBlock> held_;
  Vector2 tool_;                       // where the compensated path is
  double toolZ_ = 0;                   // its Z
  std::vector<ExecutedEvent> waiting_; // events after the held block
  int blocksWithoutPlaneMotion_ = 0;
  bool movedInPlane_ = false;     // in the current block
  bool cornerArcPending_ = false; // Mitsubishi's G39 in the current block
};

bool isArc(const ExecutedEvent& event);

} // namespace cncc::backends::sim
