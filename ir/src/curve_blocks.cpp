#include "cncc/ir/curve_blocks.h"

#include "cncc/geom/bspline_fitting.h"
#include "cncc/geom/discretisation.h"
#include "cncc/geom/evaluation_budget.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/ir/curve_lap.h"
#include "cncc/ir/nurbs_move.h"
#include "cncc/ir/printed_grid.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace cncc::ir {

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

// A clamped cubic B-spline within `tolerance`, its ends the curve's; the
// search asks a bounded number of points of the curve (a fit asks
// derivatives too, each some ten points' work), past which it throws
// geom::EvaluationBudgetExceeded.
geom::NurbsCurve fittedCubic(const geom::Curve& curve, double tolerance) {
  // The fit measures the curve at least as densely as chords within the
  // tolerance: a curve whose chords are well past the budget is refused at
  // once, not after the budget's seconds.
  constexpr std::size_t budget = maximumCurveEvaluations / 8;
  if (geom::estimateDiscretisation(curve, tolerance).chords > 2.0 * static_cast<double>(budget)) {
    throw geom::EvaluationBudgetExceeded(budget);
  }
  geom::BudgetedCurve budgeted(curve, budget);
  geom::BSplineFitOptions fit;
  fit.degree = 3;
  fit.tolerance = tolerance;
  return geom::fitBSpline(budgeted, fit).spline;
}

// The XY direction of the last chord through `points`, on the printed grid.
std::optional<Eigen::Vector3d> lastChordDirection(const std::vector<Eigen::Vector3d>& points,
                                                  double grid) {
  std::size_t n = points.size();
  if (n < 2) {
    return std::nullopt;
  }
  Eigen::Vector3d direction =
      onPrintedGrid(points[n - 1], grid) - onPrintedGrid(points[n - 2], grid);
  direction.z() = 0;
  return direction.norm() > 1e-9 ? std::optional<Eigen::Vector3d>(direction) : std::nullopt;
}

// How an A or C spline starts and ends; `arrival` the XY direction of the
// ramp's last chord, as printed, if the spline follows a ramp.
geom::SplineTransitions splineTransitions(SplineEnds ends,
                                          const std::optional<Eigen::Vector3d>& arrival) {
  geom::SplineTransitions transitions;
  switch (ends) {
  case SplineEnds::Automatic:
    transitions.start =
        arrival ? geom::SplineEndCondition::Tangent : geom::SplineEndCondition::Natural;
    transitions.startDirection = arrival;
    transitions.end = geom::SplineEndCondition::Natural;
    break;
  case SplineEnds::Natural:
    transitions.start = transitions.end = geom::SplineEndCondition::Natural;
    break;
  case SplineEnds::Auto:
    transitions.start = transitions.end = geom::SplineEndCondition::Auto;
    break;
  }
  return transitions;
}

std::string_view splineKindName(SplineKind kind) {
  switch (kind) {
  case SplineKind::CSpline:
    return "CSPLINE";
  case SplineKind::ASpline:
    return "ASPLINE";
  case SplineKind::BSpline:
    break;
  }
  return "BSPLINE";
}

} // namespace

std::optional<SplineKind> splineKindOfMethod(std::string_view method) {
  if (method == "bspline" || method == "nurbs") {
    return SplineKind::BSpline;
  }
  if (method == "cspline") {
    return SplineKind::CSpline;
  }
  if (method == "aspline") {
    return SplineKind::ASpline;
  }
  return std::nullopt;
}

bool liesInPlane(const geom::Curve& curve) {
  constexpr double sameZ = 1e-9;
  constexpr int probes = 16;
  geom::ParameterRange domain = curve.domain();
  double z = curve.point(domain.t0).z();
  for (int k = 1; k <= probes; ++k) {
    double t = domain.t0 + domain.length() * k / probes;
    if (std::abs(curve.point(t).z() - z) > sameZ) {
      return false;
    }
  }
  return true;
}

