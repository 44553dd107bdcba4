// Evaluates macro expressions as Custom Macro B does: angles in degrees,
// vacant values that count as 0 in arithmetic and stay distinct from 0 in
// EQ and NE, FIX toward zero, FUP away from zero, ROUND half away from zero.
#pragma once

#include "cncc/backends/sim_program.h"

namespace cncc::backends::sim {

struct Value {
  double number = 0;
  bool vacant = true;

  static Value of(double number) { return {number, false}; }
  static Value vacantValue() { return {}; }
};

class VariableReader {
public:
  virtual Value read(int variable, const Block& block) const = 0;

protected:
  ~VariableReader() = default;
};

// The value of `expression`; errors (division by zero, a function outside
// its domain, an overflow) name `block`.
Value evaluate(const Expression& expression, const VariableReader& variables, const Block& block);
// The variable a `#` refers to: a whole number, at least 0.
int evaluateVariableNumber(const Expression& expression, const VariableReader& variables,
                           const Block& block);
// A whole number: a sequence number, a program number, a repeat count.
int evaluateWholeNumber(const Expression& expression, const VariableReader& variables,
                        const Block& block, std::string_view what);

[[noreturn]] void failInBlock(const Block& block, const std::string& message);

} // namespace cncc::backends::sim
