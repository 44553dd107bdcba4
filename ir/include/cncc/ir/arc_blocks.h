// How many move.arc blocks an arc of a known turn is printed in: a whole
// number k of turns in k blocks, each ending exactly where it starts (a
// full circle, written with the start's values so no rounding makes it a
// sliver); any other turn in the fewest blocks of at most 2 pi - 0.01 each
// (a block close to a full turn would end too near its start to say
// which). The lowering counts an arc of constants so, and the host's
// legalisation an arc whose turn the part's parameters set (split-arc-laps).
#pragma once

#include <numbers>
#include <string>

namespace cncc::ir {

inline constexpr double fullArcTurn = 2 * std::numbers::pi;
// The most a block short of a full turn turns (radians).
inline constexpr double largestPartialArcBlock = fullArcTurn - 0.01;
// More blocks than this for one arc: the program would be absurd.
inline constexpr double maximumArcBlocks = 100'000;

struct ArcBlockCount {
  double blocks = 0;
  bool wholeTurns = false;
  double turns = 0; // |sweep| / 2 pi, for a diagnostic past maximumArcBlocks
};

// The blocks of an arc that turns by `sweep` radians (either sign).
ArcBlockCount arcBlockCount(double sweep);
// The error for a count past maximumArcBlocks.
std::string arcTurnsPastTheLimit(const ArcBlockCount& count);

} // namespace cncc::ir