std::vector<PolynomialMove> lapPolynomialSpans(const CurveTableEntry& entry,
                                               const geom::Curve& curve) {
  std::vector<PolynomialMove> spans;
  try {
    if (nonRationalCubic(curve)) {
      spans = polynomialMoves(dynamic_cast<const geom::NurbsCurve&>(curve));
    } else {
      spans = polynomialMoves(fittedCubic(curve, entry.amount));
    }
  } catch (const geom::GeometryError& error) {
    throw CurveLapError(
        CurveLapError::Kind::InvalidTolerance, entry.cutSpan,
        fmt::format("no cubic spans follow this curve within {:g} for the spline blocks: {}",
                    entry.amount, error.what()));
  }
  Eigen::Vector3d start = onPrintedGrid(spans.front().start(), entry.grid);
  for (PolynomialMove& span : spans) {
    span.end = onPrintedGrid(span.end, entry.grid);
    span.startAt(start);
    start = span.end;
  }
  return spans;
}

FittedNurbsBlock lapFittedNurbs(const CurveTableEntry& entry, const geom::Curve& curve) {
  // A NURBS of its own is its block; any other curve a cubic B-spline.
  const auto* own = dynamic_cast<const geom::NurbsCurve*>(&curve);
  std::optional<geom::NurbsCurve> nurbs;
  try {
    nurbs = own != nullptr ? *own : fittedCubic(curve, entry.amount);
  } catch (const geom::GeometryError& error) {
    throw CurveLapError(CurveLapError::Kind::InvalidTolerance, entry.cutSpan,
                        fmt::format("no B-spline fits this curve within {:g} for the NURBS "
                                    "blocks: {}",
                                    entry.amount, error.what()));
  }
  std::vector<Eigen::Vector3d> points = nurbs->controlPoints();
  for (Eigen::Vector3d& point : points) {
    point = onPrintedGrid(point, entry.grid);
  }
  geom::NurbsCurve block(nurbs->knots(), std::move(points), nurbs->weights());
  FittedNurbsBlock fitted;
  fitted.own = own != nullptr;
  fitted.table = nurbsMoveTable(block);
  for (std::size_t k = 0; k < block.controlPoints().size(); ++k) {
    fitted.weights.push_back(block.weights().empty() ? 1.0 : block.weights()[k]);
  }
  return fitted;
}

FittedSplineBlocks lapSplineBlocks(const CurveTableEntry& entry, const geom::Curve& curve) {
  const SplineBlocksFit fit = entry.splineFit.value_or(SplineBlocksFit{});
  SplineFitRequest request;
  request.curve = &curve;
  request.kind = fit.kind;
  request.budget.tolerance =
      entry.amount > 0 ? entry.amount : std::numeric_limits<double>::quiet_NaN();
  request.budget.increment = entry.grid;
  if (entry.chosenParameters) {
    for (double t : *entry.chosenParameters) {
      request.samples.push_back(curve.point(t));
    }
  }
  std::optional<Eigen::Vector3d> arrival;
  if (fit.afterRamp) {
    arrival = lastChordDirection(request.samples, entry.grid);
  }
  request.transitions = splineTransitions(fit.ends, arrival);
  std::string_view name = splineKindName(fit.kind);
  checkFiniteAlong(entry, curve, request.samples);
  try {
    return fitSplineBlocks(request);
  } catch (const geom::EvaluationBudgetExceeded& error) {
    throw CurveLapError(
        CurveLapError::Kind::ProgramTooLarge, entry.cutSpan,
        fmt::format("fitting {} blocks to this curve within its tolerance asks more than {} "
                    "points of it; that is the limit of one cut's spline fit (a coarser "
                    "tolerance, or a shorter curve, needs fewer)",
                    name, error.limit));
  } catch (const geom::GeometryError& error) {
    throw CurveLapError(CurveLapError::Kind::DegenerateCurve, entry.cutSpan,
                        fmt::format("cannot write this cut as {} blocks: {}", name, error.what()));
  }
}

std::optional<std::string> splineExactStops(const std::vector<PolynomialMove>& spans) {
  int corners = 0;
  double largest = 0;
  for (std::size_t i = 1; i < spans.size(); ++i) {
    double turn = polynomialTransitionDegrees(spans[i - 1], spans[i]);
    if (turn > smoothTransitionDegrees) {
      ++corners;
      largest = std::max(largest, turn);
    }
  }
  if (corners == 0) {
    return std::nullopt;
  }
  return fmt::format("{} of this curve's spline transitions turn by more than {} degrees (the "
                     "largest {:.3g}): the control stops exactly there",
                     corners, smoothTransitionDegrees, largest);
}

} // namespace cncc::ir
