// Constant folding and algebraic simplification.
//
// The rule for identities: one is used only when it gives the same bits as
// the operation for every input the operand can hold. So `x + -0 -> x`,
// `x - 0 -> x`, `x * 1`, `x / 1`, `-(-x)`, `min(x, x)` always apply, and so do
// `x * -1 -> -x`, `a + -b -> a - b`, `a - -b -> a + b` and `a + b * -c ->
// a - b * c`; but
//   x + 0  -> x   only when x is known not to be -0 (-0 + 0 is +0, and the
//                 sign of a zero reaches atan2 and division);
//   x * 0  -> 0   only when x is known finite and not negative (inf * 0 is
//                 NaN, -1 * 0 is -0);
//   x - x  -> 0,  x == x -> true  only when x is known finite / not NaN.
// What is known comes from ValueFacts below: constants, loop induction
// variables (the interpreter only runs loops with finite bounds), loads
// from tables of finite numbers, and a few operations that keep those.
// Parameters are never assumed anything: their values come at run time.
// A result that is NaN or infinite is not folded into a constant.
#include "cncc/ir/passes.h"

#include "evaluate.h"
#include "rewriter.h"

#include <cmath>

namespace cncc::ir {

namespace {

using passes::constantValue;

struct ValueFacts {
  bool finite = false;
  bool nonNegative = false; // not NaN and the sign bit clear (so not -0)
};

ValueFacts factsOfNumber(double value) {
  return {std::isfinite(value), !std::isnan(value) && !std::signbit(value)};
}

class Folder : public passes::Rewriter {
public:
  using Rewriter::Rewriter;

private:
  void visit(const Instruction& instruction) override {
    switch (instruction.opcode) {
    case Opcode::If:
      visitIf(instruction);
      return;
    case Opcode::Loop:
      visitLoop(instruction);
      return;
    case Opcode::Const:
    case Opcode::ConstBool:
    case Opcode::Param:
      copy(instruction);
      return;
    default:
      break;
    }
    if (!isPure(instruction.opcode)) {
      copy(instruction);
      return;
    }
    std::vector<ValueId> operands = mappedOperands(instruction);
    ValueId replacement = foldedConstant(instruction, operands);
    if (!replacement.valid()) {
      replacement = simplified(instruction, operands);
    }
    if (replacement.valid()) {
      replace(instruction.result, replacement);
      markChanged();
      return;
    }
    replace(instruction.result, emit(instruction, std::move(operands)));
  }

  void visitIf(const Instruction& instruction) {
    std::optional<double> condition = constantValue(output_, mapped(instruction.operands[0]));
    if (!condition) {
      copy(instruction);
      return;
    }
    // The taken region's instructions join the enclosing region.
    rewriteRegion(instruction.regions[*condition != 0 ? 0 : 1]);
    markChanged();
  }

  void visitLoop(const Instruction& instruction) {
    std::optional<double> low = constantValue(output_, mapped(instruction.operands[0]));
    std::optional<double> high = constantValue(output_, mapped(instruction.operands[1]));
    if (low && high) {
      bool advancing = loopAdvance(source_, instruction).valid();
      std::optional<std::size_t> trips = advancing && *low >= *high
                                             ? std::optional<std::size_t>(0)
                                             : passes::tripCount(*low, *high, 0);
      if (trips && *trips == 0) {
        markChanged();
        return;
      }
    }
    copy(instruction);
  }

  // A constant for an operation whose operands are all constants.
  ValueId foldedConstant(const Instruction& instruction, const std::vector<ValueId>& operands) {
    std::vector<double> values;
    for (ValueId operand : operands) {
      std::optional<double> value = constantValue(output_, operand);
      if (!value) {
        return {};
      }
      values.push_back(*value);
    }
    std::optional<double> result = passes::evaluate(output_, instruction, values);
    if (!result) {
      return {};
    }
    if (opcodeInfo(instruction.opcode).result == ValueType::Bool) {
      return constantBool(*result != 0);
    }
    return std::isfinite(*result) ? constant(*result) : ValueId{};
  }

