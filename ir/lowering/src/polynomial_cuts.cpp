// A spline cut (method=cspline, aspline, bspline or nurbs) on a target
// with polynomial span blocks (LoweringOptions::polynomialBlocks: the
// Heidenhain TNC's SPL). The cut's curve becomes cubic spans: exactly, one
// per knot span, when it is a non-rational NURBS of degree 3 or less;
// otherwise (a rational NURBS, any other curve) from a cubic B-spline fitted
// within the tolerance less the rounding of the end points. Each end point
// is put on the printed grid and each span made to start exactly where the
// one before ends (polynomial_move.h). A transition that turns by more than
// the TNC's 0.1 degree, where the control stops exactly, is a warning
// naming how many there are. The spans are a table of the function; each
// pass is a rapid over the start, a plunge, and a curve.lap at the pass
// height whose entry names the table (CurveSampling::PolynomialBlocks),
// which the legalisation write-curve-blocks writes out as one
// move.polynomial per span.
#include "part_lowering.h"

#include "cncc/geom/bspline_fitting.h"
#include "cncc/geom/evaluation_budget.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/ir/polynomial_move.h"
#include "cncc/ir/printed_grid.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

namespace cncc::ir::lowering {

using namespace frontend;

namespace {

// The TNC stops exactly where consecutive spline blocks turn by more.
constexpr double smoothTransitionDegrees = 0.1;

bool nonRationalCubic(const geom::Curve& curve) {
  const auto* nurbs = dynamic_cast<const geom::NurbsCurve*>(&curve);
  if (nurbs == nullptr || nurbs->degree() > 3) {
    return false;
  }
  const std::vector<double>& weights = nurbs->weights();
  return std::all_of(weights.begin(), weights.end(),
                     [&](double weight) { return weight == weights.front(); });
}

} // namespace

std::vector<PolynomialMove> PartLowering::polynomialSpans(const CutStmt& cut,
                                                          const CutCurve& curve) {
  ToleranceBudget budget = toleranceBudget(cut);
  if (std::isnan(budget.tolerance)) { // samples= or spacing=: the default tolerance
    budget.tolerance = options_.defaultTolerance;
  }
  double rounding = budget.pointRounding();
  if (!(budget.tolerance > 2 * rounding)) {
    const Expr* written = modifierValue(cut, "tolerance");
    fail(written != nullptr ? written->span : cut.span,
         fmt::format("the tolerance {:g} leaves no room for the controller's rounding of the "
                     "spline end points ({:.6g})",
                     budget.tolerance, rounding),
         DiagnosticKind::InvalidTolerance);
  }
  std::vector<PolynomialMove> spans;
  try {
    if (nonRationalCubic(*curve.geometry)) {
      spans = polynomialMoves(dynamic_cast<const geom::NurbsCurve&>(*curve.geometry));
    } else {
      geom::BSplineFitOptions fit;
      fit.degree = 3;
      fit.tolerance = budget.forPoints();
      // A fit asks derivatives too, each some ten points' work.
      geom::BudgetedCurve budgeted(*curve.geometry, maximumCurveEvaluations / 8);
      spans = polynomialMoves(geom::fitBSpline(budgeted, fit).spline);
    }
  } catch (const geom::GeometryError& error) {
    fail(cut.span,
         fmt::format("no cubic spans follow this curve within {:g} for the spline blocks: {}",
                     budget.forPoints(), error.what()),
         DiagnosticKind::InvalidTolerance);
  }
  Eigen::Vector3d start = onPrintedGrid(spans.front().start(), budget.increment);
  for (PolynomialMove& span : spans) {
    span.end = onPrintedGrid(span.end, budget.increment);
    span.startAt(start);
    start = span.end;
  }
  return spans;
}

void PartLowering::reportSplineCorners(const CutStmt& cut,
                                       const std::vector<PolynomialMove>& spans) {
  int corners = 0;
  double largest = 0;
  for (std::size_t i = 1; i < spans.size(); ++i) {
    double turn = polynomialTransitionDegrees(spans[i - 1], spans[i]);
    if (turn > smoothTransitionDegrees) {
      ++corners;
      largest = std::max(largest, turn);
    }
  }
  if (corners > 0) {
    diagnostics_->report(DiagnosticKind::SplineExactStop, cut.span,
                         fmt::format("{} of this curve's spline transitions turn by more than "
                                     "{} degrees (the largest {:.3g}): the control stops "
                                     "exactly there",
                                     corners, smoothTransitionDegrees, largest));
  }
}

// A move.polynomial per span at height z.
void PartLowering::emitPolynomialMoves(const std::vector<PolynomialMove>& spans, double z,
                                       ValueId feed) {
  for (const PolynomialMove& span : spans) {
    std::vector<ValueId> operands{builder_.constant(span.end.x()), builder_.constant(span.end.y()),
                                  builder_.constant(z + span.end.z())};
    for (int axis = 0; axis < 3; ++axis) {
      for (const Eigen::Vector3d& coefficient : span.coefficients) {
        operands.push_back(builder_.constant(coefficient[axis]));
      }
    }
    operands.push_back(feed);
    builder_.operation(Opcode::Polynomial, std::move(operands));
  }
}

bool PartLowering::lowerPolynomialCut(const CutStmt& cut, const CutCurve* given) {
  const Modifier* method = findModifier(cut, "method");
  std::string word = method != nullptr && method->value ? wordOf(*method->value) : "";
  bool spline = word == "cspline" || word == "aspline" || word == "bspline" || word == "nurbs";
  if (!options_.polynomialBlocks || !spline || rampEntry(cut)) {
    return false;
  }
  if (!safe_) {
    fail(cut.span, "this cut has no safe height; write 'safe z=Z' before it",
         DiagnosticKind::NoSafeHeight);
  }
  Scalar feed = cutFeed(cut);
  CutCurve curve = given != nullptr ? *given : cutCurve(cut);
  fixParameters(*cut.curve, cut.curve->span, "this curve's points");
  std::vector<PolynomialMove> spans = polynomialSpans(cut, curve);
  reportSplineCorners(cut, spans);
  ValueId feedValue = arithmetic_.value(feed);
  ValueId safeValue = arithmetic_.value(*safe_);
  CutGeometry geometry;
  geometry.curve = curve.geometry;
  geometry.tolerance = chordTolerance(cut).value_or(std::numeric_limits<double>::quiet_NaN());
  geometry.span = cut.span;
  geometry.method = word;
  beginCutMoves(geometry);

  // A curve beside the cut's (an offset) computed otherwise than its laps
  // follow has no regions: its spans are the moves themselves.
  std::optional<std::uint32_t> spansTable;
  if (!curve.pieces.empty() || curve.beside) {
    std::uint32_t table = builder_.addTable(polynomialMoveTable(spans));
    spansTable = builder_.addCurve(blocksTableEntry(cut, curve, CurveSampling::PolynomialBlocks,
                                                    table, toleranceBudget(cut).forPoints()));
  }
  Eigen::Vector3d first = spans.front().start();
  std::vector<double> depths = passDepths(cut);
  for (std::size_t k = 0; k < depths.size(); ++k) {
    PassScope pass(builder_, sweepPass(k, depths.size()));
    double z = beginPass(depths[k], depths.size());
    approachPassStart(first, z, safeValue, feedValue);
    if (spansTable) {
      // The lap at the pass height, which write-curve-blocks writes out as
      // a move.polynomial per span.
      emitCurveLap(curve, *spansTable, z, z, feedValue, cut);
    } else {
      emitPolynomialMoves(spans, z, feedValue);
    }
    const Eigen::Vector3d& last = spans.back().end;
    builder_.rapid(builder_.constant(last.x()), builder_.constant(last.y()), safeValue);
  }
  return true;
}

} // namespace cncc::ir::lowering
