// `unroll-host-control`: where the host computes the program (no cut has
// controller digits: gcode, sinumerik, jit), each `for` the lowering gave
// every target as the loop a controller runs is written out trip by trip at
// its bounds' compiled values, as the host's program is a list of moves:
// its variable a number in each trip, what the bounds read fixed; and each
// `if` whose branches cut is its branch taken at the compiled values, what
// the condition reads fixed (an if of the lowering's checks, such as an
// arc's alarm, stays: the program runs it). Each
// trip's cut is a cut of its own (the table renumbered in the program's
// order, as the lowering numbers the cuts of a loop it writes out), and a
// curve.lap whose curve reads the variable gets an entry of its own in each
// trip, without the lowering's geometry (the curve at the first trip): its
// regions, at the trip's number, are the curve, which
// split-arc-laps and bound-controller-steps then cut at the compiled
// values; an entry no lap names any more is dropped from the table (the
// curves renumbered in order). A loop within whose bounds read the variable is written out in
// the next round. Past maximumUnrolledTrips trips in all, an error at the
// loop naming the bound.
#include "cncc/ir/curve_lap.h"
#include "cncc/ir/sweep_pass.h"

#include "compiled_values.h"
#include "lap_cuts.h"
#include "passes/rewriter.h"

#include <fmt/format.h>

#include <map>
#include <set>
#include <vector>

namespace cncc::ir {

namespace {

// The trips written out in all: the lowering's bound on the trips of the
// loops it writes out.
constexpr std::size_t maximumUnrolledTrips = 100'000;

bool hostComputesTheProgram(const Function& function) {
  if (function.cuts.empty()) {
    return false;
  }
  for (std::uint32_t cut = 0; cut < function.cuts.size(); ++cut) {
    if (hostComputedCut(function, cut) == nullptr) {
      return false;
    }
  }
  return true;
}

// The parameters `value` reads (through pure arithmetic).
void collectParameters(const Function& function, ValueId value, std::set<std::uint32_t>& into) {
  std::set<std::uint32_t> read = valueInputs(function, {value}).parameters;
  into.insert(read.begin(), read.end());
}

class HostLoopUnroller : public passes::Rewriter {
public:
  HostLoopUnroller(const Function& source, std::size_t& tripsSoFar)
      : Rewriter(source), tripsSoFar_(tripsSoFar) {}

  // The parameters the bounds of the loops written out and the conditions
  // of the ifs chosen read.
  const std::set<std::uint32_t>& boundParameters() const { return boundParameters_; }

private:
  void visit(const Instruction& instruction) override {
    if (instruction.opcode == Opcode::Loop &&
        static_cast<LoopRole>(instruction.index) == LoopRole::Statement) {
      if (std::optional<Trips> trips = tripsOf(instruction)) {
        unroll(instruction, *trips);
        return;
      }
    }
    if (instruction.opcode == Opcode::If && branchesCut(instruction)) {
      if (std::optional<double> condition = compiled_(instruction.operands[0])) {
        collectParameters(source_, instruction.operands[0], boundParameters_);
        rewriteRegion(instruction.regions[*condition != 0 ? 0 : 1]);
        markChanged();
        return;
      }
    }
    if (instruction.opcode == Opcode::CutBegin && !unrolling_.empty()) {
      copyCutOfTrip(instruction);
      return;
    }
    if (instruction.opcode == Opcode::CurveLap && !unrolling_.empty()) {
      copyLapOfTrip(instruction);
      return;
    }
    copy(instruction);
  }

  // A loop's first value and how many trips it runs.
  struct Trips {
    double first = 0;
    std::size_t count = 0;
  };

