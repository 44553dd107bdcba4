#include "lap_cuts.h"

#include "passes/rewriter.h"

#include <optional>
#include <set>
#include <utility>
#include <vector>

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

bool lapRamps(const Function& function, const Instruction& lap) {
  ValueId from = lap.operands[0];
  ValueId to = lap.operands[1];
  if (from == to) {
    return false;
  }
  std::optional<double> a = passes::constantValue(function, from);
  std::optional<double> b = passes::constantValue(function, to);
  return !(a && b && *a == *b);
}

const CutGeometry* hostComputedCut(const Function& function, std::uint32_t cut) {
  bool host = cut < function.cuts.size() && !function.cuts[cut].controllerDigits;
  return host ? &function.cuts[cut] : nullptr;
}

LapInputs valueInputs(const Function& function, std::vector<ValueId> work) {
  LapInputs inputs;
  std::set<std::uint32_t> seen;
  while (!work.empty()) {
    ValueId value = work.back();
    work.pop_back();
    if (!value.valid() || !seen.insert(value.index).second) {
      continue;
    }
    const Instruction& definition = function.definition(value);
    if (definition.opcode == Opcode::Param) {
      inputs.parameters.insert(definition.index);
    } else if (definition.opcode == Opcode::Loop) {
      inputs.loopVariables.insert(value.index);
    } else if (definition.opcode != Opcode::CurveLap) {
      work.insert(work.end(), definition.operands.begin(), definition.operands.end());
    }
  }
  return inputs;
}

LapInputs lapInputs(const Function& function, const Instruction& lap) {
  std::vector<ValueId> work;
  for (const Region& region : lap.regions) {
    for (InstructionId id : region.instructions) {
      const Instruction& instruction = function.instructions[id];
      work.insert(work.end(), instruction.operands.begin(), instruction.operands.end());
    }
  }
  // The ranges of the regions whose steps the program computes: the chords
  // are chosen over their values too (not the counts, which they replace).
  for (std::size_t first = 3; first + 1 < lap.operands.size(); first += 3) {
    work.push_back(lap.operands[first]);
    work.push_back(lap.operands[first + 1]);
  }
  return valueInputs(function, std::move(work));
}

std::optional<CurveTableEntry> entryToMeasure(const Function& function, const Instruction& lap,
                                              CompiledValues& compiled, const LoopTrip* trip) {
  if (lap.opcode != Opcode::CurveLap || lap.index >= function.curves.size()) {
    return std::nullopt; // the verifier's problem
  }
  std::set<std::uint32_t> variables = lapInputs(function, lap).loopVariables;
  for (std::uint32_t variable : variables) {
    auto value = trip != nullptr ? trip->find(variable) : LoopTrip::const_iterator{};
    if (trip == nullptr || value == trip->end()) {
      return std::nullopt;
    }
    compiled.know(ValueId{variable}, value->second);
  }
  CurveTableEntry entry = function.curves[lap.index];
  if (!variables.empty()) {
    entry.geometry = nullptr;
  }
  return entry;
}

} // namespace cncc::ir
