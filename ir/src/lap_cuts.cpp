#include "lap_cuts.h"

#include <optional>

namespace cncc::ir {

namespace {

void collectLaps(const Function& function, const Region& region, std::optional<std::uint32_t>& cut,
                 std::map<std::uint32_t, std::vector<LapOfCut>>& laps) {
  for (InstructionId id : region.instructions) {
    const Instruction& instruction = function.instructions[id];
    if (instruction.opcode == Opcode::CutBegin) {
      cut = instruction.index;
    } else if (instruction.opcode == Opcode::CurveLap) {
      laps[instruction.index].push_back({id, cut.value_or(noCut)});
      continue; // its regions are arithmetic
    }
    for (const Region& inner : instruction.regions) {
      collectLaps(function, inner, cut, laps);
    }
  }
}

} // namespace

std::map<std::uint32_t, std::vector<LapOfCut>> lapsByEntry(const Function& function) {
  std::map<std::uint32_t, std::vector<LapOfCut>> laps;
  std::optional<std::uint32_t> cut;
  collectLaps(function, function.body, cut, laps);
  return laps;
}

const CutGeometry* hostComputedCut(const Function& function, std::uint32_t cut) {
  bool host = cut < function.cuts.size() && !function.cuts[cut].controllerDigits;
  return host ? &function.cuts[cut] : nullptr;
}

} // namespace cncc::ir
