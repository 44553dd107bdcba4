// A cut beside its curve with the controller's cutter radius compensation
// (`side=left|right comp=controller`): the program runs the curve itself
// and the controller offsets it by the radius in the tool's register
// (G41/G42 D.., TARGETS.md), so a shop can tune the radius there. As the
// controls require, compensation is switched on by a linear start-up move
// and off (G40) by a linear move, both off the part, joined to the curve by
// tangent lead-in and lead-out arcs; no spline blocks run inside it (G06.2
// is not allowed with G41/G42), so the curve is cut as chords within its
// tolerance, or as its own lines and arcs.
//
// The cut table holds the tool centre's path at the radius compiled with:
// start-up line, lead-in arc of the lead's radius, the exact offset curve,
// a straight run-out where the curve bends away from the tool at its end,
// lead-out arc and cancel line, which verify measures the executed path
// against (ir/tool_centre_path.h runs the compensation on the host).
#include "part_lowering.h"

#include "cncc/geom/composite_curve.h"
#include "cncc/geom/deviation.h"
#include "cncc/geom/line_arc_curves.h"
#include "cncc/geom/offset_curve.h"
#include "cncc/ir/printed_grid.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <optional>

namespace cncc::ir::lowering {

using namespace frontend;

namespace {

Eigen::Vector3d leftOf(const Eigen::Vector3d& direction) {
  return {-direction.y(), direction.x(), 0};
}

// The unit tangent of the curve's XY projection at t.
Eigen::Vector3d planeTangent(const geom::Curve& curve, double t) {
  Eigen::Vector3d derivative = curve.derivative(t);
  derivative.z() = 0;
  return derivative.normalized();
}

// A quarter circle about `centre` from `start`, turning left for offset > 0.
geom::ArcSegment quarterArc(const Eigen::Vector3d& start, const Eigen::Vector3d& centre,
                            const Eigen::Vector3d& end, double offset) {
  geom::ArcSegment arc;
  arc.kind = geom::ArcSegmentKind::Arc;
  arc.start = start;
  arc.end = end;
  arc.centre = centre.head<2>();
  arc.radius = (start - centre).head<2>().norm();
  arc.sweep = offset > 0 ? std::numbers::pi / 2 : -std::numbers::pi / 2;
  arc.direction = offset > 0 ? geom::ArcDirection::CounterClockwise : geom::ArcDirection::Clockwise;
  return arc;
}

// The programmed leads of a curve from `first` to `last` (points and unit
// tangents): each arc's centre lies the programmed radius away on the tool's
// side, and the start-up and cancel lines run that far along the normal.
CompensatedLeads programmedLeads(const Eigen::Vector3d& first, const Eigen::Vector3d& firstTangent,
                                 const Eigen::Vector3d& last, const Eigen::Vector3d& lastTangent,
                                 double offset, double radius) {
  double side = offset > 0 ? 1.0 : -1.0;
  Eigen::Vector3d inNormal = side * leftOf(firstTangent);
  Eigen::Vector3d inCentre = first + radius * inNormal;
  Eigen::Vector3d inStart = inCentre - radius * firstTangent;
  Eigen::Vector3d outNormal = side * leftOf(lastTangent);
  Eigen::Vector3d outCentre = last + radius * outNormal;
  Eigen::Vector3d outEnd = outCentre + radius * lastTangent;
  CompensatedLeads leads;
  leads.startUp = inStart + radius * inNormal;
  leads.leadIn = quarterArc(inStart, inCentre, first, offset);
  leads.leadOut = quarterArc(last, outCentre, outEnd, offset);
  leads.cancel = outEnd + radius * outNormal;
  leads.offset = offset;
  return leads;
}

// Where the tool's centre runs when the controller offsets the leads and
// the curve's pieces as one open chain, at the radius compiled with: what
// verify measures against. The chain is open even where the curve closes,
// as the leads join it there.
std::shared_ptr<const geom::Curve>
toolCentrePath(const CompensatedLeads& leads,
               const std::vector<std::shared_ptr<const geom::Curve>>& contour) {
  std::vector<std::shared_ptr<const geom::Curve>> chain{leads.leadIn.curve()};
  chain.insert(chain.end(), contour.begin(), contour.end());
  if (leads.runOut) {
    chain.push_back(std::make_shared<geom::LineCurve>(
        contour.back()->point(contour.back()->domain().t1), leads.leadOut.start));
  }
  chain.push_back(leads.leadOut.curve());
  std::shared_ptr<const geom::Curve> offset = geom::offsetOfPieces(chain, leads.offset);
  geom::ParameterRange domain = offset->domain();
  std::vector<std::shared_ptr<const geom::Curve>> pieces{
      std::make_shared<geom::LineCurve>(leads.startUp, offset->point(domain.t0)), offset,
      std::make_shared<geom::LineCurve>(offset->point(domain.t1), leads.cancel)};
  return std::make_shared<geom::CompositeCurve>(std::move(pieces));
}

// The largest distance of the exact offset over [ta, tb] from the line the
// controller offsets the chord C(ta)C(tb) to: where the curve's bend varies
// along the chord (an inflection, a tight bend at one end), the offset strays
// further from its chord than the curve from its own.
double offsetChordDeviation(const geom::Curve& curve, double ta, double tb, double offset) {
  Eigen::Vector3d chord = curve.point(tb) - curve.point(ta);
  chord.z() = 0;
  if (!(chord.norm() > 0)) {
    return 0;
  }
  Eigen::Vector3d along = chord.normalized();
  Eigen::Vector3d base = curve.point(ta) + offset * leftOf(along);
  constexpr int steps = 16;
  double worst = 0;
  for (int i = 0; i <= steps; ++i) {
    double t = ta + (tb - ta) * i / steps;
    Eigen::Vector3d tangent = planeTangent(curve, t);
    if (!tangent.allFinite()) {
      continue;
    }
    Eigen::Vector3d away = curve.point(t) + offset * leftOf(tangent) - base;
    worst = std::max(worst, std::fabs(along.x() * away.y() - along.y() * away.x()));
  }
  return worst;
}

// The chord to `end` (at parameter tb) from ta, halved until its offset keeps
// within `budget` of the exact offset (at most `depth` more times).
void appendOffsetChord(const geom::Curve& curve, double ta, double tb, const Eigen::Vector3d& end,
                       double offset, double budget, int depth, geom::CurveSamples& out) {
  if (depth > 0 && offsetChordDeviation(curve, ta, tb, offset) > budget) {
    double middle = (ta + tb) / 2;
    appendOffsetChord(curve, ta, middle, curve.point(middle), offset, budget, depth - 1, out);
    appendOffsetChord(curve, middle, tb, end, offset, budget, depth - 1, out);
    return;
  }
  out.parameters.push_back(tb);
  out.points.push_back(end);
}

// `samples` of the drawn curve, chords split where the controller's offset
// of them would stray more than `budget` from the exact offset.
geom::CurveSamples withinOffsetBudget(const geom::CurveSamples& samples, const geom::Curve& curve,
                                      double offset, double budget) {
  if (samples.points.size() < 2 || samples.parameters.size() != samples.points.size()) {
    return samples;
  }
  geom::CurveSamples refined;
  refined.parameters.push_back(samples.parameters.front());
  refined.points.push_back(samples.points.front());
  for (std::size_t i = 1; i < samples.points.size(); ++i) {
    appendOffsetChord(curve, samples.parameters[i - 1], samples.parameters[i], samples.points[i],
                      offset, budget, 8, refined);
  }
  return refined;
}

// Whether the curve bends away from the tool where it ends (curvature
// against the offset's side): there its last chord meets the lead-out arc,
// which bends towards the tool, at a slight outside corner, which LinuxCNC
// refuses ("arc move in concave corner cannot be reached by the tool
// without gouging"). A straight run along the end tangent between the two
// makes the corner one between lines, which every control offsets; on that
// side the run leaves the part.
bool needsRunOut(const geom::Curve& contour, double offset) {
  double t = contour.domain().t1;
  Eigen::Vector3d first = contour.derivative(t);
  Eigen::Vector3d second = contour.secondDerivative(t);
  double bend = first.x() * second.y() - first.y() * second.x(); // left positive
  return bend * offset < 0;
}

// The leads with the lead-out, and the cancel line after it, moved
// `length` along the curve's end tangent.
void withRunOut(CompensatedLeads& leads, const Eigen::Vector3d& tangent, double length) {
  Eigen::Vector3d shift = length * tangent;
  leads.leadOut.start += shift;
  leads.leadOut.end += shift;
  leads.leadOut.centre += shift.head<2>();
  leads.cancel += shift;
  leads.runOut = true;
}

// The tool centre's arc for a programmed lead arc the controller offsets by
// `toolRadius` towards its centre: the same centre, the lead's radius.
geom::ArcSegment centreArc(const geom::ArcSegment& programmed, double toolRadius) {
  geom::ArcSegment arc = programmed;
  Eigen::Vector3d centre(programmed.centre.x(), programmed.centre.y(), 0);
  for (Eigen::Vector3d* end : {&arc.start, &arc.end}) {
    Eigen::Vector3d inwards = centre - *end;
    inwards.z() = 0;
    *end += toolRadius * inwards.normalized();
  }
  arc.radius = programmed.radius - toolRadius;
  return arc;
}

// A convex corner of the curve: where the controller is told to go round it
// on an arc of the radius (G39), towards the next move's start direction.
struct ConvexCorner {
  Eigen::Vector3d point;
  Eigen::Vector3d nextTangent; // unit, in the plane
  double parameter = 0;        // on the pieces joined (geom::CompositeCurve)
};

// Corners of less than this (radians) are left to the controller's own
// meeting of the offsets, off the arc by r (1 / cos(a / 2) - 1): 4e-7 r.
constexpr double cornerArcAngle = 1e-3;

// Whether the turn from `incoming` to `outgoing` (unit tangents) is a convex
// corner for a tool `offset` to the left (negative: right) of the path.
bool isConvexCorner(const Eigen::Vector3d& incoming, const Eigen::Vector3d& outgoing,
                    double offset) {
  double turn = incoming.x() * outgoing.y() - incoming.y() * outgoing.x(); // left positive
  double angle = std::atan2(std::fabs(turn), incoming.head<2>().dot(outgoing.head<2>()));
  return angle > cornerArcAngle && turn * offset < 0;
}

// The convex corners between the curve's pieces.
std::vector<ConvexCorner>
convexCorners(const std::vector<std::shared_ptr<const geom::Curve>>& pieces, double offset) {
  std::vector<ConvexCorner> corners;
  double join = 0;
  for (std::size_t i = 0; i + 1 < pieces.size(); ++i) {
    geom::ParameterRange domain = pieces[i]->domain();
    join += domain.t1 - domain.t0;
    Eigen::Vector3d incoming = planeTangent(*pieces[i], domain.t1);
    Eigen::Vector3d outgoing = planeTangent(*pieces[i + 1], pieces[i + 1]->domain().t0);
    if (incoming.allFinite() && outgoing.allFinite() &&
        isConvexCorner(incoming, outgoing, offset)) {
      corners.push_back({pieces[i]->point(domain.t1), outgoing, join});
    }
  }
  return corners;
}

// `samples` with a sample at each corner: the curve is sampled as one, so
// a chord may cut across a corner, and G39 goes where the corner is.
geom::CurveSamples withCornerSamples(const geom::CurveSamples& samples,
                                     const std::vector<ConvexCorner>& corners) {
  if (samples.parameters.size() != samples.points.size()) {
    return samples;
  }
  geom::CurveSamples joined;
  std::size_t corner = 0;
  for (std::size_t i = 0; i < samples.points.size(); ++i) {
    double t = samples.parameters[i];
    for (; corner < corners.size() && corners[corner].parameter <= t; ++corner) {
      const ConvexCorner& at = corners[corner];
      bool sampled = (samples.points[i] - at.point).norm() <= 1e-9 * std::max(1.0, at.point.norm());
      if (!sampled && i > 0) {
        joined.parameters.push_back(at.parameter);
        joined.points.push_back(at.point);
      }
    }
    joined.parameters.push_back(t);
    joined.points.push_back(samples.points[i]);
  }
  return joined;
}

// The unit tangent of an arc or line segment where it starts (`atEnd`: ends).
Eigen::Vector3d segmentTangent(const geom::ArcSegment& segment, bool atEnd) {
  if (segment.kind == geom::ArcSegmentKind::Line) {
    Eigen::Vector3d along = segment.end - segment.start;
    along.z() = 0;
    return along.normalized();
  }
  Eigen::Vector3d point = atEnd ? segment.end : segment.start;
  Eigen::Vector3d radial(point.x() - segment.centre.x(), point.y() - segment.centre.y(), 0);
  Eigen::Vector3d tangent = leftOf(radial.normalized());
  return segment.direction == geom::ArcDirection::Clockwise ? Eigen::Vector3d(-tangent) : tangent;
}

// The index of the sample at `point` from `from` on, if one is there.
std::optional<std::size_t> sampleAt(const geom::CurveSamples& samples, const Eigen::Vector3d& point,
                                    std::size_t from) {
  for (std::size_t i = from; i < samples.points.size(); ++i) {
    if ((samples.points[i] - point).norm() <= 1e-9 * std::max(1.0, point.norm())) {
      return i;
    }
  }
  return std::nullopt;
}

} // namespace

CompensatedLeads tangentLeads(const geom::Curve& path, double offset, double radius,
                              double increment) {
  geom::ParameterRange domain = path.domain();
  return programmedLeads(onPrintedGrid(path.point(domain.t0), increment),
                         planeTangent(path, domain.t0),
                         onPrintedGrid(path.point(domain.t1), increment),
                         planeTangent(path, domain.t1), offset, radius);
}

void PartLowering::checkLeadClearance(const CutStmt& cut, const CompensatedLeads& centre,
                                      const geom::Curve& contour, double toolRadius) {
  const Modifier* lead = findModifier(cut, "lead");
  frontend::SourceSpan at = lead != nullptr ? lead->span() : cut.span;
  // Closest points exact to rounding (Newton on the curve): the slack is
  // only for that rounding and the printed grid the arcs' ends are on.
  constexpr double accuracy = 1e-4;
  constexpr double slack = 1e-4;
  constexpr int steps = 64;
  geom::CurveProximity part(contour, accuracy);
  double planeZ = contour.point(contour.domain().t0).z();
  auto check = [&](const geom::ArcSegment& arc, bool leadIn, std::string_view which) {
    std::shared_ptr<const geom::Curve> curve = arc.curve();
    geom::ParameterRange domain = curve->domain();
    // The end that joins the path touches the tool's circle about it.
    double nearest = std::numeric_limits<double>::infinity();
    Eigen::Vector3d where = Eigen::Vector3d::Zero();
    for (int k = leadIn ? 0 : 1; k < (leadIn ? steps : steps + 1); ++k) {
      Eigen::Vector3d point = curve->point(domain.t0 + domain.length() * k / steps);
      point.z() = planeZ;
      double distance = part.closestPoint(point).distance;
      if (distance < nearest) {
        nearest = distance;
        where = point;
      }
    }
    if (nearest < toolRadius - slack) {
      fail(at,
           fmt::format("the {} arc of radius {:g} runs the tool's centre {:.4f} from the curve "
                       "at ({:.4f}, {:.4f}), less than the tool's radius {:g}: the tool would "
                       "cut into the part there; choose a smaller lead= or start the curve "
                       "where the tool has room beside it",
                       which, arc.radius, nearest, where.x(), where.y(), toolRadius),
           DiagnosticKind::ToolTooLarge);
    }
  };
  check(centre.leadIn, true, "lead-in");
  check(centre.leadOut, false, "lead-out");
}

// G39 towards `tangent`: a 10 mm vector, so that the printed direction is
// true to 0.003 degrees on a 0.001 mm grid.
void PartLowering::emitCornerArc(const Eigen::Vector3d& tangent) {
  double increment = options_.coordinateIncrement;
  ValueId y = builder_.constant(onPrintedGrid(10 * tangent.y(), increment));
  ValueId x = builder_.constant(onPrintedGrid(10 * tangent.x(), increment));
  builder_.cornerArc(x, y);
}

// The curve's arcs and lines, with G39 at each convex corner between them.
void PartLowering::emitArcLapWithCorners(const std::vector<geom::ArcSegment>& segments,
                                         double offset, ValueId z, ValueId feed) {
  std::size_t first = 0;
  for (std::size_t i = 0; i + 1 < segments.size(); ++i) {
    Eigen::Vector3d outgoing = segmentTangent(segments[i + 1], false);
    bool afterArc = segments[i].kind == geom::ArcSegmentKind::Arc;
    if (!isConvexCorner(segmentTangent(segments[i], true), outgoing, offset) ||
        (afterArc && options_.cornerArcsAfterLinesOnly)) {
      continue;
    }
    emitArcLap({segments.begin() + static_cast<std::ptrdiff_t>(first),
                segments.begin() + static_cast<std::ptrdiff_t>(i + 1)},
               z, feed);
    emitCornerArc(outgoing);
    first = i + 1;
  }
  emitArcLap({segments.begin() + static_cast<std::ptrdiff_t>(first), segments.end()}, z, feed);
}

double PartLowering::leadRadius(const CutStmt& cut, double toolRadius) {
  const Modifier* lead = findModifier(cut, "lead");
  if (lead == nullptr || !lead->value) {
    return toolRadius;
  }
  double radius = constantNumber(*lead->value, "the lead radius");
  if (!(radius > 0) || !std::isfinite(radius)) {
    fail(lead->span(),
         fmt::format("lead= is the radius of the tool centre's lead arcs: it must "
                     "be positive, not {:g}",
                     radius),
         DiagnosticKind::UnsupportedConstruct);
  }
  return radius;
}

void PartLowering::lowerCompensatedCut(const CutStmt& cut, const Modifier& comp, double distance) {
  if (!options_.cutterCompensation) {
    fail(comp.span(),
         fmt::format("comp=controller (the controller's cutter radius compensation, G41/G42) is "
                     "not available on {} yet; leave comp= out for the compiler's "
                     "exact offset (comp=host)",
                     options_.targetName.empty() ? std::string("this target")
                                                 : "the " + options_.targetName + " target"),
         DiagnosticKind::CompensationUnavailable);
  }
  if (rampEntry(cut)) {
    unsupported(findModifier(cut, "entry")->span(), "entry=ramp with comp=controller");
  }
  CutCurve curve = cutCurve(cut);
  checkedOffset(cut, curve, distance); // the tool fits the curve
  HostCut begun = beginHostCut(cut);
  std::string method = methodOf(cut);
  if (options_.splineInterpolation && options_.reportSplineAsChords && !method.empty() &&
      method != "linear") {
    diagnostics_->report(DiagnosticKind::SplineAsChords, findModifier(cut, "method")->span(),
                         fmt::format("no spline blocks run inside the controller's cutter radius "
                                     "compensation (G06.2 is not allowed with G41/G42): "
                                     "method={} is cut as straight feed moves within the cut's "
                                     "tolerance",
                                     method));
  }
  std::vector<std::shared_ptr<const geom::Curve>> pieces = movedPieces(curve);
  std::shared_ptr<const geom::Curve> contour = joinedPieces(pieces);
  geom::ParameterRange domain = contour->domain();
  double increment = options_.coordinateIncrement;
  double toolRadius = std::fabs(distance);
  std::optional<std::vector<geom::ArcSegment>> arcs;
  if (wantsNativeArcs(cut)) {
    arcs = exactSegments(*contour);
  }
  CompensatedLeads leads =
      tangentLeads(*contour, distance, leadRadius(cut, toolRadius) + toolRadius, increment);
  leads.offsetRegister = radiusRegister_;
  if (!arcs && needsRunOut(*contour, distance)) {
    // Half the tool radius, on the printed grid so that every target runs
    // the same leads as verify's reference.
    withRunOut(leads, planeTangent(*contour, domain.t1), onPrintedGrid(toolRadius / 2, 0.001));
  }
  if ((leads.leadIn.start - leads.leadOut.end).head<2>().norm() < 1e-6) {
    fail(cut.span,
         fmt::format("the lead-in and lead-out arcs meet at ({:.4f}, {:.4f}), so the controller "
                     "would run them as one closed path: start the curve where it is smooth, or "
                     "away from a right-angle corner",
                     leads.leadIn.start.x(), leads.leadIn.start.y()),
         DiagnosticKind::UnsupportedConstruct);
  }
  CompensatedLeads centreLeads = leads;
  centreLeads.leadIn = centreArc(leads.leadIn, toolRadius);
  centreLeads.leadOut = centreArc(leads.leadOut, toolRadius);
  checkLeadClearance(cut, centreLeads, *contour, toolRadius);
  std::shared_ptr<const geom::Curve> centre;
  try {
    centre = toolCentrePath(leads, pieces);
  } catch (const geom::GeometryError& error) {
    fail(cut.span,
         fmt::format("the lead arcs of radius {:g} do not join this curve for a tool of radius "
                     "{:g}: {}",
                     leads.leadIn.radius - toolRadius, toolRadius, error.what()),
         DiagnosticKind::ToolTooLarge);
  }
  checkCutBounds(cut, *centre);
  geom::CurveSamples samples;
  if (!arcs) {
    samples = offsetSamples(cut, *contour);
    if (chordTolerance(cut)) { // the chords' budget for their offsets too (offsetSamples)
      double chords = offsetChordTolerance(cut);
      // Where the controller runs slight corners as tangent, what that adds
      // comes off the chords' budget (down to a quarter of it; beyond, verify
      // reports the cut).
      double tangentCorners = toolRadius * (1 - std::cos(options_.compensationTangentAngle));
      if (tangentCorners > 0) {
        chords = std::max(chords - tangentCorners, chords / 4);
        samples = chordsWithinBudget(cut, *contour, chords);
      }
      samples = withinOffsetBudget(samples, *contour, distance, chords);
    }
  }
  ValueId feed = arithmetic_.value(begun.feed);
  ValueId safe = arithmetic_.value(*safe_);
  bool activatesLengthOffset =
      beginCutMoves({centre, chordTolerance(cut).value_or(std::numeric_limits<double>::quiet_NaN()),
                     cut.span, method, arcs ? CutArcs::Native : CutArcs::None});
  markCutBeside(contour, toolRadius);
  // G39 after the chord that ends at each convex corner (its index in
  // chords.ends is the sample's less one).
  std::vector<ChordCorner> chordCorners;
  bool cornerArcs = options_.compensationCornerArcs && options_.controllerLoops;
  if (cornerArcs && !arcs) {
    std::vector<ConvexCorner> corners = convexCorners(pieces, distance);
    samples = withCornerSamples(samples, corners);
    std::size_t from = 0; // the corners come in the samples' order
    for (const ConvexCorner& corner : corners) {
      std::optional<std::size_t> sample = sampleAt(samples, corner.point, from);
      if (sample && *sample > 0 && *sample + 1 < samples.points.size()) {
        from = *sample;
        chordCorners.push_back({*sample - 1, corner.nextTangent});
      }
    }
  }
  // The contour's points: laps of the drawn curve itself (beside it at
  // distance 0) at the points chosen here, one per stretch between the
  // corners that get a G39.
  geom::PiecesOffset itself{contour, {}}; // each part the drawn piece
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    itself.partOrigins.emplace_back(p);
  }
  std::shared_ptr<const BesideCurve> drawn = arcs ? nullptr : besideCurve(cut, curve, itself, 0);
  std::vector<std::uint32_t> stretches;
  if (drawn) {
    stretches = stretchCurves(cut, *drawn, samples.parameters, chordCorners);
  }
  // The passes: the controller's loop where it computes depth= and step=.
  auto [startX, startY] = printedPoint(leads.startUp);
  SweepHeights sweep = beginSweep(cut, false, {startX, startY, safe, activatesLengthOffset});
  ValueId passZ = arithmetic_.value(sweep.z);
  emitCompensatedPass(leads, safe, sweep.z, feed, [&](ValueId z) {
    if (arcs && cornerArcs) {
      emitArcLapWithCorners(*arcs, distance, z, feed);
    } else if (arcs) {
      emitArcLap(*arcs, z, feed);
    } else {
      for (std::size_t k = 0; k < stretches.size(); ++k) {
        if (k > 0) {
          emitCornerArc(chordCorners[k - 1].nextTangent);
        }
        emitBesideLapAt(*drawn, stretches[k], {passZ, passZ, feed}, cut);
      }
    }
  });
  endSweep(sweep);
}

