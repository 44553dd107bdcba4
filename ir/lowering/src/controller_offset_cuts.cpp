// A cut beside its curve (side=) on a target that runs the curve loop
// itself, when the controller computes the offset: the tool's diameter a
// part parameter (the shop edits one number for a worn cutter), or a number
// where the curve has a piece that is neither a line nor an arc (the loop is
// a tenth of the chords' program). The cut is lowered by controller_cuts.cpp
// with runtimeOffset_ set, each lap a curve.lap (controller_offset_laps.cpp):
// - each step's point C and its derivative C' come from the same
//   arithmetic (forward_derivative.h: Horner's rule of a NURBS span and
//   its derivative, a polar or param curve's expressions differentiated),
//   the tool centre C + d (-y', x') / |C'| with one SQRT, d = +-diameter/2;
// - a line is moved along its normal, an arc's radius grows or shrinks by
//   the tool's radius, a convex corner of a path gets an arc of that radius
//   about it and a concave corner between two lines their offsets'
//   crossing, c + d (n1 + n2) / (1 + n1.n2), as geom::offsetOfPieces does;
//   with a number's radius, a concave corner at a polar or param piece cuts
//   the piece back where geom's compiled offset does (its range and the
//   crossing, constants: RuntimeOffset::keptParts);
// - the step counts are the legalisation's (curve_lap_offset_steps.h): with
//   a radius the program reads, N(r) = N0 sqrt(1 + q r), which the program
//   computes; with a number, the fewest on the exact offset;
// - before it cuts, the program raises an alarm for a radius (a parameter)
//   that is not positive, or not below the largest radius the tool fits the
//   curve with (its tightest concave bend, a path's concave corner, the
//   offset crossing itself), found here by bisection.
#include "controller_segment.h"
#include "forward_derivative.h"

#include "cncc/geom/composite_curve.h"
#include "cncc/geom/evaluation_budget.h"
#include "cncc/geom/line_arc_curves.h"
#include "cncc/geom/offset_clearance.h"
#include "cncc/geom/offset_curve.h"

#include <Eigen/Geometry>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace cncc::ir::lowering {

using namespace frontend;

namespace {

// The bisection for the largest radius stops within this share of it.
constexpr double radiusSearchAccuracy = 1e-6;
constexpr int radiusSearchSteps = 40;
Eigen::Vector2d leftNormal(const Eigen::Vector3d& tangent) {
  return geom::leftNormalOf(tangent).head<2>();
}

// The parts of an offset whose pieces join as `joins` says
// (geom::PiecesOffset::partOrigins): each piece's offset, then the arc about
// its end where that corner is convex (the last join closes the path).
std::vector<std::optional<std::size_t>> partOriginsOfJoins(std::size_t pieces,
                                                           const std::vector<PieceJoin>& joins) {
  std::vector<std::optional<std::size_t>> origins;
  for (std::size_t p = 0; p < pieces; ++p) {
    origins.emplace_back(p);
    if (p < joins.size() && joins[p].kind == PieceJoin::CornerArc) {
      origins.emplace_back(std::nullopt);
    }
  }
  return origins;
}

} // namespace

double
PartLowering::largestFittingRadius(const std::vector<std::shared_ptr<const geom::Curve>>& pieces,
                                   double compiledDistance, const DrawnClearance& drawn) {
  double side = compiledDistance > 0 ? 1 : -1;
  auto fits = [&](double radius) {
    return std::holds_alternative<geom::PiecesOffset>(
        offsetOrTrouble(pieces, side * radius, &drawn));
  };
  // The tightest bend the tool runs inside bounds the radius; without one
  // the search stops at a hundred times the curve's size.
  Eigen::AlignedBox3d box;
  double upper = std::numeric_limits<double>::infinity();
  for (const auto& piece : pieces) {
    geom::ParameterRange domain = piece->domain();
    for (int j = 0; j <= 16; ++j) {
      box.extend(piece->point(domain.t0 + domain.length() * j / 16));
    }
    if (const auto* arc = dynamic_cast<const geom::ArcCurve*>(piece.get())) {
      if ((arc->sweep() > 0) == (side > 0)) {
        upper = std::min(upper, arc->radius());
      }
    } else if (!isLineCurve(*piece)) {
      upper = std::min(upper, geom::offsetClearance(*piece, compiledDistance).concave.radius);
    }
  }
  double low = std::fabs(compiledDistance);
  double high = std::min(upper, low + 100 * box.diagonal().norm());
  if (fits(high * (1 - 1e-9))) {
    return high < upper ? std::numeric_limits<double>::infinity() : high * (1 - 1e-9);
  }
  for (int step = 0; step < radiusSearchSteps && high - low > radiusSearchAccuracy * high; ++step) {
    double middle = (low + high) / 2;
    (fits(middle) ? low : high) = middle;
  }
  return low;
}

