#include "macro_loop_stepping.h"

#include <cmath>
#include <limits>
#include <optional>
#include <vector>

namespace cncc::backends {

using ir::Opcode;
using ir::ValueId;

SteppedLoops stepLoopsByTheirScale(const ir::Function& function, ir::Allocation& allocation) {
  std::map<std::uint32_t, std::vector<ir::InstructionId>> users;
  for (ir::InstructionId id = 0; id < function.instructions.size(); ++id) {
    for (ValueId operand : function.instructions[id].operands) {
      users[operand.index].push_back(id);
    }
  }
  auto constant = [&](ValueId value) {
    const ir::Instruction& definition = function.definition(value);
    return definition.opcode == Opcode::Const ? std::optional<double>(definition.number)
                                              : std::nullopt;
  };
  SteppedLoops stepped;
  for (const ir::Instruction& loop : function.instructions) {
    if (loop.opcode != Opcode::Loop || ir::loopAdvance(function, loop).valid() ||
        !constant(loop.operands[0]) || users[loop.result.index].size() != 1 ||
        !allocation.inVariable(loop.result)) {
      continue;
    }
    const ir::Instruction& product = function.instructions[users[loop.result.index].front()];
    std::optional<double> scale;
    if (product.opcode == Opcode::Mul && constant(loop.operands[1])) {
      ValueId other =
          product.operands[0] == loop.result ? product.operands[1] : product.operands[0];
      scale = constant(other);
    } else if (product.opcode == Opcode::Div && product.operands[0] == loop.result &&
               product.operands[1] == loop.operands[1] && *constant(loop.operands[0]) == 1 &&
               allocation.inVariable(loop.operands[1])) {
      scale = std::numeric_limits<double>::quiet_NaN();
    }
    if (!scale || *scale == 0 || std::isinf(*scale)) {
      continue;
    }
    allocation.variableOfValue[product.result.index] =
        allocation.variableOfValue[loop.result.index];
    stepped.scaleOfIndex[loop.result.index] = *scale;
    stepped.scaledValues.insert(product.result.index);
  }
  // The products' own variables may now be unused.
  std::set<int> used(allocation.parameterVariables.begin(), allocation.parameterVariables.end());
  for (int variable : allocation.variableOfValue) {
    if (variable >= 0) {
      used.insert(variable);
    }
  }
  for (std::size_t table = 0; table < function.tables.size(); ++table) {
    for (std::size_t i = 0; allocation.tableBase[table] >= 0 && i < function.tables[table].size();
         ++i) {
      used.insert(allocation.tableBase[table] + static_cast<int>(i));
    }
  }
  allocation.usedVariables.assign(used.begin(), used.end());
  return stepped;
}

} // namespace cncc::backends