  // The loop's trips, counted against the bound; nullopt where its bounds
  // are not known at the compiled values (a loop around it not yet written
  // out) or it advances by a step it computes.
  std::optional<Trips> tripsOf(const Instruction& loop) {
    if (loopAdvance(source_, loop).valid()) {
      return std::nullopt;
    }
    std::optional<double> low = compiled_(loop.operands[0]);
    std::optional<double> high = compiled_(loop.operands[1]);
    if (!low || !high) {
      return std::nullopt;
    }
    std::optional<std::size_t> trips =
        passes::tripCount(*low, *high, maximumUnrolledTrips - tripsSoFar_);
    if (!trips) {
      throw CurveLapError(CurveLapError::Kind::ProgramTooLarge, loop.span,
                          fmt::format("the part's loops run more than {} times in all; it is "
                                      "too large to compile",
                                      maximumUnrolledTrips));
    }
    tripsSoFar_ += *trips;
    collectParameters(source_, loop.operands[0], boundParameters_);
    collectParameters(source_, loop.operands[1], boundParameters_);
    return Trips{*low, *trips};
  }

  void unroll(const Instruction& loop, Trips trips) {
    double index = trips.first;
    for (std::size_t trip = 0; trip < trips.count; ++trip, ++index) {
      unrolling_[loop.result.index] = trip;
      replace(loop.result, constant(index));
      rewriteRegion(loop.regions[0]);
      if (output_.instructions.size() > maximumInstructions) {
        throw CurveLapError(CurveLapError::Kind::ProgramTooLarge, loop.span,
                            functionTooLargeMessage());
      }
    }
    unrolling_.erase(loop.result.index);
    markChanged();
  }

  bool branchesCut(const Instruction& conditional) const {
    for (const Region& branch : conditional.regions) {
      if (holdsACut(branch)) {
        return true;
      }
    }
    return false;
  }

  bool holdsACut(const Region& region) const {
    for (InstructionId id : region.instructions) {
      const Instruction& instruction = source_.instructions[id];
      if (instruction.opcode == Opcode::CutBegin) {
        return true;
      }
      for (const Region& inner : instruction.regions) {
        if (holdsACut(inner)) {
          return true;
        }
      }
    }
    return false;
  }

  // Whether this is a later trip of some loop being written out.
  bool laterTrip() const {
    for (const auto& [variable, trip] : unrolling_) {
      if (trip > 0) {
        return true;
      }
    }
    return false;
  }

  // A later trip's cut: a copy of the cut, without the curve the lowering
  // measured (its first trip's).
  void copyCutOfTrip(const Instruction& cutBegin) {
    if (!laterTrip() || cutBegin.index >= output_.cuts.size()) {
      copy(cutBegin);
      return;
    }
    CutGeometry cut = output_.cuts[cutBegin.index];
    cut.curve = nullptr;
    cut.drawnCurve = nullptr;
    output_.cuts.push_back(std::move(cut));
    Instruction own = cutBegin;
    own.index = static_cast<std::uint32_t>(output_.cuts.size() - 1);
    copy(own);
  }

  // A lap in a trip that reads a variable written out: an entry of its own
  // (one for the laps of one entry in a trip: a ramp and the level laps
  // share it), the first trip's too, so that every trip is measured on the
  // curve its regions compute, as the interpreter measures it before.
  void copyLapOfTrip(const Instruction& lap) {
    auto read = lapVariables_.find(&lap);
    if (read == lapVariables_.end()) { // the same lap in every trip: walked once
      read = lapVariables_.emplace(&lap, lapInputs(source_, lap).loopVariables).first;
    }
    bool readsAVariableWrittenOut = false;
    for (std::uint32_t variable : read->second) {
      readsAVariableWrittenOut = readsAVariableWrittenOut || unrolling_.contains(variable);
    }
    if (!readsAVariableWrittenOut || lap.index >= output_.curves.size()) {
      copy(lap);
      return;
    }
    std::vector<std::uint32_t> trip;
    for (const auto& [variable, number] : unrolling_) {
      trip.push_back(static_cast<std::uint32_t>(number));
    }
    auto key = std::make_pair(lap.index, trip);
    auto known = tripEntries_.find(key);
    if (known == tripEntries_.end()) {
      CurveTableEntry entry = output_.curves[lap.index];
      entry.geometry = nullptr;
      output_.curves.push_back(std::move(entry));
      known =
          tripEntries_.emplace(key, static_cast<std::uint32_t>(output_.curves.size() - 1)).first;
    }
    Instruction own = lap;
    own.index = known->second;
    copy(own);
  }