// Whether a cut beside its curve whose tool radius is a number is cut with
// the offset the controller computes: where that makes the program shorter
// (a piece that is neither a line nor an arc, which the host cuts as
// chords) and nothing asks for what only the host's offset gives (spline
// blocks, fitted arcs; lead arcs, samples= and spacing= lowerControllerOffsetCut
// turns away first).
bool PartLowering::offsetOnControllerWanted(const CutStmt& cut, const CutCurve& curve) {
  std::string method = methodOf(cut);
  if (asksFittedArcs(cut) || !(method.empty() || method == "linear")) {
    return false;
  }
  for (const CurvePiece& piece : curve.pieces) {
    if (piece.value->kind != CurveKind::Line && piece.value->kind != CurveKind::Arc) {
      return true;
    }
  }
  return false;
}

// With `runtime` the tool's radius is a parameter; without, a number, and
// the cut is lowered here only where offsetOnControllerWanted says so and
// the controller's offset can follow the path (false otherwise). The same
// on every target: a host's legalisations choose the chords at the
// compiled radius (bound-controller-steps, split-arc-laps).
bool PartLowering::lowerControllerOffsetCut(const CutStmt& cut, double compiledDistance,
                                            bool runtime) {
  for (std::string_view name : {"lead", "samples", "spacing"}) {
    if (const Modifier* modifier = findModifier(cut, name)) { // only the host's offset
      return runtimeOffsetRefused(
          runtime, modifier->span(),
          fmt::format("{}= beside a curve whose tool diameter is a parameter", name));
    }
  }
  CutCurve curve = cutCurve(cut);
  if (!runtime && !offsetOnControllerWanted(cut, curve)) {
    return false;
  }
  RuntimeOffset offset;
  offset.compiledDistance = compiledDistance;
  DrawnClearance drawn = drawnClearance(cut, curve, movedPieces(curve), compiledDistance);
  geom::PiecesOffset compiled = checkedOffset(cut, curve, compiledDistance, &drawn);
  offset.compiled = compiled.curve;
  checkCutBounds(cut, *offset.compiled);
  offset.pieces = movedPieces(curve);
  const auto& pieces = offset.pieces;
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    if (curve.pieces[p].value->kind == CurveKind::Arc && !isArcCurve(*pieces[p])) {
      return runtimeOffsetRefused(runtime, cut.span,
                                  "an arc moved by a map that is not a rotation and a scale, "
                                  "beside a curve whose tool diameter is a parameter");
    }
  }
  // A ramp descends along one closed lap: an offset that does not close (a
  // corner where the path closes, which geom's offset leaves open) has
  // none.
  geom::ParameterRange whole = compiled.curve->domain();
  if (rampEntry(cut) &&
      (compiled.curve->point(whole.t0) - compiled.curve->point(whole.t1)).norm() > 1e-6) {
    return runtimeOffsetRefused(runtime, findModifier(cut, "entry")->span(),
                                "entry=ramp beside a path whose offset does not close (a corner "
                                "where the path closes)");
  }
  offset.joins = pieceJoins(pieces, compiledDistance, offset.closed);
  // The laps follow geom's offset: its pieces and a corner arc per convex
  // join, as the joins at the compiled radius say.
  if (compiled.partOrigins != partOriginsOfJoins(pieces.size(), offset.joins)) {
    return runtimeOffsetRefused(runtime, cut.span,
                                "a path whose offset's pieces join otherwise than its own, "
                                "beside a curve whose tool diameter is a parameter");
  }
  for (std::size_t j = 0; j < offset.joins.size(); ++j) {
    std::size_t after = (j + 1) % pieces.size();
    if (offset.joins[j].kind == PieceJoin::Crossing &&
        !(isLineCurve(*pieces[j]) && isLineCurve(*pieces[after]))) {
      // A number's radius: the pieces cut back where the compiled offset
      // is (a knot span's would need its spans cut back too).
      if (!runtime) {
        if (!curve.pieces[j].spans.empty() || !curve.pieces[after].spans.empty() ||
            isArcCurve(*pieces[j]) || isArcCurve(*pieces[after])) {
          return false;
        }
        continue;
      }
      return runtimeOffsetRefused(runtime, cut.span,
                                  "a concave corner at a piece that is not a line, "
                                  "beside a curve whose tool diameter is a parameter");
    }
  }
  if (!runtime) {
    offset.keptParts.assign(pieces.size(), nullptr);
    std::vector<const geom::Curve*> parts = geom::piecesOf(*compiled.curve);
    for (std::size_t k = 0; k < parts.size() && k < compiled.partOrigins.size(); ++k) {
      if (compiled.partOrigins[k]) {
        offset.keptParts[*compiled.partOrigins[k]] = parts[k];
      }
    }
  }
  if (runtime) {
    offset.radius = arithmetic_.multiply(number(*toolDiameter_), Scalar::of(0.5));
    offset.distance =
        compiledDistance > 0 ? offset.radius : arithmetic_.unary(Opcode::Neg, offset.radius);
    offset.largestRadius = largestFittingRadius(pieces, compiledDistance, drawn);
  } else {
    offset.radius = Scalar::of(std::fabs(compiledDistance));
    offset.distance = Scalar::of(compiledDistance);
  }
  runtimeOffset_ = std::move(offset);
  // Unset however the lowering leaves (an error, a retry with unrolling).
  struct Unset {
    std::optional<RuntimeOffset>& offset;
    ~Unset() { offset.reset(); }
  } unset{runtimeOffset_};
  bool lowered = lowerControllerCut(cut, curve);
  if (!lowered) {
    return runtimeOffsetRefused(
        runtime, cut.span, "this cut beside its curve with a tool diameter that is a parameter");
  }
  return true;
}

