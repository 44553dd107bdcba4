// A cut beside its curve (`side=left|right`, `comp=host`): the tool centre
// runs on the exact offset of the curve by the tool's radius
// (geom/offset_curve.h), computed here at the values compiled with. The
// offset is the cut's curve in the cut table, so verify measures the
// executed path against it. Line and arc pieces stay lines and arcs
// (printed as native arcs unless samples= or spacing= choose the points);
// other curves are cut as chords within the cut's tolerance of the offset,
// or as fitted arcs where the target prints them. Before anything is
// emitted the tool must fit: no concave bend tighter than its radius, no
// offset crossing itself (tool-too-large at the cut). With lead=R the tool
// centre enters on a tangent arc of radius R onto the offset's start and
// leaves on one off its end, on the tool's side; the arcs are part of the
// cut's curve in the cut table (as comp=controller's leads are).
#include "part_lowering.h"

#include "cncc/ir/curve_blocks.h"

#include "cncc/geom/arc_fitting.h"
#include "cncc/geom/composite_curve.h"
#include "cncc/geom/discretisation.h"
#include "cncc/geom/line_arc_curves.h"
#include "cncc/geom/offset_clearance.h"
#include "cncc/geom/offset_curve.h"
#include "cncc/ir/printed_grid.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace cncc::ir::lowering {

using namespace frontend;

namespace {

// An arc piece under a translate/rotate/scale chain is still an arc: its
// centre moved, its radius scaled, its angles turned. Nullptr when the map
// is not a rotation times a positive scale.
std::shared_ptr<const geom::Curve> movedArc(const geom::ArcCurve& arc, const Affine& transform) {
  const Eigen::Matrix2d& linear = transform.linear;
  double determinant = linear(0, 0) * linear(1, 1) - linear(0, 1) * linear(1, 0);
  double scale = std::sqrt(std::fabs(determinant));
  double turn = std::atan2(linear(1, 0), linear(0, 0));
  Eigen::Matrix2d rotation;
  rotation << std::cos(turn), -std::sin(turn), std::sin(turn), std::cos(turn);
  if (!(scale > 0) || (linear - scale * rotation).norm() > 1e-12 * (1 + scale)) {
    return nullptr;
  }
  return std::make_shared<geom::ArcCurve>(
      linear * arc.centre() + transform.offset, scale * arc.radius(), arc.startAngle() + turn,
      arc.sweep(), transform.zScale * arc.startZ(), transform.zScale * arc.zChange());
}

} // namespace

// The cut's pieces in part coordinates, lines and arcs kept as such.
std::vector<std::shared_ptr<const geom::Curve>> movedPieces(const CutCurve& curve) {
  std::vector<std::shared_ptr<const geom::Curve>> pieces;
  for (const CurvePiece& piece : curve.pieces) {
    const geom::Curve& own = *piece.geometry;
    if (piece.transform.isIdentity()) {
      pieces.push_back(piece.geometry);
    } else if (const auto* line = dynamic_cast<const geom::LineCurve*>(&own)) {
      geom::ParameterRange domain = line->domain();
      pieces.push_back(
          std::make_shared<geom::LineCurve>(piece.transform.apply(line->point(domain.t0)),
                                            piece.transform.apply(line->point(domain.t1))));
    } else if (auto arc = dynamic_cast<const geom::ArcCurve*>(&own);
               arc != nullptr && movedArc(*arc, piece.transform)) {
      pieces.push_back(movedArc(*arc, piece.transform));
    } else {
      pieces.push_back(std::make_shared<TransformedCurve>(piece.geometry, piece.transform));
    }
  }
  return pieces;
}

std::shared_ptr<const geom::Curve>
joinedPieces(const std::vector<std::shared_ptr<const geom::Curve>>& pieces) {
  if (pieces.size() == 1) {
    return pieces.front();
  }
  return std::make_shared<geom::CompositeCurve>(pieces, pathJoinTolerance);
}

bool isLineCurve(const geom::Curve& curve) {
  return dynamic_cast<const geom::LineCurve*>(&curve) != nullptr;
}

