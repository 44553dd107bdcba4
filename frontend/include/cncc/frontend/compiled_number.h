// A number expression of one variable (a polar curve's r(t), a parametric
// curve's x(t)) compiled to a flat list of operations, for the millions of
// points a chord walk asks of a curve: interpreting the tree at each point
// (an environment to bind the variable in, a visit per node) cost several
// times the rest of the walk.
#pragma once

#include "cncc/frontend/ast.h"
#include "cncc/frontend/sema.h"
#include "cncc/frontend/value.h"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace cncc::frontend {

// What ExpressionEvaluator::evaluate computes for the expression, to the
// bit: the same arithmetic as the evaluator's number fast path, node for
// node. Names other than the variable (part parameters, lets, constants)
// are read once, when compiling; fn calls are inlined; what does not
// depend on the variable is computed once.
class CompiledNumber {
public:
  // The most operations (and fn calls deep) a compiled expression has;
  // larger ones are evaluated the ordinary way.
  static constexpr std::size_t maximumOperations = 512;
  static constexpr int maximumCallDepth = 16;

  // Nullopt where the fast path would not evaluate the expression to a
  // number at any value of the variable (an if, a list, a name bound to
  // something else than a number, a part not finite whatever the
  // variable), and where it is larger than the limits above: the caller
  // evaluates it the ordinary way. `environment` binds the other names, as
  // ExpressionEvaluator::evaluate would be given it.
  static std::optional<CompiledNumber>
  compile(const Expr& expression, const Environment& environment, const Declaration* variable);

  // The value with the variable bound to `x`. False where the fast path
  // gives up (a value that is not finite, a division by zero): the ordinary
  // evaluation then gives the value, or the error it reports.
  bool evaluate(double x, double& result) const;

  std::size_t operationCount() const { return operations_.size(); }

private:
  // An operand: a value computed once (constants_[index]), or the result of
  // operations_[index] (the variable is an operation).
  struct Operand {
    bool constant = true;
    std::uint16_t index = 0;
  };
  enum class Code : std::uint8_t { Variable, Negate, Add, Subtract, Multiply, Divide, Call };
  struct Operation {
    Code code = Code::Variable;
    Operand left;
    Operand right;
    // Code::Call: the math function (a second operand unused for one
    // argument); also `%` and `^`, which compute as the functions rem and
    // pow. `checkDivisor` for / and %.
    double (*function)(double, double) = nullptr;
    bool checkDivisor = false;
  };
  friend class NumberCompiler;

  std::vector<double> constants_;
  std::vector<Operation> operations_;
  Operand result_;
};

} // namespace cncc::frontend
