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
  auto known = bounded_.find(&lap);
  if (known == bounded_.end()) {
    known = bounded_.emplace(&lap, boundedStepsEntry(function_, lap, cutOf(lap))).first;
  }
  return known->second ? *known->second : own;
}

const LegalisedEntries::SplitLap* LegalisedEntries::splitOf(const Instruction& lap) {
  const CurveTableEntry& own = function_.curves[lap.index];
  if (own.sampling != CurveSampling::Steps || own.arcRegions.empty()) {
    return nullptr;
  }
  auto known = split_.find(&lap);
  if (known == split_.end()) {
    std::optional<std::vector<LapPart>> parts;
    try {
      parts = hostArcLapParts(function_, lap, cutOf(lap));
    } catch (const CurveLapError& error) {
      throw InterpreterError(error.what());
    }
    std::optional<SplitLap> split;
    if (parts) {
      split.emplace();
      for (const LapPart& part : *parts) {
        split->laps.push_back(partLap(lap, part));
      }
      split->parts = std::move(*parts);
    }
    known = split_.emplace(&lap, std::move(split)).first;
  }
  return known->second ? &*known->second : nullptr;
}

std::uint32_t LegalisedEntries::cutOf(const Instruction& lap) {
  if (!cuts_) {
    cuts_.emplace();
    for (const auto& [index, laps] : lapsByEntry(function_)) {
      (*cuts_)[index] = laps.front().cut;
    }
  }
  auto cut = cuts_->find(lap.index);
  return cut != cuts_->end() ? cut->second : noCut;
}

} // namespace cncc::ir