  std::size_t& tripsSoFar_;
  CompiledValues compiled_{source_};
  std::map<std::uint32_t, std::size_t> unrolling_; // the variables written out: their trip
  std::map<std::pair<std::uint32_t, std::vector<std::uint32_t>>, std::uint32_t> tripEntries_;
  std::set<std::uint32_t> boundParameters_;
  std::map<const Instruction*, std::set<std::uint32_t>> lapVariables_; // by source lap
};

void collectCutOrder(const Function& function, const Region& region,
                     std::map<std::uint32_t, std::uint32_t>& renumbered) {
  for (InstructionId id : region.instructions) {
    const Instruction& instruction = function.instructions[id];
    if (instruction.opcode == Opcode::CutBegin && !renumbered.contains(instruction.index)) {
      auto next = static_cast<std::uint32_t>(renumbered.size());
      renumbered[instruction.index] = next;
    }
    for (const Region& inner : instruction.regions) {
      collectCutOrder(function, inner, renumbered);
    }
  }
}

// The cut table in the order the program begins its cuts (the order the
// lowering numbers them in when it writes a loop out); a cut no cut.begin
// names is dropped.
void numberCutsInProgramOrder(Function& function) {
  std::map<std::uint32_t, std::uint32_t> renumbered;
  collectCutOrder(function, function.body, renumbered);
  std::vector<CutGeometry> cuts(renumbered.size());
  for (const auto& [old, now] : renumbered) {
    if (old < function.cuts.size()) {
      cuts[now] = function.cuts[old];
    }
  }
  function.cuts = std::move(cuts);
  for (Instruction& instruction : function.instructions) {
    if (instruction.opcode == Opcode::CutBegin) {
      auto found = renumbered.find(instruction.index);
      if (found != renumbered.end()) {
        instruction.index = found->second;
      }
    }
  }
}

// The curve table without the entries no lap names any more (a loop's
// entry whose trips each have their own, an untaken branch's), in order.
void dropCurvesNoLapNames(Function& function) {
  std::map<std::uint32_t, std::uint32_t> renumbered;
  for (const Instruction& instruction : function.instructions) {
    if (instruction.opcode == Opcode::CurveLap) {
      renumbered.emplace(instruction.index, 0);
    }
  }
  std::vector<CurveTableEntry> curves;
  for (auto& [old, now] : renumbered) {
    now = static_cast<std::uint32_t>(curves.size());
    curves.push_back(old < function.curves.size() ? function.curves[old] : CurveTableEntry{});
  }
  function.curves = std::move(curves);
  for (Instruction& instruction : function.instructions) {
    if (instruction.opcode == Opcode::CurveLap) {
      instruction.index = renumbered.at(instruction.index);
    }
  }
}

} // namespace

bool unrollHostControl(Function& function) {
  if (!hostComputesTheProgram(function)) {
    return false;
  }
  std::size_t tripsSoFar = 0;
  bool changed = false;
  for (;;) {
    HostLoopUnroller unroller(function, tripsSoFar);
    Function unrolled = unroller.run();
    if (!unroller.changed()) {
      break;
    }
    for (std::uint32_t parameter : unroller.boundParameters()) {
      unrolled.parameters[parameter].fixed = true;
    }
    function = std::move(unrolled);
    changed = true;
  }
  if (changed) {
    numberCutsInProgramOrder(function);
    dropCurvesNoLapNames(function);
  }
  return changed;
}

} // namespace cncc::ir
