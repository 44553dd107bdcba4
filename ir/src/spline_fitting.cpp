#include "cncc/ir/spline_fitting.h"

#include "cncc/geom/bspline_fitting.h"
#include "cncc/geom/controller_bspline.h"
#include "cncc/geom/curve_deviation.h"
#include "cncc/geom/curve_stand_in.h"
#include "cncc/geom/evaluation_budget.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/geom/nurbs_curve.h"
#include "cncc/geom/nurbs_reparametrisation.h"
#include "cncc/geom/spline_knot_placement.h"
#include "cncc/ir/printed_grid.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace cncc::ir {

namespace {

constexpr geom::WeightRange kWeightRange{1e-4, 3.0}; // PW: 0..3 in steps of 0.0001
constexpr double kWeightStep = 1e-4;
// PL gets three more decimals than the coordinates.
constexpr double kIntervalIncrementShare = 1e-3;
// Each retry with the printed numbers over the tolerance aims this much lower.
constexpr double kRetryFactor = 0.9;
constexpr int kRetries = 4;

double measure(const geom::Curve& spline, const geom::Curve& curve, const ToleranceBudget& budget) {
  double accuracy = std::isnan(budget.tolerance) ? 1e-6 : budget.measurementAccuracy();
  return geom::measureCurveDeviation(spline, curve, {accuracy}).maxDeviation();
}

// The blocks of a clamped B spline: its points after the first, PW and PL,
// on the printed grid.
FittedSplineBlocks blocksOfSpline(const geom::NurbsCurve& spline, double increment) {
  FittedSplineBlocks blocks;
  blocks.data.kind = SplineKind::BSpline;
  blocks.data.degree = spline.degree();
  const std::vector<double>& knots = spline.knots().values();
  double first = spline.weights().front();
  blocks.start = onPrintedGrid(spline.controlPoints().front(), increment);
  for (std::size_t i = 1; i < spline.controlPoints().size(); ++i) {
    blocks.data.points.push_back(onPrintedGrid(spline.controlPoints()[i], increment));
    blocks.data.weights.push_back(onPrintedGrid(spline.weights()[i] / first, kWeightStep));
    blocks.data.intervals.push_back(
        onPrintedGrid(knots[i + 1] - knots[i], increment * kIntervalIncrementShare));
  }
  return blocks;
}

// What the controller builds from the blocks.
geom::NurbsCurve modelOf(const FittedSplineBlocks& blocks) {
  return geom::bsplineOfBlocks(blocks.start, blocks.data.degree, blocks.data.points,
                               blocks.data.weights, blocks.data.intervals);
}

// A NURBS of degree 2 or 3 whose weights fit PW once scaled, or once
// reparametrised: its own blocks. Nothing (and `note` says why) when it
// cannot be written as it is.
std::optional<FittedSplineBlocks> exactBlocks(const geom::NurbsCurve& nurbs,
                                              const SplineFitRequest& request, std::string& note) {
  int degree = nurbs.degree();
  if (degree != 2 && degree != 3) {
    note = fmt::format("degree {} (SD is 2 or 3)", degree);
    return std::nullopt;
  }
  if (!nurbs.knots().isClamped()) {
    note = "its knots are not clamped";
    return std::nullopt;
  }
  std::optional<geom::FittingWeights> fitting = geom::weightsWithin(nurbs, kWeightRange);
  if (!fitting) {
    auto [lowest, highest] = std::minmax_element(nurbs.weights().begin(), nurbs.weights().end());
    note = fmt::format("no reparametrisation brings its weights (relative to the first, {:g} to "
                       "{:g}) into PW's range 0..3",
                       *lowest / nurbs.weights().front(), *highest / nurbs.weights().front());
    return std::nullopt;
  }
  FittedSplineBlocks blocks = blocksOfSpline(fitting->curve, request.budget.increment);
  blocks.deviation = measure(modelOf(blocks), *request.curve, request.budget);
  if (!(blocks.deviation <= request.budget.tolerance) && !std::isnan(request.budget.tolerance)) {
    note = fmt::format("its printed numbers (weights in steps of 0.0001) move it by {:.3g} mm",
                       blocks.deviation);
    return std::nullopt;
  }
  bool moved = fitting->lambda != 1;
  blocks.way = moved ? SplineFitWay::Reparametrised : SplineFitWay::Exact;
  if (moved) {
    blocks.note = fmt::format("reparametrised (lambda {:.4g}) for PW's range", fitting->lambda);
  }
  return blocks;
}

// The curve's own points as control points (samples= or spacing=, as the
// published programs did), PL the chord lengths.
FittedSplineBlocks samplesAsControlPoints(const SplineFitRequest& request) {
  const std::vector<Eigen::Vector3d>& samples = request.samples;
  if (samples.size() < 3) {
    throw geom::GeometryError("a B spline needs at least three points");
  }
  int degree = samples.size() >= 4 ? 3 : 2;
  double increment = request.budget.increment;
  std::vector<Eigen::Vector3d> points;
  for (const Eigen::Vector3d& sample : samples) {
    points.push_back(onPrintedGrid(sample, increment));
  }
  geom::NurbsCurve spline = geom::NurbsCurve::bspline(degree, points);
  double length = 0;
  for (std::size_t i = 1; i < points.size(); ++i) {
    length += (points[i] - points[i - 1]).norm();
  }
  FittedSplineBlocks blocks = blocksOfSpline(spline, increment);
  for (double& interval : blocks.data.intervals) {
    interval = onPrintedGrid(interval * length, increment * kIntervalIncrementShare);
  }
  blocks.deviation = measure(modelOf(blocks), *request.curve, request.budget);
  blocks.way = SplineFitWay::Samples;
  return blocks;
}

FittedSplineBlocks fittedBlocks(const SplineFitRequest& request) {
  double target = request.budget.forSplineControlPoints();
  for (int attempt = 0; attempt < kRetries && target > 0; ++attempt, target *= kRetryFactor) {
    geom::BSplineFitOptions options;
    options.tolerance = target;
    geom::BSplineFit fit = geom::fitBSpline(*request.curve, options);
    FittedSplineBlocks blocks = blocksOfSpline(fit.spline, request.budget.increment);
    blocks.deviation = measure(modelOf(blocks), *request.curve, request.budget);
    if (blocks.deviation <= request.budget.tolerance) {
      return blocks;
    }
  }
  throw geom::GeometryError(fmt::format(
      "no B spline with coordinates on the printed grid ({:g}) stays within {:g} mm of this curve",
      request.budget.increment, request.budget.tolerance));
}

// `original`: the request's curve before it was budgeted or stood in for,
// a NURBS written as it is where it can be.
FittedSplineBlocks bsplineBlocks(const SplineFitRequest& request, const geom::Curve& original) {
  if (std::isnan(request.budget.tolerance)) {
    return samplesAsControlPoints(request);
  }
  std::string note;
  if (const auto* nurbs = dynamic_cast<const geom::NurbsCurve*>(&original)) {
    if (std::optional<FittedSplineBlocks> blocks = exactBlocks(*nurbs, request, note)) {
      return *blocks;
    }
  }
  FittedSplineBlocks blocks = fittedBlocks(request);
  if (!note.empty()) {
    blocks.way = SplineFitWay::Refitted;
    blocks.note = "re-fitted: " + note;
  }
  return blocks;
}

geom::InterpolatingSplineKind modelKind(SplineKind kind) {
  return kind == SplineKind::CSpline ? geom::InterpolatingSplineKind::CSpline
                                     : geom::InterpolatingSplineKind::ASpline;
}

// Points on the curve through which the modelled spline, built from the
// printed numbers, stays within the tolerance.
FittedSplineBlocks interpolatingBlocks(const SplineFitRequest& request) {
  FittedSplineBlocks blocks;
  blocks.data.kind = request.kind;
  blocks.data.start = request.transitions.start;
  blocks.data.end = request.transitions.end;
  auto finish = [&](const std::vector<Eigen::Vector3d>& points) {
    std::vector<Eigen::Vector3d> printed;
    for (const Eigen::Vector3d& point : points) {
      // Knots closer than the printed resolution become one.
      Eigen::Vector3d rounded = onPrintedGrid(point, request.budget.increment);
      if (printed.empty() || rounded != printed.back()) {
        printed.push_back(rounded);
      }
    }
    geom::PiecewisePolynomialCurve model =
        geom::modelSpline(modelKind(request.kind), printed, request.transitions);
    blocks.start = printed.front();
    blocks.data.points.assign(printed.begin() + 1, printed.end());
    blocks.deviation = measure(model, *request.curve, request.budget);
  };
  if (std::isnan(request.budget.tolerance)) {
    finish(request.samples);
    blocks.way = SplineFitWay::Samples;
    return blocks;
  }
  double target = request.budget.forSplineKnots();
  for (int attempt = 0; attempt < kRetries && target > 0; ++attempt, target *= kRetryFactor) {
    geom::SplineKnotPlacementOptions options;
    options.kind = modelKind(request.kind);
    options.tolerance = target;
    options.transitions = request.transitions;
    geom::SplineKnots knots = geom::placeSplineKnots(*request.curve, options);
    finish(knots.points);
    if (blocks.deviation <= request.budget.tolerance) {
      return blocks;
    }
  }
  throw geom::GeometryError(
      fmt::format("no {} knots on the printed grid ({:g}) keep the spline within {:g} mm of this "
                  "curve",
                  request.kind == SplineKind::CSpline ? "CSPLINE" : "ASPLINE",
                  request.budget.increment, request.budget.tolerance));
}

} // namespace

