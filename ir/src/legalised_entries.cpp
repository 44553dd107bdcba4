#include "legalised_entries.h"

#include "cncc/ir/curve_lap.h"
#include "cncc/ir/interpreter.h"

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
    known = bounded_.emplace(&lap, boundedStepsEntry(function_, lap)).first;
  }
  return known->second ? *known->second : own;
}

} // namespace cncc::ir
