// The curve table entry each lap has once the legalisations that give laps
// other entries have run: chords or samples of constants a controller counts in steps
// (choose-controller-steps), steps whose counts at the compiled values are
// past a region's limit cut at points chosen on the host
// (bound-controller-steps), and steps of a cut the host computes chosen as
// its chords (bound-controller-steps too); and a lap of a cut the host
// computes split at its arcs into laps of its pieces (split-arc-laps). The
// interpreter runs laps with these, so the IR before those passes runs the
// path after them.
#pragma once

#include "cncc/ir/ir.h"

#include "lap_cuts.h"

#include <cstdint>
#include <map>
#include <optional>

namespace cncc::ir {

class LegalisedEntries {
public:
  explicit LegalisedEntries(const Function& function) : function_(function) {}

  // The lap's entry as the legalisations leave it (its own where they keep
  // it). Throws InterpreterError where the lap's curve cannot be read.
  const CurveTableEntry& of(const Instruction& lap);

  // A lap split-arc-laps splits: each part's lap (of the lap's regions) and
  // its entry.
  struct SplitLap {
    std::vector<LapPart> parts;
    std::vector<Instruction> laps;
  };
  // The lap's parts, or null where it is not split. Throws InterpreterError
  // (an arc of too many turns).
  const SplitLap* splitOf(const Instruction& lap);

private:
  std::uint32_t cutOf(const Instruction& lap);

  const Function& function_;
  // Found once for the function: the steps of every entry at once.
  std::optional<std::map<std::uint32_t, CurveTableEntry>> stepped_;
  // Each entry's cut (its first lap's).
  std::optional<std::map<std::uint32_t, std::uint32_t>> cuts_;
  std::map<const Instruction*, std::optional<CurveTableEntry>> bounded_;
  std::map<const Instruction*, std::optional<SplitLap>> split_;
};

} // namespace cncc::ir
