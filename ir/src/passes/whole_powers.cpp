// `expand-whole-powers`: a ^ n with a whole constant n as multiplications
// (1 / the product for a negative n, 1 for n = 0), and a ^ (n + 1/2) as
// that product times sqrt(a), for the macro targets.
//
// Why: a controller without a power function computes a ^ b as
// EXP[LN[a]*b] (Fanuc, Mitsubishi), which stops with an alarm for any a <= 0
// (the parabola y = t^2 over t = -5 .. 5 halts at its first negative t),
// and a power function or operator may refuse a negative base too. a ^ n
// for a whole n is defined for every a (0 ^ n is 0 for n > 0), and its
// multiplications are what every controller computes; a ^ 1.5 is defined
// from a = 0 on, where the host's pow gives 0 and LN[0] would stop the
// program (t ^ 1.5 from t = 0), and SQRT[a] is defined there too. The
// product differs from the host's pow by rounding in the last bits, so this
// is a target's pass (passes.h, Pass::exact), run with fold-finite before
// printing. A power of a larger or other fractional exponent, or one the
// program computes, stays as it is.
#include "cncc/ir/passes.h"

#include "rewriter.h"

#include <cmath>
#include <cstdint>
#include <optional>

namespace cncc::ir {

namespace {

class WholePowerExpander : public passes::Rewriter {
public:
  using Rewriter::Rewriter;

private:
  void visit(const Instruction& instruction) override {
    std::optional<double> exponent = instruction.opcode == Opcode::Pow
                                         ? passes::constantValue(source_, instruction.operands[1])
                                         : std::nullopt;
    // Whole or half: twice the exponent is whole.
    if (!exponent || std::trunc(2 * *exponent) != 2 * *exponent ||
        !(std::abs(*exponent) <= largestExpandedExponent)) {
      copy(instruction);
      return;
    }
    ValueId base = mapped(instruction.operands[0]);
    double magnitude = std::abs(*exponent);
    auto whole = static_cast<std::uint32_t>(std::trunc(magnitude));
    ValueId power = whole == 0 ? ValueId{} : product(instruction, base, whole);
    if (magnitude != whole) {
      ValueId root = emitAs(instruction, Opcode::Sqrt, {base});
      power = power.valid() ? emitAs(instruction, Opcode::Mul, {power, root}) : root;
    }
    if (!power.valid()) {
      power = constant(1);
    }
    if (*exponent < 0) {
      ValueId one = constant(1);
      power = emitAs(instruction, Opcode::Div, {one, power});
    }
    replace(instruction.result, power);
    markChanged();
  }

  // base ^ exponent (exponent >= 1) by repeated squaring, the factors
  // multiplied lowest first.
  ValueId product(const Instruction& instruction, ValueId base, std::uint32_t exponent) {
    ValueId result;
    ValueId square = base;
    while (true) {
      if ((exponent & 1U) != 0) {
        result = result.valid() ? emitAs(instruction, Opcode::Mul, {result, square}) : square;
      }
      exponent >>= 1U;
      if (exponent == 0) {
        return result;
      }
      square = emitAs(instruction, Opcode::Mul, {square, square});
    }
  }
};

} // namespace

bool expandWholePowers(Function& function) {
  WholePowerExpander expander(function);
  Function expanded = expander.run();
  function = std::move(expanded);
  return expander.changed();
}

} // namespace cncc::ir
