// method=nurbs on a target that prints NURBS blocks (LoweringOptions::
// nurbsBlocks: Fanuc and Mitsubishi G06.2). Each pass is a rapid over the
// start, a plunge, a `comment "NURBS"` and one feed to the curve's end; the
// printer replaces that feed by the G06.2 blocks of the cut's curve
// (CutGeometry::curve, fitted within the tolerance when it is not a NURBS),
// at the feed's height and rate. The curve is the host's, evaluated with the
// parameters' values at compile time.
#include "lowering/part_lowering.h"

#include <fmt/format.h>

#include <limits>

namespace cncc::ir::lowering {

using namespace frontend;

// "NURBS R5=P2" for each weight of a nurbs(...) cut that is a part
// parameter (control point 5, parameter 2): the printer writes it as that
// parameter's variable (`R#3`), so the operator's edit reaches the curve.
std::vector<std::string> PartLowering::parameterWeights(const CutStmt& cut, const CutCurve& curve) {
  std::vector<std::string> notes;
  const Expr* expression = curveArgument(cut, "weights");
  if (expression == nullptr || curve.pieces.size() != 1) {
    return notes;
  }
  std::optional<std::vector<std::optional<Lowered>>> weights = symbolicList(*expression);
  if (!weights) {
    return notes;
  }
  for (std::size_t i = 0; i < weights->size(); ++i) {
    const std::optional<Lowered>& weight = (*weights)[i];
    if (!weight || weight->values.size() != 1 || weight->values[0].isConstant()) {
      continue;
    }
    const Instruction& definition = builder_.function().definition(weight->values[0].value);
    if (definition.opcode == Opcode::Param) {
      notes.push_back(fmt::format("NURBS R{}=P{}", i, definition.index));
    }
  }
  return notes;
}

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

bool PartLowering::lowerNurbsCut(const CutStmt& cut) {
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
  CutCurve curve = cutCurve(cut);
  ValueId feedValue = arithmetic_.value(feed);
  ValueId safeValue = arithmetic_.value(*safe_);
  auto index = static_cast<std::uint32_t>(cuts_.size());
  CutGeometry geometry;
  geometry.curve = curve.geometry;
  geometry.tolerance = chordTolerance(cut).value_or(std::numeric_limits<double>::quiet_NaN());
  geometry.span = cut.span;
  cuts_.push_back(geometry);
  builder_.cutBegin(index);

  std::vector<std::string> weightNotes = parameterWeights(cut, curve);
  fixNurbsBlockParameters(cut);
  geom::ParameterRange domain = curve.geometry->domain();
  Eigen::Vector3d start = curve.geometry->point(domain.t0);
  Eigen::Vector3d end = curve.geometry->point(domain.t1);
  std::vector<double> depths = passDepths(cut);
  for (double depth : depths) {
    builder_.comment(depths.size() > 1 ? fmt::format("pass at depth {}", depth) : "cut");
    double z = depth == 0 ? 0.0 : -depth;
    ValueId startX = builder_.constant(start.x());
    ValueId startY = builder_.constant(start.y());
    builder_.rapid(startX, startY, safeValue);
    builder_.feed(startX, startY, builder_.constant(z + start.z()), feedValue);
    for (const std::string& note : weightNotes) {
      builder_.comment(note);
    }
    builder_.comment("NURBS");
    ValueId endX = builder_.constant(end.x());
    ValueId endY = builder_.constant(end.y());
    builder_.feed(endX, endY, builder_.constant(z + end.z()), feedValue);
    builder_.rapid(endX, endY, safeValue);
  }
  return true;
}

} // namespace cncc::ir::lowering
