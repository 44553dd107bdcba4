// method=bspline, nurbs, cspline or aspline on a target that prints
// Sinumerik spline blocks (LoweringOptions::splineBlocks). The cut's blocks
// are fitted once (spline_fitting.cpp), every number on the printed grid,
// and put in a table; each pass is a rapid over the spline's start, a
// plunge (and the ramp lap's chords with entry=ramp), the blocks' comment
// and a curve.lap at the pass height whose entry gives the table
// (CurveSampling::SplineBlocks), which the legalisation write-curve-blocks
// writes out as one move.spline, and a retract. A curve that does
// not lie in one plane z = constant (the spline axes are X and Y) is cut as
// chords.
#include "part_lowering.h"
#include "spline_fitting.h"

#include "cncc/geom/evaluation_budget.h"
#include "cncc/ir/printed_grid.h"

#include "cncc/geom/geometry_error.h"
#include "cncc/ir/spline_move.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

namespace cncc::ir::lowering {

using namespace frontend;

namespace {

constexpr double kSameZ = 1e-9;
constexpr int kPlanarityProbes = 16;

std::optional<SplineKind> splineKindOf(const std::string& method) {
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

// Whether the curve lies in a plane z = constant.
bool isPlanar(const geom::Curve& curve) {
  geom::ParameterRange domain = curve.domain();
  double z = curve.point(domain.t0).z();
  for (int k = 1; k <= kPlanarityProbes; ++k) {
    double t = domain.t0 + domain.length() * k / kPlanarityProbes;
    if (std::abs(curve.point(t).z() - z) > kSameZ) {
      return false;
    }
  }
  return true;
}

// How an A or C spline starts and ends; `arrival` is the XY direction of
// the ramp's last chord, as printed, if the spline follows a ramp.
geom::SplineTransitions transitionsFor(SplineEnds ends,
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

} // namespace

// The XY direction of the ramp lap's last chord, on the printed grid.
std::optional<Eigen::Vector3d> PartLowering::rampArrival(const geom::CurveSamples& samples) {
  std::size_t n = samples.points.size();
  if (n < 2) {
    return std::nullopt;
  }
  double increment = options_.coordinateIncrement;
  Eigen::Vector3d direction = onPrintedGrid(samples.points[n - 1], increment) -
                              onPrintedGrid(samples.points[n - 2], increment);
  direction.z() = 0;
  return direction.norm() > 1e-9 ? std::optional<Eigen::Vector3d>(direction) : std::nullopt;
}

FittedSplineBlocks PartLowering::splineBlocksFor(const CutStmt& cut, const CutCurve& curve,
                                                 SplineKind kind, const geom::CurveSamples& samples,
                                                 bool ramp) {
  SplineFitRequest request;
  request.curve = curve.geometry.get();
  request.kind = kind;
  request.budget = toleranceBudget(cut);
  request.samples = samples.points;
  request.transitions =
      transitionsFor(options_.splineEnds, ramp ? rampArrival(samples) : std::nullopt);
  try {
    return fitSplineBlocks(request);
  } catch (const geom::EvaluationBudgetExceeded& error) {
    fail(cut.span,
         fmt::format("fitting {} blocks to this curve within its tolerance asks more than {} "
                     "points of it; that is the limit of one cut's spline fit (a coarser "
                     "tolerance, or a shorter curve, needs fewer)",
                     methodOf(cut), error.limit),
         DiagnosticKind::ProgramTooLarge);
  } catch (const geom::GeometryError& error) {
    fail(
        cut.span,
        fmt::format("cannot write cut {} as {}: {}", cuts_.size() + 1, methodOf(cut), error.what()),
        DiagnosticKind::DegenerateCurve);
  }
}

bool PartLowering::lowerSplineCut(const CutStmt& cut, const CutCurve& curve) {
  std::optional<SplineKind> kind = splineKindOf(methodOf(cut));
  if (!options_.splineBlocks || !kind || !isPlanar(*curve.geometry)) {
    return false;
  }
  auto [feed, ramp] = beginHostCut(cut);
  geom::CurveSamples samples = checkedSamplesFor(cut, *curve.geometry);
  std::vector<double> depths = passDepths(cut);
  if (ramp) {
    checkRampCloses(curve, cut);
  }
  FittedSplineBlocks blocks = splineBlocksFor(cut, curve, *kind, samples, ramp);
  std::uint32_t table = builder_.addTable(splineMoveTable(blocks.data));
  // A curve beside the cut's (an offset) computed otherwise than its laps
  // follow has no regions: its blocks are the move itself.
  std::optional<std::uint32_t> blocksTable;
  if (!curve.pieces.empty() || curve.beside) {
    blocksTable = builder_.addCurve(blocksTableEntry(cut, curve, CurveSampling::SplineBlocks, table,
                                                     toleranceBudget(cut).tolerance));
  }
  std::string comment = splineBlocksComment(blocks);

  ValueId feedValue = arithmetic_.value(feed);
  ValueId safeValue = arithmetic_.value(*safe_);
  CutGeometry geometry{curve.geometry,
                       chordTolerance(cut).value_or(std::numeric_limits<double>::quiet_NaN()),
                       cut.span, methodOf(cut)};
  geometry.splineBlocks = comment;
  beginCutMoves(std::move(geometry));
  // The ramp's lap as chords through the points the blocks were fitted to.
  std::optional<std::uint32_t> rampTable;
  if (ramp) {
    CurveTableEntry entry = curveTableEntry(cut, curve);
    entry.chosenParameters = std::make_shared<const std::vector<double>>(samples.parameters);
    rampTable = builder_.addCurve(std::move(entry));
  }
  // The ramp's lap as chords, the lap at the pass height as the blocks
  // (a curve.lap that write-curve-blocks writes out as the move.spline).
  auto lap = [&](double zFrom, double zTo) {
    if (zFrom != zTo) {
      emitCurveLap(curve, *rampTable, zFrom, zTo, feedValue, cut);
      return;
    }
    builder_.comment(comment);
    if (blocksTable) {
      emitCurveLap(curve, *blocksTable, zTo, zTo, feedValue, cut);
    } else {
      builder_.spline(table, builder_.constant(zTo), feedValue);
    }
  };
  emitHostPasses(depths, ramp, blocks.start, blocks.data.points.back(), feedValue, safeValue, lap);
  return true;
}

} // namespace cncc::ir::lowering
