// method=nurbs on a target that prints NURBS blocks (LoweringOptions::
// nurbsBlocks: Fanuc and Mitsubishi G06.2), for a curve that reads
// parameters and for an offset the host computes (offset_cuts.cpp); a curve
// of constants is chords that ask for the blocks, made the block by the
// legalisation choose-curve-blocks. Each pass of the sweep's loop
// is a rapid over the block's first control point, a plunge and a curve.lap
// at the pass height whose entry asks for the block
// (CurveSampling::NurbsBlocks), which the legalisation write-curve-blocks
// writes out as one move.nurbs. A curve that
// is a NURBS of its own is its block: the lowering puts its data, control
// points on the printed grid, in a table the entry names, and its weights
// are operands of the lap, so a weight that is a part parameter stays its
// SSA value, the printer writes it as that parameter's variable (`R#3`) and
// the operator's edit reaches the curve. Any other curve's block is a cubic
// B-spline that write-curve-blocks fits within the tolerance less the
// rounding of the control points, on the grid (curve_blocks.h). Every other
// number of the curve is fixed at its default.
#include "part_lowering.h"

#include "cncc/geom/geometry_error.h"
#include "cncc/ir/nurbs_move.h"
#include "cncc/ir/printed_grid.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>
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

namespace {

// A NURBS's own block: its control points on the printed grid.
geom::NurbsCurve onGrid(const geom::NurbsCurve& own, double increment) {
  std::vector<Eigen::Vector3d> points = own.controlPoints();
  for (Eigen::Vector3d& point : points) {
    point = onPrintedGrid(point, increment);
  }
  return geom::NurbsCurve(own.knots(), std::move(points), own.weights());
}

} // namespace

// The blocks carry the host's control points and knots: every parameter
// they read is fixed, except a weight that is a parameter itself (R#n).
void PartLowering::fixNurbsBlockParameters(const CutStmt& cut) {
  const Expr* weights = curveArgument(cut, "weights");
  if (weights == nullptr || weights->kind != ExprKind::List) {
    fixParameters(*cut.curve, cut.curve->span, "this curve's points");
    return;
  }
  for (const Argument& argument : as<CallExpr>(*cut.curve).arguments) {
    if (argument.value && argument.value.get() != weights) {
      fixParameters(*argument.value, argument.value->span, "this curve's points");
    }
  }
  for (const ExprPtr& element : as<ListExpr>(*weights).elements) {
    std::optional<Lowered> weight = tryLower(*element, bindings_, environment_);
    bool direct = weight && weight->values.size() == 1 && !weight->values[0].isConstant() &&
                  builder_.function().definition(weight->values[0].value).opcode == Opcode::Param;
    if (!direct) {
      fixParameters(*element, element->span, "this curve's weights");
    }
  }
}

bool PartLowering::lowerNurbsCut(const CutStmt& cut, const CutCurve* given) {
  const Modifier* method = findModifier(cut, "method");
  std::string word = method != nullptr && method->value ? wordOf(*method->value) : "";
  if (!options_.nurbsBlocks || word != "nurbs" || rampEntry(cut)) {
    return false;
  }
  if (!safe_) {
    fail(cut.span, "this cut has no safe height; write 'safe z=Z' before it",
         DiagnosticKind::NoSafeHeight);
  }
  Scalar feed = cutFeed(cut);
  CutCurve curve = given != nullptr ? *given : cutCurve(cut);
  checkCutBounds(cut, *curve.geometry);
  std::vector<std::optional<ValueId>> parameters = parameterWeights(cut, curve);
  fixNurbsBlockParameters(cut);
  ToleranceBudget budget = blocksBudget(cut, "NURBS control points");
  CurveTableEntry entry =
      blocksTableEntry(cut, curve, CurveSampling::NurbsBlocks, std::nullopt, budget.forPoints());
  // A NURBS of its own is its block (its weights operands of the lap, a
  // parameter's its SSA value); any other curve's block is the cubic
  // B-spline write-curve-blocks fits, its weights its own.
  std::vector<ValueId> weights;
  // The block starts and ends at its first and last control points, on the
  // printed grid: a fitted B-spline's are where the curve starts and ends.
  auto [first, last] = curveEndsOnGrid(*curve.geometry, budget.increment);
  if (const auto* own = dynamic_cast<const geom::NurbsCurve*>(curve.geometry.get())) {
    geom::NurbsCurve blocks = onGrid(*own, budget.increment);
    first = blocks.controlPoints().front();
    last = blocks.controlPoints().back();
    for (std::size_t i = 0; i < blocks.controlPoints().size(); ++i) {
      bool parameter = i < parameters.size() && parameters[i];
      weights.push_back(
          parameter ? *parameters[i]
                    : builder_.constant(blocks.weights().empty() ? 1.0 : blocks.weights()[i]));
    }
    entry.blockTable = builder_.addTable(nurbsMoveTable(blocks));
  } else {
    entry.grid = budget.increment;
  }
  std::uint32_t lapTable = builder_.addCurve(std::move(entry));
  ValueId feedValue = arithmetic_.value(feed);
  ValueId safeValue = arithmetic_.value(*safe_);
  CutGeometry geometry;
  geometry.curve = curve.geometry;
  geometry.tolerance = chordTolerance(cut).value_or(std::numeric_limits<double>::quiet_NaN());
  geometry.span = cut.span;
  bool activatesLengthOffset = beginCutMoves(geometry);
  // The passes (the controller's loop: depth= and step= stay editable), each
  // a rapid over the block's first control point, the plunge and the lap at
  // the pass height, which write-curve-blocks writes out as the block
  // (move.nurbs) with its weights.
  ValueId firstX = builder_.constant(first.x());
  ValueId firstY = builder_.constant(first.y());
  emitSweep(cut, false, {firstX, firstY, safeValue, activatesLengthOffset, Scalar::of(first.z())},
            {builder_.constant(last.x()), builder_.constant(last.y())}, feedValue,
            [&](ValueId zFrom, ValueId zTo) {
              std::vector<ValueId> operands = {zFrom, zTo, feedValue};
              operands.insert(operands.end(), weights.begin(), weights.end());
              if (curve.beside) {
                emitBesideLapAt(*curve.beside, lapTable, std::move(operands), cut);
              } else {
                emitCurveLapAt(curve, lapTable, std::move(operands), curvePointOf(curve, cut));
              }
            });
  return true;
}

} // namespace cncc::ir::lowering
