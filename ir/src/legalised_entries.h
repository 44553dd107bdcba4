// The curve table entry each lap has once the legalisations that give laps
// other entries have run: chords or samples of constants a controller counts in steps
// (choose-controller-steps), steps whose counts at the compiled values are
// past a region's limit cut at points chosen on the host
// (bound-controller-steps), and steps of a cut the host computes chosen as
// its chords (bound-controller-steps too); and a lap of a cut the host
// computes split at its arcs into laps of its pieces (split-arc-laps). The
// interpreter runs laps with these, so the IR before those passes runs the
// path after them. A lap of a cut the host computes whose curve reads the
// variable of a loop around it is measured at the variable's value in the
// trip being run, as after unroll-host-control writes the trips out.
#pragma once

#include "cncc/ir/ir.h"

#include "lap_cuts.h"

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <vector>

namespace cncc::ir {

class LegalisedEntries {
public:
  // The value a loop's variable has in the trip being run.
  using CurrentValue = std::function<double(ValueId)>;

  LegalisedEntries(const Function& function, CurrentValue current)
      : function_(function), current_(std::move(current)) {}

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
  // The lap's cut, and where the host computes it the loop variables its
  // curve reads (found once a lap).
  struct LapFacts {
    std::uint32_t cut = 0;
    std::vector<std::uint32_t> loopVariables;
  };
  const LapFacts& factsOf(const Instruction& lap);
  // The values of those variables in the trip being run.
  LoopTrip tripOf(const LapFacts& facts) const;
  // `cache`'s value for the trip, made by `make` when not there; a lap's
  // trips are kept up to a bound, then forgotten.
  template <class Value, class Make>
  const Value& remembered(std::map<LoopTrip, Value>& cache, const LoopTrip& trip, const Make& make);

  const Function& function_;
  CurrentValue current_;
  // Found once for the function: the steps of every entry at once.
  std::optional<std::map<std::uint32_t, CurveTableEntry>> stepped_;
  // Each entry's cut (its first lap's).
  std::optional<std::map<std::uint32_t, std::uint32_t>> cuts_;
  std::map<const Instruction*, LapFacts> facts_;
  std::map<const Instruction*, std::map<LoopTrip, std::optional<CurveTableEntry>>> bounded_;
  std::map<const Instruction*, std::map<LoopTrip, std::optional<SplitLap>>> split_;
};

} // namespace cncc::ir
