#include "legalised_entries.h"

#include "cncc/ir/curve_lap.h"
#include "cncc/ir/interpreter.h"

#include <set>

namespace cncc::ir {

namespace {

// The trips of one lap kept at once (a loop of many trips runs each once).
constexpr std::size_t keptTrips = 64;

} // namespace

const CurveTableEntry& LegalisedEntries::of(const Instruction& lap) {
  const CurveTableEntry& own = function_.curves[lap.index];
  if (own.sampling == CurveSampling::ChordTolerance || own.sampling == CurveSampling::Samples) {
    if (!stepped_) {
      try {
        stepped_ = controllerStepsEntries(function_);
      } catch (const CurveLapError& error) {
        throw InterpreterError(error.what());
      }
    }
    auto stepped = stepped_->find(lap.index);
    return stepped != stepped_->end() ? stepped->second : own;
  }
  if (own.sampling != CurveSampling::Steps) {
    return own;
  }
  const LapFacts& facts = factsOf(lap);
  LoopTrip trip = tripOf(facts);
  const std::optional<CurveTableEntry>& bounded = remembered(
      bounded_[&lap], trip, [&] { return boundedStepsEntry(function_, lap, facts.cut, &trip); });
  return bounded ? *bounded : own;
}

const LegalisedEntries::SplitLap* LegalisedEntries::splitOf(const Instruction& lap) {
  const CurveTableEntry& own = function_.curves[lap.index];
  if (own.sampling != CurveSampling::Steps || own.arcRegions.empty()) {
    return nullptr;
  }
  const LapFacts& facts = factsOf(lap);
  LoopTrip trip = tripOf(facts);
  const std::optional<SplitLap>& split = remembered(split_[&lap], trip, [&] {
    std::optional<std::vector<LapPart>> parts;
    try {
      parts = hostArcLapParts(function_, lap, facts.cut, &trip);
    } catch (const CurveLapError& error) {
      throw InterpreterError(error.what());
    }
    std::optional<SplitLap> made;
    if (parts) {
      made.emplace();
      for (const LapPart& part : *parts) {
        made->laps.push_back(partLap(lap, part));
      }
      made->parts = std::move(*parts);
    }
    return made;
  });
  return split ? &*split : nullptr;
}

const LegalisedEntries::LapFacts& LegalisedEntries::factsOf(const Instruction& lap) {
  auto known = facts_.find(&lap);
  if (known != facts_.end()) {
    return known->second;
  }
  if (!cuts_) {
    cuts_.emplace();
    for (const auto& [index, laps] : lapsByEntry(function_)) {
      (*cuts_)[index] = laps.front().cut;
    }
  }
  LapFacts facts;
  auto cut = cuts_->find(lap.index);
  facts.cut = cut != cuts_->end() ? cut->second : noCut;
  if (hostComputedCut(function_, facts.cut) != nullptr) {
    std::set<std::uint32_t> variables = lapInputs(function_, lap).loopVariables;
    facts.loopVariables.assign(variables.begin(), variables.end());
  }
  return facts_.emplace(&lap, std::move(facts)).first->second;
}

LoopTrip LegalisedEntries::tripOf(const LapFacts& facts) const {
  LoopTrip trip;
  for (std::uint32_t variable : facts.loopVariables) {
    trip[variable] = current_(ValueId{variable});
  }
  return trip;
}

template <class Value, class Make>
const Value& LegalisedEntries::remembered(std::map<LoopTrip, Value>& cache, const LoopTrip& trip,
                                          const Make& make) {
  auto known = cache.find(trip);
  if (known == cache.end()) {
    if (cache.size() >= keptTrips) {
      cache.clear();
    }
    known = cache.emplace(trip, make()).first;
  }
  return known->second;
}

} // namespace cncc::ir
