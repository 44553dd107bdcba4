// The cut each curve.lap belongs to (the cut.begin before it in the
// program's order), for the legalisations that decide by the cut's target:
// whether its controller computes the program's numbers or the host does.
#pragma once

#include "cncc/ir/curve_lap.h"
#include "cncc/ir/ir.h"

#include <cstdint>
#include <map>
#include <vector>

namespace cncc::ir {

struct LapOfCut {
  InstructionId lap = 0;
  std::uint32_t cut = 0; // or noCut
};

// Every curve.lap, by the index of its entry in the curve table.
std::map<std::uint32_t, std::vector<LapOfCut>> lapsByEntry(const Function& function);

// The function's cut `cut` where the host computes its numbers (no
// controller digits, CutGeometry::controllerDigits); null where a
// controller does, or for noCut.
const CutGeometry* hostComputedCut(const Function& function, std::uint32_t cut);

} // namespace cncc::ir