bool isArcCurve(const geom::Curve& curve) {
  return dynamic_cast<const geom::ArcCurve*>(&curve) != nullptr;
}

PieceJoin pieceJoin(const geom::Curve& before, const geom::Curve& after, double distance) {
  PieceJoin join;
  geom::ParameterRange own = before.domain();
  join.corner = before.point(own.t1);
  join.before = geom::leftNormalOf(before.derivative(own.t1)).head<2>();
  join.after = geom::leftNormalOf(after.derivative(after.domain().t0)).head<2>();
  join.turn = geom::cornerTurn(before, after);
  // Offsets that meet (within geom's tangent join) are joined directly.
  if (std::fabs(distance) * (join.before - join.after).norm() <= 1e-7) {
    join.kind = PieceJoin::Direct;
  } else {
    join.kind = distance * join.turn < 0 ? PieceJoin::CornerArc : PieceJoin::Crossing;
  }
  return join;
}

std::vector<PieceJoin> pieceJoins(const std::vector<std::shared_ptr<const geom::Curve>>& pieces,
                                  double distance, bool& closed) {
  std::vector<PieceJoin> joins;
  for (std::size_t p = 0; p + 1 < pieces.size(); ++p) {
    joins.push_back(pieceJoin(*pieces[p], *pieces[p + 1], distance));
  }
  const geom::Curve& first = *pieces.front();
  const geom::Curve& last = *pieces.back();
  closed = pieces.size() > 1 &&
           (last.point(last.domain().t1) - first.point(first.domain().t0)).norm() <= 1e-9;
  if (closed) {
    joins.push_back(pieceJoin(last, first, distance));
  }
  return joins;
}

// The offset as line and arc moves, when it is made of nothing else.
std::optional<std::vector<geom::ArcSegment>> exactSegments(const geom::Curve& offset) {
  std::vector<const geom::Curve*> parts = geom::piecesOf(offset);
  std::vector<geom::ArcSegment> segments;
  for (const geom::Curve* part : parts) {
    geom::ParameterRange domain = part->domain();
    geom::ArcSegment segment;
    segment.start = part->point(domain.t0);
    segment.end = part->point(domain.t1);
    if (const auto* arc = dynamic_cast<const geom::ArcCurve*>(part)) {
      if (arc->zChange() != 0) {
        return std::nullopt; // a helix: its height is not an arc move's
      }
      // One move turns at most half a circle (ArcSegment), so a longer arc
      // is split into equal parts.
      int count = static_cast<int>(std::ceil(std::fabs(arc->sweep()) / std::numbers::pi - 1e-12));
      for (int k = 0; k < count; ++k) {
        double from = domain.t0 + domain.length() * k / count;
        double to = domain.t0 + domain.length() * (k + 1) / count;
        geom::ArcSegment piece;
        piece.kind = geom::ArcSegmentKind::Arc;
        piece.start = arc->point(from);
        piece.end = arc->point(to);
        piece.centre = arc->centre();
        piece.radius = arc->radius();
        piece.sweep = arc->sweep() / count;
        piece.direction =
            arc->sweep() > 0 ? geom::ArcDirection::CounterClockwise : geom::ArcDirection::Clockwise;
        segments.push_back(piece);
      }
    } else if (isLineCurve(*part)) {
      segments.push_back(segment);
    } else {
      return std::nullopt;
    }
  }
  return segments;
}