// Where the controller's laps cannot follow the offset: false, the host's
// offset at the compiled radius instead, but for a radius that is a
// parameter where a controller computes the program (refused).
bool PartLowering::runtimeOffsetRefused(bool runtime, SourceSpan span, std::string_view what) {
  if (runtime && options_.controllerLoops) {
    unsupported(span, what);
  }
  return false;
}

// Before the cut (lowerControllerCut, once it knows it cuts it): an alarm
// for a radius that is not positive, or not below the largest the tool
// fits the curve with.
void PartLowering::guardRuntimeRadius(const RuntimeOffset& offset) {
  alarmWhen(arithmetic_.binary(Opcode::Le, offset.radius, Scalar::of(0)),
            "the tool diameter is not positive");
  if (std::isfinite(offset.largestRadius)) {
    // Printed with four decimals, rounded down: a radius at it is refused.
    double limit = std::floor(offset.largestRadius * 1e4) / 1e4;
    alarmWhen(arithmetic_.binary(Opcode::Ge, offset.radius, Scalar::of(limit)),
              fmt::format("the tool radius must be below {:.4f} for this curve", limit));
  }
}

// The counts of the offset's pieces, left to the legalisation: with a
// radius that is a number measured on the exact offset (but where one chord
// cuts a piece), with a radius the program reads grown with it
// (OffsetStepGrowth, curve_lap_offset_steps.h). False where the check of
// one chord asks more points of the offset than a cut may: the host's
// chords then.
bool PartLowering::planOffsetSteps(const CutCurve& curve, std::vector<ControllerSegment>& segments,
                                   double budget) {
  const RuntimeOffset& offset = *runtimeOffset_;
  double side = offset.compiledDistance > 0 ? 1 : -1;
  double compiledRadius = std::fabs(offset.compiledDistance);
  double measured = measuredBudget(budget);
  std::size_t evaluated = 0; // the points asked of the exact offset so far
  for (ControllerSegment& segment : segments) {
    const CurvePiece& piece = curve.pieces[segment.piece];
    if (segment.isArc || piece.value->kind == CurveKind::Line) {
      continue;
    }
    if (!segment.isNurbs && !offset.keptParts.empty()) {
      if (offset.keptParts[segment.piece] == nullptr) {
        return false;
      }
      // Cut back at its concave corners, as the compiled offset is.
      geom::ParameterRange kept = offset.keptParts[segment.piece]->domain();
      segment.from = kept.t0;
      segment.to = kept.t1;
    }
    segment.steps = stepsChosenByLegalisation;
    segment.stepCount.reset();
    if (!offset.radius.isConstant()) {
      continue;
    }
    auto moved = std::make_shared<TransformedCurve>(piece.geometry, piece.transform);
    double from = segment.isNurbs ? piece.spans[segment.span].t0 : segment.from;
    double to = segment.isNurbs ? piece.spans[segment.span].t1 : segment.to;
    geom::OffsetCurve offsetCurve(moved, side * compiledRadius);
    geom::BudgetedCurve exact(offsetCurve, maximumOffsetStepEvaluations - evaluated);
    EvaluationsCharged charged{evaluated, exact};
    try {
      if (uniformStepsFit(exact, from, to, 1, measured)) {
        segment.steps = 1;
      }
    } catch (const geom::EvaluationBudgetExceeded&) {
      return false;
    }
  }
  return true;
}

