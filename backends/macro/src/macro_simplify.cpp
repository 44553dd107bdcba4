#include "macro_simplify.h"

#include "cncc/ir/arithmetic.h"

#include <cmath>
#include <optional>

namespace cncc::backends {

namespace {

// A constant number from constant operands, by the IR's own arithmetic (a
// comparison, whose result is a bool, stays as it is).
std::optional<double> fold(ir::Opcode opcode, double a) {
  if (ir::opcodeInfo(opcode).result != ir::ValueType::F64) {
    return std::nullopt;
  }
  return ir::unaryResult(opcode, a);
}

std::optional<double> fold(ir::Opcode opcode, double a, double b) {
  if (ir::opcodeInfo(opcode).result != ir::ValueType::F64) {
    return std::nullopt;
  }
  return ir::binaryResult(opcode, a, b);
}

class Simplifier {
public:
  explicit Simplifier(const ir::Function& function) : function_(function) {
    alias_.resize(function.valueTypes.size());
    for (std::size_t i = 0; i < alias_.size(); ++i) {
      alias_[i] = ir::ValueId{static_cast<std::uint32_t>(i)};
    }
  }

  ir::Function run() {
    simplifyRegion(function_.body);
    return std::move(function_);
  }

private:
  std::optional<double> constant(ir::ValueId value) const {
    const ir::Instruction& instruction = function_.definition(value);
    if (instruction.opcode == ir::Opcode::Const) {
      return std::abs(instruction.number) < 1e-12 ? 0 : instruction.number;
    }
    return std::nullopt;
  }

  bool isConstant(ir::ValueId value, double number) const {
    std::optional<double> known = constant(value);
    return known && std::abs(*known - number) < 1e-12; // 0.9999999999999999 is 1
  }

  void simplifyRegion(const ir::Region& region) {
    for (ir::InstructionId id : region.instructions) {
      for (ir::ValueId& operand : function_.instructions[id].operands) {
        operand = alias_[operand.index];
      }
      simplifyInstruction(id);
      // Regions are visited after the operands of their owner are resolved.
      std::size_t regionCount = function_.instructions[id].regions.size();
      for (std::size_t r = 0; r < regionCount; ++r) {
        ir::Region nested = function_.instructions[id].regions[r];
        simplifyRegion(nested);
      }
    }
  }

  void becomeConstant(ir::InstructionId id, double number) {
    if (!std::isfinite(number)) {
      return; // leave it to the controller, which will alarm where the host would fail
    }
    ir::Instruction& instruction = function_.instructions[id];
    // sin(2 pi) is -2.4e-16, not 0: below any printed digit, it is 0.
    if (std::abs(number) < 1e-12) {
      number = 0;
    }
    instruction.opcode = ir::Opcode::Const;
    instruction.operands.clear();
    instruction.number = number;
  }

  void simplifyInstruction(ir::InstructionId id) {
    ir::Instruction& instruction = function_.instructions[id];
    if (!instruction.result.valid() || instruction.opcode == ir::Opcode::Loop) {
      return;
    }
    const std::vector<ir::ValueId>& operands = instruction.operands;
    if (operands.size() == 1) {
      if (std::optional<double> a = constant(operands[0])) {
        if (std::optional<double> folded = fold(instruction.opcode, *a)) {
          becomeConstant(id, *folded);
        }
      }
      return;
    }
    if (operands.size() != 2) {
      return;
    }
    std::optional<double> a = constant(operands[0]);
    std::optional<double> b = constant(operands[1]);
    if (a && b) {
      if (std::optional<double> folded = fold(instruction.opcode, *a, *b)) {
        becomeConstant(id, *folded);
      }
      return;
    }
    applyIdentity(id);
  }

  // x+0, 0+x, x-0, x*1, 1*x, x/1 are x; x*0 and 0*x are 0.
  void applyIdentity(ir::InstructionId id) {
    ir::Instruction& instruction = function_.instructions[id];
    ir::ValueId left = instruction.operands[0];
    ir::ValueId right = instruction.operands[1];
    ir::ValueId same;
    switch (instruction.opcode) {
    case ir::Opcode::Add:
      same = isConstant(left, 0) ? right : isConstant(right, 0) ? left : ir::ValueId{};
      break;
    case ir::Opcode::Sub:
      same = isConstant(right, 0) ? left : ir::ValueId{};
      break;
    case ir::Opcode::Mul:
      if (isConstant(left, 0) || isConstant(right, 0)) {
        becomeConstant(id, 0);
        return;
      }
      same = isConstant(left, 1) ? right : isConstant(right, 1) ? left : ir::ValueId{};
      break;
    case ir::Opcode::Div:
      same = isConstant(right, 1) ? left : ir::ValueId{};
      break;
    default:
      break;
    }
    if (same.valid()) {
      alias_[instruction.result.index] = same;
    }
  }

  ir::Function function_;
  std::vector<ir::ValueId> alias_;
};

} // namespace

ir::Function simplifyForMacroProgram(const ir::Function& function) {
  return Simplifier(function).run();
}

} // namespace cncc::backends