  bool isConstant(ValueId value, double number) {
    std::optional<double> constant = constantValue(output_, value);
    return constant && *constant == number && std::signbit(*constant) == std::signbit(number);
  }

  const Instruction& definition(ValueId value) const { return output_.definition(value); }

  // An existing or new value equal to the operation, or none.
  ValueId simplified(const Instruction& instruction, const std::vector<ValueId>& operands) {
    switch (instruction.opcode) {
    case Opcode::Add:
      return simplifiedAdd(instruction, operands[0], operands[1]);
    case Opcode::Sub:
      if (isConstant(operands[1], 0.0)) {
        return operands[0];
      }
      if (definition(operands[1]).opcode == Opcode::Neg) {
        return emitAs(instruction, Opcode::Add, {operands[0], definition(operands[1]).operands[0]});
      }
      if (ValueId product = negatedProduct(instruction, operands[1]); product.valid()) {
        return emitAs(instruction, Opcode::Add, {operands[0], product});
      }
      return operands[0] == operands[1] && facts(operands[0]).finite ? constant(0.0) : ValueId{};
    case Opcode::Mul:
      return simplifiedMultiply(instruction, operands[0], operands[1]);
    case Opcode::Div:
      return isConstant(operands[1], 1.0) ? operands[0] : ValueId{};
    case Opcode::Neg:
    case Opcode::Not:
      return definition(operands[0]).opcode == instruction.opcode
                 ? definition(operands[0]).operands[0]
                 : ValueId{};
    case Opcode::Abs:
      return definition(operands[0]).opcode == Opcode::Abs ? operands[0] : ValueId{};
    case Opcode::Min:
    case Opcode::Max:
      return operands[0] == operands[1] ? operands[0] : ValueId{};
    case Opcode::Select:
      return simplifiedSelect(operands);
    default:
      break;
    }
    return simplifiedLogic(instruction.opcode, operands);
  }

  // a + -b and -b + a are a - b, a + b * -c and b * -c + a are a - b * c:
  // the same bits for every a and b.
  ValueId simplifiedAdd(const Instruction& instruction, ValueId left, ValueId right) {
    for (auto [value, other] : {std::pair{left, right}, std::pair{right, left}}) {
      if (isConstant(other, -0.0) || (isConstant(other, 0.0) && facts(value).nonNegative)) {
        return value;
      }
      if (definition(other).opcode == Opcode::Neg) {
        return emitAs(instruction, Opcode::Sub, {value, definition(other).operands[0]});
      }
    }
    for (auto [value, other] : {std::pair{left, right}, std::pair{right, left}}) {
      if (ValueId product = negatedProduct(instruction, other); product.valid()) {
        return emitAs(instruction, Opcode::Sub, {value, product});
      }
    }
    return {};
  }

  // b * c for a product b * -c of a constant -c < 0: a + b * -c is a - b * c
  // and a - b * -c is a + b * c, bit for bit (negation is exact).
  ValueId negatedProduct(const Instruction& instruction, ValueId value) {
    const Instruction& product = definition(value);
    if (product.opcode != Opcode::Mul) {
      return {};
    }
    for (auto [factor, other] : {std::pair{product.operands[1], product.operands[0]},
                                 std::pair{product.operands[0], product.operands[1]}}) {
      std::optional<double> number = constantValue(output_, factor);
      if (number && std::signbit(*number) && !std::isnan(*number)) {
        return emitAs(instruction, Opcode::Mul, {other, constant(-*number)});
      }
    }
    return {};
  }

  // x * -1 is -x, bit for bit.
  ValueId simplifiedMultiply(const Instruction& instruction, ValueId left, ValueId right) {
    for (auto [value, other] : {std::pair{left, right}, std::pair{right, left}}) {
      if (isConstant(other, 1.0)) {
        return value;
      }
      if (isConstant(other, -1.0)) {
        return emitAs(instruction, Opcode::Neg, {value});
      }
      ValueFacts known = facts(value);
      if (isConstant(other, 0.0) && known.finite && known.nonNegative) {
        return constant(0.0);
      }
    }
    return {};
  }

