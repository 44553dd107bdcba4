// The laps of a cut beside its curve whose tool radius the controller knows
// only as it runs (planned in controller_offset_cuts.cpp): each lap is a
// curve.lap cut in steps, written out by expand-controller-loops as any
// other. Its regions follow the tool along the path:
// - a line's offset, from its offset start to its offset end (where a
//   concave corner cuts it back, the crossing the radius gives), in one step
//   over the fraction 0 .. 1;
// - an arc's, an arc region in the drawn arc's parameter on the radius the
//   tool's grows or shrinks, in the drawn arc's blocks;
// - another piece's (a knot span, a polar or param curve), the tool centre
//   C + d (-y', x') / |C'| with C' the derivative in the region's parameter
//   (forward_derivative.h), its count the legalisation's: with a radius
//   the program reads, one it computes from the radius (the entry's
//   offsetGrowth, the lap's last operand the distance), with a number the
//   fewest on the entry's geometry;
// - after a piece that ends at a convex corner, an arc region of the tool's
//   radius about the corner over the fraction 0 .. 1 of its turn.
// The entry's geometry is the offset at the compiled radius in the same
// parameters (geom::offsetOfPieces makes the same pieces and corner arcs).
#include "controller_segment.h"

#include "cncc/ir/curve_lap_steps.h"

#include "cncc/geom/composite_curve.h"
#include "cncc/geom/function_curve.h"
#include "cncc/geom/line_arc_curves.h"

#include <cmath>