Scalar PartLowering::plusScaled(Scalar base, Scalar value, Scalar factor) {
  if (!factor.isConstant()) {
    return arithmetic_.add(base, times(value, factor));
  }
  // A normal's share of an axis below 1e-9 is the rounding of a derivative
  // found by differences, not a direction (and moves the point 1e-9 r).
  double share = std::fabs(factor.constant) < 1e-9 ? 0.0 : factor.constant;
  if (share == 0) {
    return base;
  }
  Scalar scaled = std::fabs(share) == 1 ? value : times(value, Scalar::of(std::fabs(share)));
  if (base.isConstant() && base.constant == 0) {
    return share > 0 ? scaled : arithmetic_.unary(Opcode::Neg, scaled);
  }
  return arithmetic_.binary(share > 0 ? Opcode::Add : Opcode::Sub, base, scaled);
}

CurvePoint PartLowering::besideAt(const CurvePoint& point, const Eigen::Vector2d& normal) {
  const Scalar& distance = runtimeOffset_->distance;
  return {plusScaled(point.x, distance, Scalar::of(normal.x())),
          plusScaled(point.y, distance, Scalar::of(normal.y())), point.z};
}

CurvePoint PartLowering::offsetSegmentEnd(const CutCurve& curve, const ControllerSegment& segment,
                                          bool atEnd, const CurvePoint& point) {
  const RuntimeOffset& offset = *runtimeOffset_;
  const CurvePiece& piece = curve.pieces[segment.piece];
  std::size_t lastPiece = curve.pieces.size() - 1;
  // The join at this end, if any.
  const PieceJoin* join = nullptr;
  if (atEnd && endsItsPiece(segment, piece) && (segment.piece < lastPiece || offset.closed)) {
    join = &offset.joins[segment.piece];
  } else if (!atEnd && startsItsPiece(segment) && (segment.piece > 0 || offset.closed)) {
    // The join before the piece: a line's region starts at the crossing too
    // (a host that samples the region at its start reads it).
    join = &offset.joins[segment.piece > 0 ? segment.piece - 1 : offset.joins.size() - 1];
  }
  if (join != nullptr && join->kind == PieceJoin::Crossing) {
    std::size_t count = offset.pieces.size();
    std::size_t other = atEnd ? (segment.piece + 1) % count : (segment.piece + count - 1) % count;
    const geom::Curve* kept = offset.keptParts.empty() ? nullptr : offset.keptParts[segment.piece];
    if (kept != nullptr &&
        !(isLineCurve(*offset.pieces[segment.piece]) && isLineCurve(*offset.pieces[other]))) {
      // A number's radius beside a curved piece: where the compiled
      // offsets cross.
      geom::ParameterRange range = kept->domain();
      Eigen::Vector3d crossing = kept->point(atEnd ? range.t1 : range.t0);
      return {Scalar::of(crossing.x()), Scalar::of(crossing.y()), point.z};
    }
    Eigen::Vector2d shift = (join->before + join->after) / (1 + join->before.dot(join->after));
    return besideAt({Scalar::of(join->corner.x()), Scalar::of(join->corner.y()), point.z}, shift);
  }
  const geom::Curve& drawn = *offset.pieces[segment.piece];
  double t = atEnd ? drawn.domain().t1 : drawn.domain().t0;
  if (!segment.isNurbs && !segment.isArc && !isLineCurve(drawn)) {
    t = atEnd ? segment.to : segment.from; // cut back at a concave corner
  }
  if (segment.isNurbs) {
    const geom::PolynomialSpan& span = piece.spans[segment.span];
    t = atEnd ? span.t1 : span.t0;
  }
  return besideAt(point, leftNormal(drawn.derivative(t)));
}

CurvePoint PartLowering::offsetAlongDerivative(const CurvePoint& point, ValueId variable,
                                               Scalar distance, const CutStmt& cut) {
  ForwardDerivative derivative(builder_, arithmetic_, variable);
  std::optional<Scalar> dx = derivative.of(point.x);
  std::optional<Scalar> dy = derivative.of(point.y);
  if (!dx || !dy) {
    unsupported(cut.curve->span, "this curve's tangent on the controller");
  }
  Scalar speed = arithmetic_.unary(Opcode::Sqrt, arithmetic_.add(times(*dx, *dx), times(*dy, *dy)));
  Scalar share = arithmetic_.binary(Opcode::Div, distance, speed);
  return {arithmetic_.binary(Opcode::Sub, point.x, times(share, *dy)),
          arithmetic_.add(point.y, times(share, *dx)), point.z};
}

} // namespace cncc::ir::lowering
