// Which pass of a cut's sweep (`depth=.. step=..`) an instruction, and the
// machine events and program lines made from it, belong to, where the
// lowering writes the passes out one after another. Where the passes are a
// controller loop (LoopRole::Passes) the lines have no fixed pass.
#pragma once

#include <cstdint>

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

} // namespace cncc::ir