  ValueId simplifiedSelect(const std::vector<ValueId>& operands) {
    std::optional<double> condition = constantValue(output_, operands[0]);
    if (condition) {
      return *condition != 0 ? operands[1] : operands[2];
    }
    return operands[1] == operands[2] ? operands[1] : ValueId{};
  }

  // Comparisons of a value with itself, and and/or with a constant.
  ValueId simplifiedLogic(Opcode opcode, const std::vector<ValueId>& operands) {
    if (operands.size() != 2) {
      return {};
    }
    bool same = operands[0] == operands[1];
    ValueFacts known = facts(operands[0]);
    bool notNaN = known.finite || known.nonNegative;
    switch (opcode) {
    case Opcode::Lt:
    case Opcode::Gt:
      return same ? constantBool(false) : ValueId{}; // false for NaN too
    case Opcode::Le:
    case Opcode::Ge:
    case Opcode::Eq:
      return same && notNaN ? constantBool(true) : ValueId{};
    case Opcode::Ne:
      return same && notNaN ? constantBool(false) : ValueId{};
    case Opcode::And:
    case Opcode::Or:
      return simplifiedAndOr(opcode == Opcode::And, operands[0], operands[1]);
    default:
      return {};
    }
  }

  // Bools are always 0 or 1, so `b and true` is b itself.
  ValueId simplifiedAndOr(bool isAnd, ValueId left, ValueId right) {
    if (left == right) {
      return left;
    }
    for (auto [value, other] : {std::pair{left, right}, std::pair{right, left}}) {
      std::optional<double> constant = constantValue(output_, other);
      if (constant) {
        bool absorbing = isAnd ? *constant == 0 : *constant != 0;
        return absorbing ? other : value;
      }
    }
    return {};
  }

  ValueFacts facts(ValueId value) {
    if (value.index >= known_.size()) {
      known_.resize(output_.valueTypes.size());
    }
    if (!known_[value.index]) {
      known_[value.index] = computeFacts(value);
    }
    return *known_[value.index];
  }

  ValueFacts computeFacts(ValueId value) {
    const Instruction& instruction = definition(value);
    switch (instruction.opcode) {
    case Opcode::Const:
      return factsOfNumber(instruction.number);
    case Opcode::Loop: // i runs from low up to a finite high
      return {true, facts(instruction.operands[0]).nonNegative};
    case Opcode::TableLoad:
      return tableFacts(instruction.index);
    case Opcode::Abs: {
      ValueFacts operand = facts(instruction.operands[0]);
      return {operand.finite, operand.finite || operand.nonNegative};
    }
    case Opcode::Floor:
    case Opcode::Ceil:
    case Opcode::Round:
      return facts(instruction.operands[0]);
    case Opcode::Min:
    case Opcode::Max:
      return both(facts(instruction.operands[0]), facts(instruction.operands[1]));
    case Opcode::Select:
      return both(facts(instruction.operands[1]), facts(instruction.operands[2]));
    default:
      return {};
    }
  }

  static ValueFacts both(ValueFacts a, ValueFacts b) {
    return {a.finite && b.finite, a.nonNegative && b.nonNegative};
  }

  ValueFacts tableFacts(std::uint32_t table) const {
    ValueFacts result{true, true};
    for (double entry : output_.tables[table]) {
      ValueFacts entryFacts = factsOfNumber(entry);
      result = both(result, entryFacts);
    }
    return result;
  }

  std::vector<std::optional<ValueFacts>> known_;
};

} // namespace

bool foldConstants(Function& function) {
  Folder folder(function);
  Function folded = folder.run();
  function = std::move(folded);
  return folder.changed();
}

} // namespace cncc::ir