// The laps of the stretches between the corners (G39 after chord `after`:
// the stretch ends at sample after + 1, where the next starts).
std::vector<std::uint32_t> PartLowering::stretchCurves(const CutStmt& cut, const BesideCurve& drawn,
                                                       const std::vector<double>& parameters,
                                                       const std::vector<ChordCorner>& corners) {
  std::vector<std::uint32_t> stretches;
  auto from = parameters.begin();
  for (const ChordCorner& corner : corners) {
    auto to = parameters.begin() + static_cast<std::ptrdiff_t>(corner.after + 1);
    stretches.push_back(chosenPointsCurve(cut, drawn, std::vector<double>(from, to + 1)));
    from = to;
  }
  stretches.push_back(chosenPointsCurve(cut, drawn, std::vector<double>(from, parameters.end())));
  return stretches;
}

// One pass: down off the part, compensation on with the start-up line, the
// lead-in arc, the curve, the lead-out arc, compensation off with the
// cancel line, up.
void PartLowering::emitCompensatedPass(const CompensatedLeads& leads, ValueId safe, Scalar passZ,
                                       ValueId feed,
                                       const std::function<void(ValueId z)>& contour) {
  ValueId z = planeHeight(leads.leadIn.end.z(), passZ);
  auto [startX, startY] = printedPoint(leads.startUp);
  builder_.rapid(startX, startY, safe);
  builder_.feed(startX, startY, z, feed);
  builder_.compensation(leads.offset, leads.offsetRegister);
  auto [inX, inY] = printedPoint(leads.leadIn.start);
  builder_.feed(inX, inY, z, feed);
  emitArcLap({leads.leadIn}, z, feed);
  contour(z);
  if (leads.runOut) {
    auto [runX, runY] = printedPoint(leads.leadOut.start);
    builder_.feed(runX, runY, z, feed);
  }
  emitArcLap({leads.leadOut}, z, feed);
  builder_.compensation(0, 0);
  auto [endX, endY] = printedPoint(leads.cancel);
  builder_.feed(endX, endY, z, feed);
  builder_.rapid(endX, endY, safe);
}

// A lead's point (x, y) on the printed grid, so that every target runs the
// same leads as verify's reference.
std::array<ValueId, 2> PartLowering::printedPoint(const Eigen::Vector3d& point) {
  double increment = options_.coordinateIncrement;
  return {builder_.constant(onPrintedGrid(point.x(), increment)),
          builder_.constant(onPrintedGrid(point.y(), increment))};
}

} // namespace cncc::ir::lowering