namespace cncc::ir::lowering {

using namespace frontend;

namespace {

bool isLineSegment(const ControllerSegment& segment, const CurvePiece& piece) {
  return !segment.isArc && !segment.isNurbs && piece.value->kind == CurveKind::Line;
}

// The compiled offset's pieces (one per drawn piece, one per corner arc) in
// the parameters the entry lays out: each mapped linearly onto its own.
// Null when the offset is made of other pieces than the entry lays out
// (lowerControllerOffsetCut refuses such a path before: a guard).
std::shared_ptr<const geom::Curve>
besideGeometry(const CurveTableEntry& entry, const std::shared_ptr<const geom::Curve>& offset) {
  std::vector<const geom::Curve*> parts = geom::piecesOf(*offset);
  if (parts.size() != entry.pieces.size()) {
    return nullptr;
  }
  std::vector<std::shared_ptr<const geom::Curve>> pieces;
  for (std::size_t p = 0; p < parts.size(); ++p) {
    const CurvePieceLayout& layout = entry.pieces[p];
    geom::ParameterRange own = parts[p]->domain();
    double scale = own.length() / (layout.to - layout.from);
    const geom::Curve* part = parts[p];
    pieces.push_back(std::make_shared<geom::FunctionCurve>(
        geom::ParameterRange{layout.from, layout.to},
        [offset, part, own, from = layout.from, scale](double t) {
          return part->point(own.t0 + (t - from) * scale);
        }));
  }
  return joinedPieces(pieces);
}

} // namespace

PartLowering::SteppedLap
PartLowering::besideSteppedLap(const CutStmt& cut, const CutCurve& curve,
                               const std::vector<ControllerSegment>& segments, double budget) {
  const RuntimeOffset& offset = *runtimeOffset_;
  CurveTableEntry entry = curveTableEntryOn(cut, curve.geometry);
  entry.sampling = CurveSampling::Steps;
  entry.amount = measuredBudget(budget);
  double start = 0;
  auto addPiece = [&](CurvePieceLayout layout) {
    layout.start = start;
    start += layout.to - layout.from;
    entry.pieces.push_back(std::move(layout));
  };
  SteppedLap lap;
  for (std::size_t s = 0; s < segments.size(); ++s) {
    const ControllerSegment& segment = segments[s];
    const CurvePiece& piece = curve.pieces[segment.piece];
    bool line = isLineSegment(segment, piece);
    if (startsItsPiece(segment)) {
      CurvePieceLayout layout = line ? CurvePieceLayout{0, 0, 1} : pieceLayout(piece, 0);
      if (!line && !segment.isArc && !segment.isNurbs) {
        layout.from = segment.from; // cut back at a concave corner
        layout.to = segment.to;
      }
      addPiece(std::move(layout));
    }
    lap.besideRegions.push_back({s, 0});
    if (segment.isArc) {
      addArcRegion(entry, lap, segment, curve, cut);
    } else {
      // A line in one step; another piece's count is the legalisation's
      // (planOffsetSteps), or 1 where one chord cuts it.
      entry.regionSteps.push_back(line ? 1 : segment.steps);
    }
    bool corner = endsItsPiece(segment, piece) && segment.piece < offset.joins.size() &&
                  offset.joins[segment.piece].kind == PieceJoin::CornerArc;
    if (corner) {
      const PieceJoin& join = offset.joins[segment.piece];
      ArcPath turn;
      turn.sweep = Scalar::of(join.turn);
      addPiece({0, 0, 1});
      entry.arcRegions.push_back({entry.regionSteps.size(), join.turn > 0, false});
      entry.regionSteps.push_back(static_cast<int>(arcBlocks(turn, cut).count.constant));
      lap.besideRegions.push_back({std::nullopt, segment.piece});
    }
  }
  if (entry.pieces.size() == 1) {
    entry.pieces.front().start = entry.pieces.front().from;
    entry.from = entry.pieces.front().from;
    entry.to = entry.pieces.front().to;
  } else {
    entry.from = 0;
    entry.to = start;
  }
  entry.geometry = besideGeometry(entry, offset.compiled);
  if (!offset.radius.isConstant() && hasChosenSteps(entry)) {
    // The counts grow with the radius: the lap reads the distance last.
    entry.offsetGrowth = OffsetStepGrowth{offset.compiledDistance > 0 ? 1.0 : -1.0,
                                          std::fabs(offset.compiledDistance), offset.largestRadius};
    lap.computedSteps.push_back(arithmetic_.value(offset.distance));
  }
  lap.table = builder_.addCurve(std::move(entry));
  return lap;
}

LapRegionPoint PartLowering::besideRegionPoint(const CutCurve& curve,
                                               const std::vector<ControllerSegment>& segments,
                                               const BesideRegion& region, Scalar local,
                                               const CutStmt& cut) {
  if (!region.segment) {
    return cornerArcRegionPoint(runtimeOffset_->joins[region.join], local);
  }
  const ControllerSegment& segment = segments[*region.segment];
  const CurvePiece& piece = curve.pieces[segment.piece];
  if (segment.isArc) {
    return offsetArcRegionPoint(curve, segment, local, cut);
  }
  if (isLineSegment(segment, piece)) {
    CurvePoint from =
        offsetSegmentEnd(curve, segment, false, segmentEndPoint(curve, segment, false, cut));
    CurvePoint to =
        offsetSegmentEnd(curve, segment, true, segmentEndPoint(curve, segment, true, cut));
    return pointBetween(from, to, local);
  }
  CurvePoint point;
  if (segment.isNurbs) {
    point = spanPointAt(cleanedSpan(piece.spans[segment.span]), local); // u in 0 .. 1
    point = segment.moved != nullptr ? applied(*segment.moved, point)
                                     : transformed(piece.transform, point);
  } else {
    point = pointAt(curve, segment.piece, segment.span, local, cut);
  }
  return offsetAlongDerivative(point, local.value, runtimeOffset_->distance, cut);
}

// The drawn arc's point moved towards its centre by the share d / R (left of
// a counter-clockwise arc is inwards), the centre nearer by as much.
LapRegionPoint PartLowering::offsetArcRegionPoint(const CutCurve& curve,
                                                  const ControllerSegment& segment, Scalar local,
                                                  const CutStmt& cut) {
  // An arc piece moved is an arc (lowerControllerOffsetCut checked).
  const auto* arc = static_cast<const geom::ArcCurve*>(runtimeOffset_->pieces[segment.piece].get());
  Scalar inwards = arc->sweep() > 0 ? runtimeOffset_->distance
                                    : arithmetic_.unary(Opcode::Neg, runtimeOffset_->distance);
  Scalar share = times(inwards, Scalar::of(1 / arc->radius()));
  Scalar kept = arithmetic_.binary(Opcode::Sub, Scalar::of(1), share);
  LapRegionPoint drawn = arcRegionPoint(curve, segment, local, cut);
  const CurvePoint& point = drawn.point;
  const CurvePoint& centre = *drawn.toCentre;
  return {{plusScaled(point.x, share, centre.x), plusScaled(point.y, share, centre.y), point.z},
          {times(kept, centre.x), times(kept, centre.y), centre.z}};
}

// The tool centre on an arc of its radius about the corner, turning from d n1
// (the normal of the piece ending there) by the fraction of the corner's turn.
LapRegionPoint PartLowering::cornerArcRegionPoint(const PieceJoin& join, Scalar fraction) {
  Scalar angle = times(fraction, Scalar::of(join.turn));
  Scalar cosine = angle.isConstant() ? Scalar::of(std::cos(angle.constant))
                                     : arithmetic_.unary(Opcode::Cos, angle);
  Scalar sine = angle.isConstant() ? Scalar::of(std::sin(angle.constant))
                                   : arithmetic_.unary(Opcode::Sin, angle);
  const Eigen::Vector2d& normal = join.before;
  // The radial direction, to be scaled by the distance.
  Scalar x = arithmetic_.binary(Opcode::Sub, times(cosine, Scalar::of(normal.x())),
                                times(sine, Scalar::of(normal.y())));
  Scalar y =
      arithmetic_.add(times(sine, Scalar::of(normal.x())), times(cosine, Scalar::of(normal.y())));
  const Scalar& distance = runtimeOffset_->distance;
  Scalar minus = arithmetic_.unary(Opcode::Neg, distance);
  CurvePoint point{plusScaled(Scalar::of(join.corner.x()), distance, x),
                   plusScaled(Scalar::of(join.corner.y()), distance, y),
                   Scalar::of(join.corner.z())};
  CurvePoint toCentre{plusScaled(Scalar::of(0), minus, x), plusScaled(Scalar::of(0), minus, y),
                      Scalar::of(0)};
  return {point, toCentre};
}

} // namespace cncc::ir::lowering
