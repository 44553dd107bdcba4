// The laps of a cut beside its curve whose offset the host computes
// (offset_cuts.cpp), when they are cut as points: each lap is a curve.lap
// on the exact offset (geom::offsetOfPieces, the cut's curve in the cut
// table), its pieces laid out in the offset's own parameter, one region per
// piece (per knot span of a NURBS piece's offset):
// - a line's offset (cut back at a concave corner) and an arc's, and the
//   arc about a convex corner: the line or arc the host computed, in
//   numbers;
// - another piece's offset: the drawn piece's own arithmetic C at the
//   parameter and the tool centre C + d (-y', x') / |C'|, C' its derivative
//   (forward_derivative.h), over the range left of it at concave corners.
// The points are chosen by the target's legalisation (expand-curve-laps)
// within the cut's tolerance of the offset, as samples= or spacing= ask;
// where a controller computes the program they are printed as numbers (the
// entry's pointsAsNumbers, on every target), a controller keeping its
// numbers in a few hundred variables. Fitted arcs and the spline, SPL and
// NURBS blocks fitted to the offset are laps of the same regions (the
// stand-in CutCurve whose `beside` this is). At distance 0 the regions are
// the drawn curve itself: comp=controller's chords (compensated_cuts.cpp).
#include "forward_derivative.h"

#include "cncc/geom/composite_curve.h"
#include "cncc/geom/line_arc_curves.h"

#include <fmt/format.h>

#include <cmath>

namespace cncc::ir::lowering {

using namespace frontend;

std::shared_ptr<const BesideCurve> PartLowering::besideCurve(const CutStmt& cut,
                                                             const CutCurve& curve,
                                                             const geom::PiecesOffset& offset,
                                                             double distance) {
  std::vector<const geom::Curve*> parts = geom::piecesOf(*offset.curve);
  // geom says which drawn piece each part lies beside (nullopt: a convex
  // corner's arc).
  const std::vector<std::optional<std::size_t>>& origins = offset.partOrigins;
  if (origins.size() != parts.size()) {
    fail(cut.span,
         fmt::format("the offset of this curve has {} pieces that do not follow its {} pieces "
                     "one by one",
                     parts.size(), curve.pieces.size()),
         DiagnosticKind::UnsupportedConstruct);
  }
  auto beside = std::make_shared<BesideCurve>();
  beside->layout = curveTableEntryOn(cut, offset.curve);
  beside->drawn = curve;
  beside->distance = distance;
  double start = 0;
  for (std::size_t k = 0; k < parts.size(); ++k) {
    geom::ParameterRange own = parts[k]->domain();
    CurvePieceLayout layout{parts.size() == 1 ? own.t0 : start, own.t0, own.t1};
    start += own.length();
    const CurvePiece* piece = origins[k] ? &curve.pieces[*origins[k]] : nullptr;
    bool numbers = isLineCurve(*parts[k]) || isArcCurve(*parts[k]);
    if (numbers || piece == nullptr || piece->spans.empty()) {
      beside->regions.push_back({parts[k], numbers ? std::nullopt : origins[k]});
    } else {
      // The knot spans left of the piece, each a region.
      for (std::size_t s = 0; s < piece->spans.size(); ++s) {
        const geom::PolynomialSpan& span = piece->spans[s];
        double from = std::max(own.t0, span.t0);
        double to = std::min(own.t1, span.t1);
        if (to > from) {
          layout.spans.emplace_back(from, to);
          double length = span.t1 - span.t0;
          beside->regions.push_back(
              {parts[k], origins[k], s, (from - span.t0) / length, (to - from) / length});
        }
      }
    }
    beside->layout.pieces.push_back(std::move(layout));
  }
  return beside;
}

std::uint32_t PartLowering::besideChordsCurve(const CutStmt& cut, const BesideCurve& beside,
                                              std::optional<ArcsAsked> arcs, bool blocksAsked) {
  CurveTableEntry entry = beside.layout;
  entry.arcsAsked = arcs;
  entry.blocksAsked = blocksAsked;
  chooseSampling(entry, cut, *entry.geometry, offsetChordTolerance(cut));
  entry.pointsAsNumbers = true;
  return builder_.addCurve(std::move(entry));
}

// Cut at parameters chosen for something else too (comp=controller's
// chords, kept within the budget of their offsets).
std::uint32_t PartLowering::chosenPointsCurve(const CutStmt& cut, const BesideCurve& beside,
                                              const std::vector<double>& parameters) {
  CurveTableEntry entry = beside.layout;
  // How the points would be chosen again (IR read from text keeps them).
  chooseSampling(entry, cut, *entry.geometry, toleranceBudget(cut).forPoints());
  entry.chosenParameters = std::make_shared<const std::vector<double>>(parameters);
  entry.pointsAsNumbers = true;
  return builder_.addCurve(std::move(entry));
}

void PartLowering::emitBesideLapAt(const BesideCurve& beside, std::uint32_t table,
                                   std::vector<ValueId> operands, const CutStmt& cut) {
  emitLapRegions(table, std::move(operands), beside.regions.size(),
                 [&](std::size_t region, Scalar local) {
                   return besidePoint(beside, beside.regions[region], local, cut);
                 });
}

LapRegionPoint PartLowering::besidePoint(const BesideCurve& beside, const HostBesideRegion& region,
                                         Scalar local, const CutStmt& cut) {
  if (const auto* line = dynamic_cast<const geom::LineCurve*>(region.part)) {
    geom::ParameterRange own = line->domain();
    return linePointAt(line->point(own.t0), line->point(own.t1), own.length(), local);
  }
  if (const auto* arc = dynamic_cast<const geom::ArcCurve*>(region.part)) {
    return arcPointAt({arc->centre(), arc->radius(), arc->startAngle(),
                       arc->sweep() / arc->length(), arc->startZ(), arc->zChange() / arc->length()},
                      local);
  }
  const CutCurve& curve = beside.drawn;
  const CurvePiece& piece = curve.pieces[*region.drawn];
  Scalar own = local;
  if (!piece.spans.empty()) {
    own = arithmetic_.add(Scalar::of(region.spanFrom),
                          arithmetic_.multiply(Scalar::of(region.spanShare), local));
  }
  CurvePoint point = pointAt(curve, *region.drawn, region.span, own, cut);
  if (beside.distance == 0) {
    return point; // the drawn curve itself (comp=controller's)
  }
  return offsetAlongDerivative(point, local.value, Scalar::of(beside.distance), cut);
}

} // namespace cncc::ir::lowering