double PartLowering::offsetDistance(const CutStmt& cut, const Modifier& side, bool controller) {
  if (toolDiameter_ == nullptr) {
    fail(side.span(), "side= runs the tool at its radius beside the curve, but no tool is chosen",
         DiagnosticKind::SideWithoutTool);
  }
  // Offsets are computed here: on a controller-side target what they
  // depend on must not be a parameter, but for the tool's diameter when the
  // controller computes the offset (controller_offset_cuts.cpp), as its laps
  // do on every target (a host's legalisation fixes it, or lowerOffsetCut
  // where they cannot follow); the passes' depth and step may be (the
  // sweep's pass loop computes them).
  std::optional<ParameterUse> use = parameterUse(cut, toolDiameter_);
  if (use && use->what == "tool diameter" && !controller) {
    double radius = evaluate(*toolDiameter_, environment_).number / 2;
    return wordOf(*side.value) == "left" ? radius : -radius;
  }
  if (use && options_.controllerLoops) {
    fail(cut.span,
         fmt::format("this cut beside the curve (side=) has its {} depend on parameter '{}': on "
                     "this target the offset path is computed by the compiler, which needs its "
                     "value{}",
                     use->what, use->parameter,
                     controller ? "" : " (only the tool diameter may be a parameter)"),
         DiagnosticKind::UnsupportedConstruct);
  }
  double radius = constantNumber(*toolDiameter_, "the tool diameter") / 2;
  return wordOf(*side.value) == "left" ? radius : -radius;
}

DrawnClearance::DrawnClearance(const std::vector<std::shared_ptr<const geom::Curve>>& pieces,
                               double slack)
    : drawn(joinedPieces(pieces)),
      budgeted(std::make_unique<geom::BudgetedCurve>(*drawn, maximumCurveEvaluations)),
      proximity(std::make_unique<geom::CurveProximity>(*budgeted, slack / 4)), slack(slack) {}

std::variant<geom::PiecesOffset, OffsetTrouble>
offsetOrTrouble(const std::vector<std::shared_ptr<const geom::Curve>>& pieces, double distance,
                const DrawnClearance* drawn) {
  double radius = std::fabs(distance);
  for (const auto& piece : pieces) {
    // A line never bends; an arc's offset radius is checked as it is built.
    if (isLineCurve(*piece) || isArcCurve(*piece)) {
      continue;
    }
    geom::CurvatureExtreme concave = geom::offsetClearance(*piece, distance).concave;
    if (!(concave.radius > radius)) {
      return OffsetTrouble{OffsetTrouble::Bend, concave.point, concave.radius, "", 0};
    }
  }
  geom::PiecesOffset parts;
  try {
    parts = geom::offsetOfPiecesWithOrigins(pieces, distance);
  } catch (const geom::OffsetError& error) {
    return OffsetTrouble{error.radius > 0 ? OffsetTrouble::InsideArc : OffsetTrouble::Corner,
                         error.place, error.radius, error.what(), 0};
  } catch (const geom::GeometryError& error) {
    return OffsetTrouble{OffsetTrouble::Degenerate, {}, 0, error.what(), 0};
  }
  try {
    if (std::optional<Eigen::Vector3d> crossing = geom::offsetSelfCrossing(*parts.curve)) {
      return OffsetTrouble{OffsetTrouble::SelfCrossing, *crossing, 0, "", 0};
    }
    if (drawn != nullptr) {
      if (std::optional<geom::ClearanceViolation> near = geom::offsetClearanceViolation(
              *parts.curve, *drawn->proximity, radius, drawn->slack)) {
        return OffsetTrouble{OffsetTrouble::TooNear, near->centre, near->distance, "", 0};
      }
    }
  } catch (const geom::EvaluationBudgetExceeded& error) {
    return OffsetTrouble{OffsetTrouble::TooMuchWork, {}, 0, "", error.limit};
  }
  return parts;
}