FittedSplineBlocks fitSplineBlocks(const SplineFitRequest& given) {
  // The fit's searches (the knots placed, each retry, the measurements) ask
  // at most maximumSplineFitEvaluations points of the curve: a long or fast
  // curve at a fine tolerance ends in EvaluationBudgetExceeded.
  geom::BudgetedCurve budgeted(*given.curve, maximumSplineFitEvaluations);
  SplineFitRequest request = given;
  request.curve = &budgeted;
  // An analytic curve, whose every evaluation runs the part's expressions:
  // the searches run on a stand-in within the budget's share for it.
  SplineFitRequest cheap = request;
  std::optional<geom::CurveStandIn> standIn;
  std::optional<geom::BudgetedCurve> cheapCurve;
  bool analytic = dynamic_cast<const geom::NurbsCurve*>(given.curve) == nullptr &&
                  dynamic_cast<const geom::PiecewisePolynomialCurve*>(given.curve) == nullptr;
  if (analytic && !std::isnan(request.budget.tolerance)) {
    standIn = geom::standInFor(*request.curve, request.budget.standInError());
    if (standIn) {
      // The stand-in is cheap to ask, but the fit's measurements ask it for
      // as many points as the curve is long over the tolerance: bounded too.
      cheapCurve.emplace(*standIn->curve, maximumSplineFitEvaluations);
      cheap.curve = &*cheapCurve;
      cheap.budget.tolerance = request.budget.tolerance - standIn->error;
    }
  }
  FittedSplineBlocks blocks = request.kind == SplineKind::BSpline
                                  ? bsplineBlocks(cheap, *given.curve)
                                  : interpolatingBlocks(cheap);
  if (standIn) {
    blocks.deviation += standIn->error;
  }
  return blocks;
}

std::string splineBlocksComment(const FittedSplineBlocks& blocks) {
  bool bspline = blocks.data.kind == SplineKind::BSpline;
  const char* name =
      bspline ? "BSPLINE" : (blocks.data.kind == SplineKind::CSpline ? "CSPLINE" : "ASPLINE");
  std::string way;
  if (blocks.way == SplineFitWay::Exact || blocks.way == SplineFitWay::Reparametrised) {
    way = ", the NURBS as it is";
  }
  return fmt::format("{} {} {}, deviation {:.2g} mm{}{}", blocks.data.points.size(), name,
                     bspline ? "control points" : "knots", blocks.deviation, way,
                     blocks.note.empty() ? "" : ", " + blocks.note);
}

} // namespace cncc::ir
