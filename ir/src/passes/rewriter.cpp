#include "rewriter.h"

#include <cmath>

namespace cncc::ir::passes {

std::size_t regionSize(const Function& function, const Region& region) {
  std::size_t size = 0;
  for (InstructionId id : region.instructions) {
    size += 1;
    for (const Region& nested : function.instructions[id].regions) {
      size += regionSize(function, nested);
    }
  }
  return size;
}

bool regionHasEffect(const Function& function, const Region& region) {
  for (InstructionId id : region.instructions) {
    const Instruction& instruction = function.instructions[id];
    if (isEffect(instruction.opcode)) {
      return true;
    }
    for (const Region& nested : instruction.regions) {
      if (regionHasEffect(function, nested)) {
        return true;
      }
    }
  }
  return false;
}

std::optional<double> constantValue(const Function& function, ValueId value) {
  const Instruction& definition = function.definition(value);
  if (definition.opcode == Opcode::Const || definition.opcode == Opcode::ConstBool) {
    return definition.number;
  }
  return std::nullopt;
}

std::optional<std::size_t> tripCount(double low, double high, std::size_t limit) {
  if (!std::isfinite(low) || !std::isfinite(high)) {
    return std::nullopt;
  }
  std::size_t count = 0;
  for (double i = low; i <= high; ++i) {
    if (++count > limit) {
      return std::nullopt;
    }
  }
  return count;
}

Rewriter::Rewriter(const Function& source) : source_(source), map_(source.valueTypes.size()) {
  output_.name = source.name;
  output_.parameters = source.parameters;
  output_.tables = source.tables;
  output_.curves = source.curves;
  output_.cuts = source.cuts;
  output_.warnings = source.warnings;
  // Most passes write about as many instructions as they read: one
  // allocation each, not a doubling's copies (a part of thousands of cuts).
  output_.instructions.reserve(source.instructions.size());
  output_.valueTypes.reserve(source.valueTypes.size());
  output_.definitions.reserve(source.definitions.size());
}

Function Rewriter::run() {
  rewriteRegion(source_.body);
  return std::move(output_);
}

void Rewriter::rewriteRegion(const Region& region) {
  enterRegion();
  for (InstructionId id : region.instructions) {
    // What a visit makes in place of an instruction comes from its statement.
    frontend::SourceSpan outer = visiting_;
    SweepPass outerPass = visitingPass_;
    visiting_ = source_.instructions[id].span;
    visitingPass_ = source_.instructions[id].pass;
    visit(source_.instructions[id]);
    visiting_ = outer;
    visitingPass_ = outerPass;
  }
  leaveRegion();
}

std::vector<ValueId> Rewriter::mappedOperands(const Instruction& instruction) const {
  std::vector<ValueId> operands;
  operands.reserve(instruction.operands.size());
  for (ValueId operand : instruction.operands) {
    operands.push_back(mapped(operand));
  }
  return operands;
}

void Rewriter::copy(const Instruction& instruction) {
  if (instruction.regions.empty()) {
    ValueId result = emit(instruction, mappedOperands(instruction));
    if (instruction.result.valid()) {
      replace(instruction.result, result);
    }
    return;
  }
  ValueId result = beginRegions(instruction, mappedOperands(instruction));
  if (instruction.result.valid()) {
    replace(instruction.result, result);
  }
  for (std::size_t region = 0; region < instruction.regions.size(); ++region) {
    enterOutputRegion(region);
    rewriteRegion(instruction.regions[region]);
  }
  endRegions();
}

Region& Rewriter::currentRegion() {
  if (insertion_.empty()) {
    return output_.body;
  }
  auto [instruction, region] = insertion_.back();
  return output_.instructions[instruction].regions[region];
}

ValueId Rewriter::append(Instruction instruction) {
  auto id = static_cast<InstructionId>(output_.instructions.size());
  ValueType type = opcodeInfo(instruction.opcode).result;
  instruction.result = ValueId{};
  if (type != ValueType::None) {
    instruction.result = ValueId{static_cast<std::uint32_t>(output_.valueTypes.size())};
    output_.valueTypes.push_back(type);
    output_.definitions.push_back(id);
  }
  currentRegion().instructions.push_back(id);
  if (!instruction.span.valid()) {
    instruction.span = visiting_;
    instruction.pass = visitingPass_;
  }
  if (writingTrip_.number != 0) {
    instruction.pass = passInLoop(instruction.pass, writingTrip_.number, writingTrip_.count);
  }
  output_.instructions.push_back(std::move(instruction));
  return output_.instructions.back().result;
}

ValueId Rewriter::emit(const Instruction& instruction, std::vector<ValueId> operands) {
  return emitAs(instruction, instruction.opcode, std::move(operands));
}

ValueId Rewriter::emitAs(const Instruction& instruction, Opcode opcode,
                         std::vector<ValueId> operands) {
  Instruction copy = withoutRegions(instruction); // its result is the output's (append)
  copy.opcode = opcode;
  copy.operands = std::move(operands);
  return append(std::move(copy));
}

ValueId Rewriter::constant(double value) {
  Instruction instruction;
  instruction.opcode = Opcode::Const;
  instruction.number = value;
  return append(std::move(instruction));
}

ValueId Rewriter::constantBool(bool value) {
  Instruction instruction;
  instruction.opcode = Opcode::ConstBool;
  instruction.number = value ? 1 : 0;
  return append(std::move(instruction));
}

ValueId Rewriter::beginRegions(const Instruction& instruction, std::vector<ValueId> operands) {
  Instruction copy;
  copy.opcode = instruction.opcode;
  copy.operands = std::move(operands);
  copy.number = instruction.number;
  copy.index = instruction.index;
  copy.span = instruction.span;
  copy.pass = instruction.pass;
  copy.regions.resize(instruction.regions.size());
  ValueId result = append(std::move(copy));
  insertion_.push_back({static_cast<InstructionId>(output_.instructions.size() - 1), 0});
  return result;
}

void Rewriter::enterOutputRegion(std::size_t region) {
  insertion_.back().second = region;
}

void Rewriter::endRegions() {
  insertion_.pop_back();
}

} // namespace cncc::ir::passes
