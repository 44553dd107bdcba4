#include "cncc/ir/arc_blocks.h"

#include <fmt/format.h>

#include <cmath>

namespace cncc::ir {

ArcBlockCount arcBlockCount(double sweep) {
  double turns = std::abs(sweep) / fullArcTurn;
  double whole = std::round(turns);
  bool wholeTurns = whole >= 1 && std::abs(turns - whole) <= 1e-9 * turns;
  double blocks = wholeTurns ? whole : std::ceil(std::abs(sweep) / largestPartialArcBlock);
  return {blocks, wholeTurns, turns};
}

std::string arcTurnsPastTheLimit(const ArcBlockCount& count) {
  return fmt::format("this arc turns {:g} times; the limit is {:g} turns", count.turns,
                     maximumArcBlocks);
}

} // namespace cncc::ir