namespace {

// The distance from `point` to a drawn piece (exact to rounding).
double distanceToPiece(const geom::Curve& piece, const Eigen::Vector3d& point) {
  if (const auto* line = dynamic_cast<const geom::LineCurve*>(&piece)) {
    geom::ParameterRange domain = line->domain();
    Eigen::Vector3d a = line->point(domain.t0);
    Eigen::Vector3d along = line->point(domain.t1) - a;
    double share = along.squaredNorm() > 0
                       ? std::clamp((point - a).dot(along) / along.squaredNorm(), 0.0, 1.0)
                       : 0.0;
    return (a + share * along - point).norm();
  }
  return geom::CurveProximity(piece, 1e-6).closestPoint(point).distance;
}

// "piece 3 (a line)" of a path, for the diagnostics.
std::string pieceName(const geom::Curve& piece, std::size_t index) {
  const char* kind = isLineCurve(piece) ? " (a line)" : isArcCurve(piece) ? " (an arc)" : "";
  return fmt::format("piece {}{}", index + 1, kind);
}

// Which pieces of a path the tool runs beside at `centre` (on a crossing of
// the offset: the two whose offsets meet; too near: the one it is beside
// and the one it comes near), empty for a curve of one piece.
std::string besidePieces(const std::vector<std::shared_ptr<const geom::Curve>>& pieces,
                         const Eigen::Vector3d& centre, double radius, bool tooNear) {
  if (pieces.size() < 2) {
    return "";
  }
  std::vector<double> distances;
  for (const auto& piece : pieces) {
    distances.push_back(distanceToPiece(*piece, centre));
  }
  // The piece the tool runs beside is at its radius; the one it cuts into nearer.
  std::size_t beside = 0;
  std::size_t into = 0;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    if (distances[i] < distances[into]) {
      into = i;
    }
  }
  double closest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    if ((!tooNear || i != into) && std::fabs(distances[i] - radius) < closest) {
      closest = std::fabs(distances[i] - radius);
      beside = i;
    }
  }
  if (tooNear) {
    return fmt::format("beside {} comes {:.4f} from {}", pieceName(*pieces[beside], beside),
                       distances[into], pieceName(*pieces[into], into));
  }
  // A crossing is at the radius from both pieces whose offsets meet there.
  std::size_t other = beside;
  closest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    if (i != beside && std::fabs(distances[i] - radius) < closest) {
      closest = std::fabs(distances[i] - radius);
      other = i;
    }
  }
  std::size_t first = std::min(beside, other);
  std::size_t second = std::max(beside, other);
  return fmt::format("the tool beside {} meets itself beside {}", pieceName(*pieces[first], first),
                     pieceName(*pieces[second], second));
}

} // namespace

// The offset's chords within `tolerance` estimated from the drawn curve,
// before the work that grows with them (the clearance, the offset, its
// checks): an offset far past the limit of one cut (a polar range of 1e300)
// is refused at once, not after seconds. Past twice the limit, as an
// estimate; the offset's own chords are checked where it is cut.
void PartLowering::checkOffsetChordCount(
    const CutStmt& cut, const std::vector<std::shared_ptr<const geom::Curve>>& pieces,
    double distance, double tolerance) {
  double chords = 0;
  try {
    chords = geom::estimateDiscretisation(*joinedPieces(pieces), tolerance, distance).chords;
  } catch (const geom::GeometryError&) {
    return; // the offset itself reports what the estimate could not take
  }
  if (chords > 2.0 * static_cast<double>(maximumChordsPerCut)) {
    tooManyChords(cut, "the tool's path beside this curve", chords, tolerance);
  }
}

