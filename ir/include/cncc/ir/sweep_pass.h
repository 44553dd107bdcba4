// Which pass of a cut's sweep (`depth=.. step=..`) an instruction, and the
// machine events and program lines made from it, belong to: where the
// passes are written out one after another, each instruction's own; where
// they are a loop (LoopRole::Passes), the trip the host runs (the
// interpreter's events), or the copy the unroller wrote. A controller's
// pass loop printed as a loop has lines of no fixed pass.
#pragma once

#include <cstdint>
#include <string>

namespace cncc::ir {

struct SweepPass {
  std::uint32_t number = 0; // 1 .. count; 0: not in a written-out pass
  std::uint32_t count = 0;  // the passes of the sweep (1: a cut without depth=)
  // The ramp lap (entry=ramp) that descends to this pass; on a pass loop
  // computed on the controller, with number 0.
  bool ramp = false;
  bool any() const { return number != 0 || ramp; }
  friend bool operator==(const SweepPass&, const SweepPass&) = default;
};

// The pass of an instruction run in trip `number` of a pass loop of `count`
// trips (LoopRole::Passes): its own where it has one, else that trip, a
// ramp lap's staying one.
SweepPass passInLoop(SweepPass own, std::uint32_t number, std::uint32_t count);

// Trip `trip` of a pass loop of `trips` trips (counted as doubles, as the
// loop runs; past 2^32 - 1, that).
SweepPass passTrip(double trip, double trips);

// What a program says where a pass at height z starts (`pass.begin`).
std::string passDepthComment(double z);

} // namespace cncc::ir
