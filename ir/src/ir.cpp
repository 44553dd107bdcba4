#include "cncc/ir/ir.h"

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

} // namespace cncc::ir