geom::PiecesOffset PartLowering::checkedOffset(const CutStmt& cut, const CutCurve& curve,
                                               double distance, const DrawnClearance* drawn) {
  std::vector<std::shared_ptr<const geom::Curve>> pieces = movedPieces(curve);
  std::optional<DrawnClearance> own;
  if (drawn == nullptr) {
    own.emplace(drawnClearance(cut, curve, pieces, distance));
    drawn = &*own;
  }
  auto result = offsetOrTrouble(pieces, distance, drawn);
  if (auto* offset = std::get_if<geom::PiecesOffset>(&result)) {
    return *offset;
  }
  const OffsetTrouble& trouble = std::get<OffsetTrouble>(result);
  double radius = std::fabs(distance);
  auto inside = [&](std::string_view what) {
    return fmt::format("the tool's radius {:g} is too large for this curve: {} {:.4g} at ({:.4f}, "
                       "{:.4f}), where the tool runs on the inside of the bend; it would cut "
                       "into the part there",
                       radius, what, trouble.radius, trouble.place.x(), trouble.place.y());
  };
  switch (trouble.kind) {
  case OffsetTrouble::Bend:
    fail(cut.span, inside("its radius of curvature is"), DiagnosticKind::ToolTooLarge);
  case OffsetTrouble::InsideArc:
    fail(cut.span, inside("the radius of an arc it runs inside is"), DiagnosticKind::ToolTooLarge);
  case OffsetTrouble::Corner:
    fail(cut.span,
         fmt::format("the tool's radius {:g} is too large for this path: {}", radius,
                     trouble.message),
         DiagnosticKind::ToolTooLarge);
  case OffsetTrouble::Degenerate:
    fail(cut.curve->span, fmt::format("cannot offset this curve: {}", trouble.message),
         DiagnosticKind::DegenerateCurve);
  case OffsetTrouble::TooMuchWork:
    offsetCheckTooLarge(cut, trouble.limit);
  case OffsetTrouble::TooNear: {
    std::string which = besidePieces(pieces, trouble.place, radius, true);
    fail(cut.span,
         fmt::format("the tool's radius {:g} is too large for this {}: its centre {} at ({:.4f}, "
                     "{:.4f}); it would cut {:.4f} into the part there",
                     radius, pieces.size() > 1 ? "path" : "curve",
                     which.empty() ? fmt::format("comes {:.4f} from another part of the curve",
                                                 trouble.radius)
                                   : which,
                     trouble.place.x(), trouble.place.y(), radius - trouble.radius),
         DiagnosticKind::ToolTooLarge);
  }
  case OffsetTrouble::SelfCrossing:
    break;
  }
  std::string where = besidePieces(pieces, trouble.place, radius, false);
  fail(cut.span,
       fmt::format("the tool's radius {:g} is too large for this {}: the offset path "
                   "crosses itself at ({:.4f}, {:.4f}){}, where the curve's sides are less than "
                   "two tool radii apart",
                   radius, pieces.size() > 1 ? "path" : "curve", trouble.place.x(),
                   trouble.place.y(), where.empty() ? "" : " (" + where + ")"),
       DiagnosticKind::ToolTooLarge);
}

DrawnClearance
PartLowering::drawnClearance(const CutStmt& cut, const CutCurve& curve,
                             const std::vector<std::shared_ptr<const geom::Curve>>& pieces,
                             double distance) {
  // A curve past the number range by more than the distance: its offset is
  // too, refused before the work below (which its size would run to the bound).
  checkCutBounds(cut, *curve.geometry, std::fabs(distance));
  // The cut may leave its tolerance unreported past the curve (as verify
  // does); a cut without one (samples=) the default.
  double slack = chordTolerance(cut).value_or(defaultTolerance);
  checkOffsetChordCount(cut, pieces, distance, slack);
  try {
    return DrawnClearance(pieces, slack);
  } catch (const geom::EvaluationBudgetExceeded& error) {
    offsetCheckTooLarge(cut, error.limit);
  }
}

void PartLowering::offsetCheckTooLarge(const CutStmt& cut, std::size_t limit) {
  fail(cut.span,
       fmt::format("checking that the tool keeps its radius from this curve everywhere takes more "
                   "than {} steps (points of the curve, or pairs of the offset's chords); that is "
                   "the limit of one cut",
                   limit),
       DiagnosticKind::ProgramTooLarge);
}

bool PartLowering::lowerOffsetCut(const CutStmt& cut) {
  const Modifier* side = findModifier(cut, "side");
  std::string word = side != nullptr && side->value ? wordOf(*side->value) : "";
  if (word != "left" && word != "right") {
    return false;
  }
  const Modifier* comp = findModifier(cut, "comp");
  bool controller = comp != nullptr && comp->value && wordOf(*comp->value) == "controller";
  double distance = offsetDistance(cut, *side, controller);
  if (controller) {
    lowerCompensatedCut(cut, *comp, distance);
    return true;
  }
  // The controller's laps on every target where they can follow the offset
  // (a host's legalisations cut them at the compiled radius); a host's own
  // offset where the curve reads parameters too (a controller refused
  // that in offsetDistance) or where they cannot follow.
  bool runtime = !parametersOf(*toolDiameter_).empty();
  bool curveReads = !parametersOf(*cut.curve).empty();
  if (!(runtime && curveReads) && lowerControllerOffsetCut(cut, distance, runtime)) {
    return true;
  }
  if (runtime) { // the host's offset at the compiled radius
    fixParameters(*toolDiameter_, toolDiameter_->span, "the tool diameter");
  }
  lowerHostOffsetCut(cut, distance);
  return true;
}

