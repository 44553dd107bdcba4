// The derivative of IR values with respect to one of them (a loop's index,
// a curve's parameter), written as more IR: the rules of differentiation
// applied to each instruction on the way from the variable to the value
// (forward mode), each instruction's derivative computed once. The
// controller then computes a point and its tangent from the same
// arithmetic, as a cut beside its curve needs for the normal.
#pragma once

#include "part_lowering.h"

#include <map>
#include <optional>

namespace cncc::ir::lowering {

// Whether an IR value is computed from `variable` (memoised walk of the
// instructions that define its operands).
class ValueDependence {
public:
  ValueDependence(const Function& function, ValueId variable)
      : function_(function), variable_(variable) {}
  bool operator()(ValueId value);

private:
  const Function& function_;
  ValueId variable_;
  std::map<std::uint32_t, bool> varying_;
};

class ForwardDerivative {
public:
  ForwardDerivative(FunctionBuilder& builder, Arithmetic& math, ValueId variable)
      : builder_(builder), math_(math), variable_(variable), varies_(builder.function(), variable) {
  }

  // d value / d variable; nullopt where an instruction on the way has no
  // rule here (a table read at an index that varies, a comparison).
  std::optional<Scalar> of(Scalar value);

private:
  std::optional<Scalar> rule(const Instruction& instruction,
                             const std::vector<Scalar>& operandDerivatives);

  FunctionBuilder& builder_;
  Arithmetic& math_;
  ValueId variable_;
  ValueDependence varies_;
  std::map<std::uint32_t, std::optional<Scalar>> derivatives_;
};

} // namespace cncc::ir::lowering
