#include "cncc/ir/ir.h"

#include <fmt/format.h>

#include <iterator>

namespace cncc::ir {

namespace {

constexpr OpcodeInfo opcodeTable[] = {
#define CNCC_IR_OP(identifier, spelling, operands, result, traits, meaning)                        \
  {spelling, operands, ValueType::result, OpcodeTraits::traits, meaning},
#include "cncc/ir/ir_ops.def"
};

} // namespace

const OpcodeInfo& opcodeInfo(Opcode opcode) {
  return opcodeTable[static_cast<int>(opcode)];
}

std::vector<Opcode> allOpcodes() {
  std::vector<Opcode> opcodes;
  for (std::size_t i = 0; i < std::size(opcodeTable); ++i) {
    opcodes.push_back(static_cast<Opcode>(i));
  }
  return opcodes;
}

namespace {
constexpr std::string_view coolantModeNames[] = {"off", "flood", "mist", "through"};
} // namespace

std::string_view coolantModeName(CoolantMode mode) {
  return coolantModeNames[static_cast<std::size_t>(mode)];
}

std::optional<CoolantMode> coolantModeNamed(std::string_view name) {
  for (std::size_t i = 0; i < std::size(coolantModeNames); ++i) {
    if (coolantModeNames[i] == name) {
      return static_cast<CoolantMode>(i);
    }
  }
  return std::nullopt;
}

} // namespace cncc::ir

namespace cncc::ir {

ValueId loopAdvance(const Function& function, const Instruction& loop) {
  if (loop.opcode != Opcode::Loop || loop.regions.empty() || loop.regions[0].instructions.empty()) {
    return {};
  }
  const Instruction& last = function.instructions[loop.regions[0].instructions.back()];
  return last.opcode == Opcode::LoopNext && !last.operands.empty() ? last.operands[0] : ValueId{};
}

} // namespace cncc::ir

namespace cncc::ir {

bool isTooLarge(const Function& function) {
  std::size_t entries = 0;
  for (const std::vector<double>& table : function.tables) {
    entries += table.size();
  }
  return function.instructions.size() > maximumInstructions || entries > maximumTableEntries;
}

std::string functionTooLargeMessage() {
  return fmt::format("the part grows past {} IR instructions or {} table entries here; it is too "
                     "large to compile",
                     maximumInstructions, maximumTableEntries);
}

} // namespace cncc::ir
