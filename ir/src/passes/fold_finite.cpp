// `fold-finite`: constant folding and the identities x + 0, x - 0, x * 1,
// x / 1 and x * 0 as they are on finite numbers, for a program that runs on
// a controller which alarms where a value is not finite.
//
// Why it is not `fold`: `fold` keeps the interpreter's tool path to the bit
// for every input, NaN, the infinities and signed zeros included, so it
// leaves x + 0 (x may be -0) and x * 0 (x may be infinite) to run time. A
// macro controller (Fanuc, Mitsubishi, LinuxCNC, Heidenhain) has no NaN, no
// infinity and no -0: a division by zero or the root of a negative number
// stops the program with an alarm. On its values these identities hold, and
// a value the host could not fold (1/0) is left to the controller, which
// alarms where the host would have failed. So the pass is for those
// targets only, after the optimiser (passes.h, Pass::exact).
//
// A number within 1e-12 of 0 or 1 is taken as it: sin(2 pi) is -2.4e-16,
// and 0.9999999999999999 is 1, far below any digit a controller reads (so
// a comparison with such a number may go the other way).
// Parameters are never constants (their values come at run time), so
// nothing is folded through `param`; x * 0 is 0 for a parameter x all the
// same, since a controller's x is finite.
#include "cncc/ir/passes.h"

#include "rewriter.h"

#include "cncc/ir/arithmetic.h"

#include <cmath>
#include <optional>

namespace cncc::ir {

namespace {

// Below any printed digit: a number this close to another is taken as it.
constexpr double negligible = 1e-12;

class FiniteFolder : public passes::Rewriter {
public:
  using Rewriter::Rewriter;

private:
  void visit(const Instruction& instruction) override {
    if (!foldable(instruction)) {
      copy(instruction);
      return;
    }
    std::vector<ValueId> operands = mappedOperands(instruction);
    if (std::optional<double> folded = foldedNumber(instruction.opcode, operands)) {
      foldTo(instruction, *folded);
      return;
    }
    ValueId same = identity(instruction, operands);
    if (same.valid()) {
      replace(instruction.result, same);
      markChanged();
      return;
    }
    replace(instruction.result, emit(instruction, std::move(operands)));
  }

  // A number-valued operation of one or two operands (a comparison, whose
  // result is a bool, stays as it is; so do loops and ifs).
  static bool foldable(const Instruction& instruction) {
    return instruction.regions.empty() && isPure(instruction.opcode) &&
           opcodeInfo(instruction.opcode).result == ValueType::F64 &&
           (instruction.operands.size() == 1 || instruction.operands.size() == 2);
  }

  // A const's number, within `negligible` of 0 taken as 0; a const.bool or
  // any other operation is not a known number here.
  std::optional<double> known(ValueId value) const {
    const Instruction& definition = output_.definition(value);
    if (definition.opcode != Opcode::Const) {
      return std::nullopt;
    }
    return std::abs(definition.number) < negligible ? 0 : definition.number;
  }

  bool isNumber(ValueId value, double number) const {
    std::optional<double> knownNumber = known(value);
    return knownNumber && std::abs(*knownNumber - number) < negligible;
  }

  // The operation on its known operands, by the IR's own arithmetic.
  std::optional<double> foldedNumber(Opcode opcode, const std::vector<ValueId>& operands) const {
    std::optional<double> first = known(operands[0]);
    if (!first) {
      return std::nullopt;
    }
    if (operands.size() == 1) {
      return unaryResult(opcode, *first);
    }
    std::optional<double> second = known(operands[1]);
    return second ? binaryResult(opcode, *first, *second) : std::nullopt;
  }

  // A result that is not finite stays an operation: the controller alarms
  // on it where the host would fail.
  void foldTo(const Instruction& instruction, double number) {
    if (!std::isfinite(number)) {
      replace(instruction.result, emit(instruction, mappedOperands(instruction)));
      return;
    }
    replace(instruction.result, constant(std::abs(number) < negligible ? 0 : number));
    markChanged();
  }

  // x+0, 0+x, x-0, x*1, 1*x and x/1 are x; x*0 and 0*x are a new 0; 0-x
  // is a new -x.
  ValueId identity(const Instruction& instruction, const std::vector<ValueId>& operands) {
    if (operands.size() != 2) {
      return {};
    }
    ValueId left = operands[0];
    ValueId right = operands[1];
    switch (instruction.opcode) {
    case Opcode::Add:
      return isNumber(left, 0) ? right : isNumber(right, 0) ? left : ValueId{};
    case Opcode::Sub:
      if (isNumber(left, 0)) {
        return emitAs(instruction, Opcode::Neg, {right});
      }
      return isNumber(right, 0) ? left : ValueId{};
    case Opcode::Mul:
      if (isNumber(left, 0) || isNumber(right, 0)) {
        return constant(0);
      }
      return isNumber(left, 1) ? right : isNumber(right, 1) ? left : ValueId{};
    case Opcode::Div:
      return isNumber(right, 1) ? left : ValueId{};
    default:
      return {};
    }
  }
};

} // namespace

bool foldAssumingFinite(Function& function) {
  FiniteFolder folder(function);
  Function folded = folder.run();
  function = std::move(folded);
  return folder.changed();
}

} // namespace cncc::ir
