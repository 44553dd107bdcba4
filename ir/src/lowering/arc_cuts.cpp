// Arcs on a controller-side target (LoweringOptions::arcBlocks: the macro
// targets and LinuxCNC). A cut that wants arcs (arcs=true, or --arcs without
// arcs=false) is lowered like a method=nurbs cut: each pass is a rapid over
// the start, a plunge, a `comment "ARCS"` and one feed to the curve's end,
// which the printer replaces by the G02/G03 blocks it fits to the cut's
// curve (CutGeometry::curve) within the tolerance. The arcs are the host's,
// so a cut whose geometry depends on a part parameter keeps its controller
// loops, with an arcs-as-chords warning saying why.
#include "lowering/part_lowering.h"

#include "cncc/geom/arc_fitting.h"

#include <fmt/format.h>

namespace cncc::ir::lowering {

using namespace frontend;

namespace {

std::optional<bool> arcsModifier(const CutStmt& cut) {
  const Expr* arcs = modifierValue(cut, "arcs");
  if (arcs != nullptr && arcs->kind == ExprKind::Bool) {
    return as<BoolExpr>(*arcs).value;
  }
  return std::nullopt;
}

} // namespace

// Why the cut cannot be printed as host-fitted arcs, before its curve is
// built; nullopt when nothing stands in the way.
std::optional<std::string> PartLowering::arcCutProblem(const CutStmt& cut) {
  if (modifierValue(cut, "samples") != nullptr || modifierValue(cut, "spacing") != nullptr) {
    return "samples= or spacing= chose its points; arcs are fitted within a tolerance=";
  }
  if (rampEntry(cut)) {
    return "its entry=ramp laps are computed on the controller";
  }
  std::pair<const char*, const Expr*> uses[] = {{"curve", cut.curve.get()},
                                                {"depth", modifierValue(cut, "depth")},
                                                {"step", modifierValue(cut, "step")}};
  for (const auto& [what, expression] : uses) {
    if (expression == nullptr) {
      continue;
    }
    std::set<std::string> parameters = parametersOf(*expression);
    unrollForLoopVariables(parameters); // unrolled, each copy's arcs are fitted
    if (!parameters.empty()) {
      return fmt::format("its {} depends on parameter '{}'", what, *parameters.begin());
    }
  }
  return std::nullopt;
}

bool PartLowering::lowerArcCut(const CutStmt& cut, const CutCurve& curve) {
  if (!options_.arcBlocks || !arcsModifier(cut).value_or(options_.arcsOnEveryCut)) {
    return false;
  }
  std::optional<std::string> problem = arcCutProblem(cut);
  if (!problem) {
    problem = geom::findArcFittingProblem(*curve.geometry);
  }
  if (problem) {
    diagnostics_->report(DiagnosticKind::ArcsAsChords, cut.span,
                         fmt::format("this cut is printed as G01 chords, not arcs: {}", *problem));
    return false;
  }
  if (!safe_) {
    fail(cut.span, "this cut has no safe height; write 'safe z=Z' before it",
         DiagnosticKind::NoSafeHeight);
  }
  checkMethod(cut);
  Scalar feed = cutFeed(cut);
  ValueId feedValue = arithmetic_.value(feed);
  ValueId safeValue = arithmetic_.value(*safe_);
  auto index = static_cast<std::uint32_t>(cuts_.size());
  cuts_.push_back(
      {curve.geometry, *chordTolerance(cut), cut.span, arcsModifier(cut), methodOf(cut)});
  builder_.cutBegin(index);

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
    builder_.comment("ARCS");
    ValueId endX = builder_.constant(end.x());
    ValueId endY = builder_.constant(end.y());
    builder_.feed(endX, endY, builder_.constant(z + end.z()), feedValue);
    builder_.rapid(endX, endY, safeValue);
  }
  return true;
}

} // namespace cncc::ir::lowering
