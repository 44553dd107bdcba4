// The weights of a nurbs(...) cut that are part parameters: a G06.2 block
// keeps such a weight the parameter's variable (`R#3`), so the operator's
// edit reaches the curve; the laps of a cut asking for blocks say which
// (CurveTableEntry::parameterWeights, read by choose-curve-blocks and
// write-curve-blocks). A weight whose parameter the points or knots read
// too is fixed with them.
#include "part_lowering.h"

#include <set>
#include <string>

namespace cncc::ir::lowering {

using namespace frontend;

// Per weight of a nurbs(...) cut, the part parameter it is (its value), or
// nullopt for a number.
std::vector<std::optional<ValueId>> PartLowering::parameterWeights(const CutStmt& cut,
                                                                   const CutCurve& curve) {
  std::vector<std::optional<ValueId>> weights;
  const Expr* expression = curveArgument(cut, "weights");
  if (expression == nullptr || curve.pieces.size() != 1) {
    return weights;
  }
  std::optional<std::vector<std::optional<Lowered>>> lowered = symbolicList(*expression);
  if (!lowered) {
    return weights;
  }
  for (const std::optional<Lowered>& weight : *lowered) {
    bool parameter =
        weight && weight->values.size() == 1 && !weight->values[0].isConstant() &&
        builder_.function().definition(weight->values[0].value).opcode == Opcode::Param;
    weights.push_back(parameter ? std::optional<ValueId>(weight->values[0].value) : std::nullopt);
  }
  return weights;
}

std::vector<CurveTableEntry::ParameterWeight>
PartLowering::ownWeightParameters(const CutStmt& cut, const CutCurve& curve) {
  std::vector<CurveTableEntry::ParameterWeight> parameters;
  std::vector<std::optional<ValueId>> weights = parameterWeights(cut, curve);
  if (weights.empty()) {
    return parameters; // no nurbs(...) of its own with a list of weights
  }
  const Expr* list = curveArgument(cut, "weights");
  std::set<std::string> elsewhere; // what the points and knots read
  for (const Argument& argument : as<CallExpr>(*cut.curve).arguments) {
    if (argument.value && argument.value.get() != list) {
      std::set<std::string> read = parametersOf(*argument.value);
      elsewhere.insert(read.begin(), read.end());
    }
  }
  const Function& function = builder_.function();
  for (std::size_t k = 0; k < weights.size(); ++k) {
    if (!weights[k]) {
      continue;
    }
    std::uint32_t index = function.definition(*weights[k]).index;
    if (!elsewhere.contains(function.parameters[index].name)) {
      parameters.push_back({k, index});
    }
  }
  return parameters;
}

} // namespace cncc::ir::lowering
