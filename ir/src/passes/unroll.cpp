// Full unrolling of loops with constant bounds and a small trip count (a
// small body, or any body that runs at most once): the loop becomes copies
// of its body, one per iteration, the induction variable a constant in
// each, counted as the interpreter counts (i = low, then ++i while
// i <= high). Loops nested in an unrolled body are copied
// and, when they qualify themselves, unrolled too.
#include "cncc/ir/passes.h"

#include "rewriter.h"

#include <set>

namespace cncc::ir {

namespace {

// The trip count of a loop that qualifies, read from the source function.
std::optional<std::size_t> unrollableTrips(const Function& function, const Instruction& loop,
                                           const UnrollOptions& options) {
  if (loopAdvance(function, loop).valid()) {
    return std::nullopt; // its trip count is known only by running it
  }
  std::optional<double> low = passes::constantValue(function, loop.operands[0]);
  std::optional<double> high = passes::constantValue(function, loop.operands[1]);
  if (!low || !high) {
    return std::nullopt;
  }
  std::optional<std::size_t> trips = passes::tripCount(*low, *high, options.maximumTripCount);
  // One trip or none never makes the function larger, whatever the body.
  if (trips && *trips > 1 &&
      passes::regionSize(function, loop.regions[0]) > options.maximumBodySize) {
    return std::nullopt;
  }
  return trips;
}

class Unroller : public passes::Rewriter {
public:
  // Unrolls the qualifying loops in `only` (instruction ids of the source),
  // or every qualifying loop when `only` is null.
  Unroller(const Function& source, const UnrollOptions& options,
           const std::set<InstructionId>* only)
      : Rewriter(source), options_(options), only_(only) {}

private:
  void visit(const Instruction& instruction) override {
    if (instruction.opcode != Opcode::Loop || !chosen(instruction)) {
      copy(instruction);
      return;
    }
    std::optional<std::size_t> trips = unrollableTrips(source_, instruction, options_);
    if (!trips) {
      copy(instruction);
      return;
    }
    double index = *passes::constantValue(source_, instruction.operands[0]);
    bool passes = static_cast<LoopRole>(instruction.index) == LoopRole::Passes;
    SweepPass outer = writingTrip_;
    for (std::size_t trip = 0; trip < *trips; ++trip, ++index) {
      if (passes) { // each copy is a pass of the sweep
        writingTrip_ = passTrip(static_cast<double>(trip + 1), static_cast<double>(*trips));
      }
      replace(instruction.result, constant(index));
      rewriteRegion(instruction.regions[0]);
    }
    writingTrip_ = outer;
    markChanged();
  }

  bool chosen(const Instruction& loop) const {
    return only_ == nullptr || only_->count(source_.definitions[loop.result.index]) != 0;
  }

  const UnrollOptions& options_;
  const std::set<InstructionId>* only_;
};

Function unrolled(const Function& function, const UnrollOptions& options,
                  const std::set<InstructionId>* only, bool& changed) {
  Unroller pass(function, options, only);
  Function result = pass.run();
  changed = pass.changed();
  return result;
}

std::size_t cleanedUpSize(Function function) {
  foldConstants(function);
  eliminateCommonSubexpressions(function);
  eliminateDeadCode(function);
  return instructionCount(function);
}

// The loops that qualify: those of one trip or none in `atMostOnce` (their
// copy of the body is never larger than the loop), the others in `candidates`.
void collectCandidates(const Function& function, const Region& region, const UnrollOptions& options,
                       std::vector<InstructionId>& candidates,
                       std::set<InstructionId>& atMostOnce) {
  for (InstructionId id : region.instructions) {
    const Instruction& instruction = function.instructions[id];
    std::optional<std::size_t> trips;
    if (instruction.opcode == Opcode::Loop) {
      trips = unrollableTrips(function, instruction, options);
    }
    if (trips && *trips <= 1) {
      atMostOnce.insert(id);
    } else if (trips) {
      candidates.push_back(id);
    }
    for (const Region& nested : instruction.regions) {
      collectCandidates(function, nested, options, candidates, atMostOnce);
    }
  }
}

// Tries each qualifying loop alone and keeps the ones after which the
// cleaned-up function is no larger; then all of them together, if that
// is no larger either. Where a trial each would copy more than
// options.maximumTrialInstructions, the loops are tried in groups of neighbours,
// each kept or not as a whole.
bool unrollWhenNoLarger(Function& function, const UnrollOptions& options) {
  std::vector<InstructionId> candidates;
  std::set<InstructionId> accepted; // a loop of one trip or none: no trial needed
  collectCandidates(function, function.body, options, candidates, accepted);
  if (candidates.empty() && accepted.empty()) {
    return false;
  }
  if (candidates.empty()) { // nothing to measure: no copy of a body is larger
    bool changed = false;
    function = unrolled(function, options, &accepted, changed);
    return changed;
  }
  std::size_t baseline = cleanedUpSize(function);
  std::size_t group = candidates.size() * baseline / options.maximumTrialInstructions + 1;
  for (std::size_t first = 0; first < candidates.size(); first += group) {
    std::size_t last = std::min(candidates.size(), first + group);
    std::set<InstructionId> only(candidates.begin() + static_cast<std::ptrdiff_t>(first),
                                 candidates.begin() + static_cast<std::ptrdiff_t>(last));
    bool changed = false;
    Function trial = unrolled(function, options, &only, changed);
    if (changed && cleanedUpSize(std::move(trial)) <= baseline) {
      accepted.insert(only.begin(), only.end());
    }
  }
  bool changed = false;
  Function result = unrolled(function, options, &accepted, changed);
  if (!changed || cleanedUpSize(result) > baseline) {
    return false;
  }
  function = std::move(result);
  return true;
}

} // namespace

bool unrollLoops(Function& function, const UnrollOptions& options) {
  if (options.onlyWhenNoLarger) {
    return unrollWhenNoLarger(function, options);
  }
  bool changed = false;
  function = unrolled(function, options, nullptr, changed);
  return changed;
}

} // namespace cncc::ir