// The offset computed here: spline blocks fitted to it, or each lap as arcs
// or points (hostOffsetLaps), with lead arcs where lead= asks.
void PartLowering::lowerHostOffsetCut(const CutStmt& cut, double distance) {
  CutCurve curve = cutCurve(cut);
  geom::PiecesOffset parts = checkedOffset(cut, curve, distance);
  std::shared_ptr<const geom::Curve> offset = parts.curve;
  std::optional<CompensatedLeads> leads = hostLeads(cut, curve, *offset, distance);
  // With leads the cut's path, which verify measures, runs on their arcs
  // too; they meet the offset at its ends on the printed grid.
  std::shared_ptr<const geom::Curve> path = offset;
  if (leads) {
    path = std::make_shared<geom::CompositeCurve>(
        std::vector<std::shared_ptr<const geom::Curve>>{leads->leadIn.curve(), offset,
                                                        leads->leadOut.curve()},
        std::max(1e-9, options_.coordinateIncrement));
  }
  checkCutBounds(cut, *path);
  std::shared_ptr<const BesideCurve> beside = besideCurve(cut, curve, parts, distance);
  HostOffsetLaps laps = hostOffsetLaps(cut, offset, *beside, rampEntry(cut));
  nativeArcs_ = laps.arcs.has_value(); // checkMethod says so
  warnSplineOffsetWithLeads(cut);
  HostCut begun = beginHostCut(cut, laps.blocksAsked);
  geom::ParameterRange domain = offset->domain();
  if (begun.ramp && (offset->point(domain.t0) - offset->point(domain.t1)).norm() > 1e-6) {
    unsupported(findModifier(cut, "entry")->span(), "entry=ramp on a curve that does not close");
  }
  ValueId feed = arithmetic_.value(begun.feed);
  ValueId safe = arithmetic_.value(*safe_);
  bool activatesLengthOffset =
      beginCutMoves({path, chordTolerance(cut).value_or(std::numeric_limits<double>::quiet_NaN()),
                     cut.span, methodOf(cut), laps.arcMoves});
  noteMethodSpan(cut);
  markCutBeside(curve.geometry, std::fabs(distance));
  Eigen::Vector3d start = offset->point(domain.t0);
  Eigen::Vector3d finish = offset->point(domain.t1);
  if (laps.arcs) {
    double increment = options_.coordinateIncrement;
    for (Eigen::Vector3d* end : {&start, &finish}) {
      *end = {onPrintedGrid(end->x(), increment), onPrintedGrid(end->y(), increment), end->z()};
    }
  }
  if (leads) {
    start = onPrintedGrid(leads->leadIn.start, options_.coordinateIncrement);
    finish = onPrintedGrid(leads->leadOut.end, options_.coordinateIncrement);
  }
  // The passes: the controller's loop where it computes depth= and step=.
  std::array<ValueId, 2> end{builder_.constant(finish.x()), builder_.constant(finish.y())};
  SweepStart from{builder_.constant(start.x()), builder_.constant(start.y()), safe,
                  activatesLengthOffset, Scalar::of(start.z())};
  emitSweep(
      cut, begun.ramp, from, end, feed,
      [&](ValueId zFrom, ValueId zTo) { emitHostOffsetLap(laps, *beside, zFrom, zTo, feed, cut); },
      leads ? &*leads : nullptr);
}

