// Common subexpression elimination over scoped tables: a pure operation is
// looked up in the table of every enclosing region (what is visible at its
// place); a value defined in a region is forgotten when the region ends, so
// nothing is ever reused outside the region that defines it, nor across the
// two branches of an if.
#include "cncc/ir/passes.h"

#include "rewriter.h"

#include <bit>
#include <map>
#include <tuple>

namespace cncc::ir {

namespace {

// What makes two pure operations equal: opcode, operands (output values)
// and immediates; the constant's bits, so -0 and 0 stay apart.
struct ExpressionKey {
  Opcode opcode;
  std::vector<std::uint32_t> operands;
  std::uint64_t numberBits;
  std::uint32_t index;

  friend bool operator<(const ExpressionKey& a, const ExpressionKey& b) {
    return std::tie(a.opcode, a.operands, a.numberBits, a.index) <
           std::tie(b.opcode, b.operands, b.numberBits, b.index);
  }
};

// Operand order does not change the result, bit for bit. (min and max
// return their first operand on ties such as -0 and 0, so they are not.)
bool isCommutative(Opcode opcode) {
  switch (opcode) {
  case Opcode::Add:
  case Opcode::Mul:
  case Opcode::Eq:
  case Opcode::Ne:
  case Opcode::And:
  case Opcode::Or:
    return true;
  default:
    return false;
  }
}

class CommonSubexpressions : public passes::Rewriter {
public:
  using Rewriter::Rewriter;

private:
  void enterRegion() override { scopes_.emplace_back(); }
  void leaveRegion() override { scopes_.pop_back(); }

  void visit(const Instruction& instruction) override {
    if (!isPure(instruction.opcode)) {
      copy(instruction);
      return;
    }
    ExpressionKey key = keyOf(instruction);
    for (auto scope = scopes_.rbegin(); scope != scopes_.rend(); ++scope) {
      auto found = scope->find(key);
      if (found != scope->end()) {
        replace(instruction.result, found->second);
        markChanged();
        return;
      }
    }
    ValueId result = emit(instruction, mappedOperands(instruction));
    replace(instruction.result, result);
    scopes_.back().emplace(std::move(key), result);
  }

  ExpressionKey keyOf(const Instruction& instruction) const {
    ExpressionKey key{instruction.opcode,
                      {},
                      std::bit_cast<std::uint64_t>(instruction.number),
                      instruction.index};
    for (ValueId operand : instruction.operands) {
      key.operands.push_back(mapped(operand).index);
    }
    if (isCommutative(instruction.opcode) && key.operands[1] < key.operands[0]) {
      std::swap(key.operands[0], key.operands[1]);
    }
    return key;
  }

  std::vector<std::map<ExpressionKey, ValueId>> scopes_;
};

} // namespace

bool eliminateCommonSubexpressions(Function& function) {
  CommonSubexpressions pass(function);
  Function result = pass.run();
  function = std::move(result);
  return pass.changed();
}

} // namespace cncc::ir
