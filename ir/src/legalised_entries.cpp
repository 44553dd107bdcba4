#include "legalised_entries.h"

#include "cncc/ir/curve_lap.h"
#include "cncc/ir/interpreter.h"

#include "lap_cuts.h"

namespace cncc::ir {

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
  if (!cuts_) {
    cuts_.emplace();
    for (const auto& [index, laps] : lapsByEntry(function_)) {
      (*cuts_)[index] = laps.front().cut;
    }
  }
  auto known = bounded_.find(&lap);
  if (known == bounded_.end()) {
    auto cut = cuts_->find(lap.index);
    std::uint32_t cutOfLap = cut != cuts_->end() ? cut->second : noCut;
    known = bounded_.emplace(&lap, boundedStepsEntry(function_, lap, cutOfLap)).first;
  }
  return known->second ? *known->second : own;
}

} // namespace cncc::ir