// The offset's own lines and arcs where it is made of nothing else (moves at
// once), else where the cut asks for fitted arcs level laps that ask for
// them (fit-arcs decides); the points of the other laps and of a ramp lap:
// a curve.lap (offset_laps.cpp).
HostOffsetLaps PartLowering::hostOffsetLaps(const CutStmt& cut,
                                            const std::shared_ptr<const geom::Curve>& offset,
                                            const BesideCurve& beside, bool ramp) {
  HostOffsetLaps laps;
  if (wantsNativeArcs(cut)) {
    laps.arcs = exactSegments(*offset);
    laps.arcMoves = laps.arcs ? CutArcs::Native : CutArcs::None;
  }
  // A method= spline asks for the target's blocks, after the offset's own
  // arcs; without lead arcs, which the blocks would not follow.
  laps.blocksAsked = !laps.arcs && findModifier(cut, "lead") == nullptr &&
                     splineKindOfMethod(methodOf(cut)).has_value();
  if (!laps.arcs) {
    if (std::optional<ArcsAsked> asked = arcsAskedBy(cut)) {
      laps.arcsTable = besideChordsCurve(cut, beside, asked, laps.blocksAsked);
    }
  }
  if (!(laps.arcs || laps.arcsTable) || ramp) {
    laps.pointsTable = besideChordsCurve(cut, beside, std::nullopt, laps.blocksAsked);
  }
  return laps;
}

void PartLowering::emitHostOffsetLap(const HostOffsetLaps& laps, const BesideCurve& beside,
                                     ValueId zFrom, ValueId zTo, ValueId feed, const CutStmt& cut) {
  bool level = heightOf(zFrom).sameAs(heightOf(zTo));
  if (laps.arcsTable && level) {
    emitBesideLapAt(beside, *laps.arcsTable, {zTo, zTo, feed}, cut);
  } else if (laps.arcs && level) {
    emitArcLap(*laps.arcs, planeHeight(laps.arcs->front().start.z(), heightOf(zTo)), feed);
  } else {
    emitBesideLapAt(beside, *laps.pointsTable, {zFrom, zTo, feed}, cut);
  }
}

// lead=R: the tool centre's tangent arcs of radius R onto the offset's
// start and off its end, on the tool's side (the arcs comp=controller runs,
// compensated_cuts.cpp), checked to keep the tool off the part.
std::optional<CompensatedLeads> PartLowering::hostLeads(const CutStmt& cut, const CutCurve& curve,
                                                        const geom::Curve& offset,
                                                        double distance) {
  if (findModifier(cut, "lead") == nullptr) {
    return std::nullopt;
  }
  double toolRadius = std::fabs(distance);
  CompensatedLeads leads =
      tangentLeads(offset, distance, leadRadius(cut, toolRadius), options_.coordinateIncrement);
  leads.offset = distance;
  checkLeadClearance(cut, leads, *joinedPieces(movedPieces(curve)), toolRadius);
  return leads;
}

// Lead arcs with a method= spline on a target that prints spline blocks:
// the offset's chords (the blocks would not follow the leads).
void PartLowering::warnSplineOffsetWithLeads(const CutStmt& cut) {
  std::string method = methodOf(cut);
  bool blocks = options_.splineBlocks || options_.polynomialBlocks || options_.nurbsBlocks;
  if (findModifier(cut, "lead") == nullptr || !splineKindOfMethod(method) ||
      !options_.splineInterpolation || !blocks || !options_.reportSplineAsChords) {
    return;
  }
  diagnostics_->report(DiagnosticKind::SplineAsChords, findModifier(cut, "method")->span(),
                       fmt::format("this cut beside the curve (side=) is cut as straight feed "
                                   "moves within its tolerance of the exact offset: method={} is "
                                   "not built for offsets with lead= on this target yet",
                                   method));
}

// The points of an offset a controller-side target prints are read back by
// tools that print fewer digits than the controller keeps (LinuxCNC's
// rs274: 4 decimals): a hundredth of the tolerance is left for them, on
// every target (the lowering is the same for all).
double PartLowering::offsetChordTolerance(const CutStmt& cut) {
  ToleranceBudget budget = toleranceBudget(cut);
  return budget.forPoints() - (chordTolerance(cut) ? budget.tolerance / 100 : 0);
}

geom::CurveSamples PartLowering::offsetSamples(const CutStmt& cut, const geom::Curve& offset) {
  if (!chordTolerance(cut)) {
    return checkedSamplesFor(cut, offset);
  }
  return chordsWithinBudget(cut, offset, offsetChordTolerance(cut));
}

} // namespace cncc::ir::lowering
