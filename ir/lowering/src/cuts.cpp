// A `curve` statement: its points chosen at compile time (chord tolerance,
// samples= or spacing=) on the whole curve, their parameters in constant
// tables (one per piece and NURBS span), and for each pass a rapid over the
// start, a plunge (or a ramp lap), loops that evaluate the curve at the
// tabled parameters, and a rapid retract.
#include "part_lowering.h"

#include "cncc/ir/curve_blocks.h"

#include "cncc/geom/arc_length.h"
#include "cncc/geom/evaluation_budget.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/ir/printed_grid.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string_view>

namespace cncc::ir::lowering {

using namespace frontend;

namespace {

constexpr double maximumPointsPerCut = 1'000'000;

} // namespace

const Modifier* findModifier(const CutStmt& cut, std::string_view name) {
  for (const Modifier& modifier : cut.modifiers) {
    if (modifier.name == name) {
      return &modifier;
    }
  }
  return nullptr;
}

const Expr* modifierValue(const CutStmt& cut, std::string_view name) {
  const Modifier* modifier = findModifier(cut, name);
  return modifier == nullptr ? nullptr : modifier->value.get();
}

std::string wordOf(const Expr& expression) {
  if (expression.kind == ExprKind::Name) {
    return std::string(as<NameExpr>(expression).name);
  }
  if (expression.kind == ExprKind::String) {
    return std::string(as<StringExpr>(expression).value);
  }
  return {};
}

std::string methodOf(const CutStmt& cut) {
  const Modifier* method = findModifier(cut, "method");
  return method != nullptr && method->value ? wordOf(*method->value) : "";
}

std::optional<ParameterUse> PartLowering::parameterUse(const CutStmt& cut,
                                                       const Expr* toolDiameter) {
  std::pair<const char*, const Expr*> uses[] = {{"curve", cut.curve.get()},
                                                {"tool diameter", toolDiameter}};
  for (const auto& [what, expression] : uses) {
    if (expression == nullptr) {
      continue;
    }
    std::set<std::string> parameters = parametersOf(*expression);
    unrollForLoopVariables(parameters);
    if (!parameters.empty()) {
      return ParameterUse{what, *parameters.begin()};
    }
  }
  return std::nullopt;
}

void PartLowering::checkMethod(const CutStmt& cut, bool blocksAsked) {
  const Modifier* method = findModifier(cut, "method");
  if (method == nullptr) {
    return;
  }
  std::string word = method->value ? wordOf(*method->value) : "";
  if (word == "linear") {
    return;
  }
  if (word != "cspline" && word != "aspline" && word != "bspline" && word != "nurbs") {
    unsupported(method->span(), fmt::format("method={}", word));
  }
  if (!options_.reportSplineAsChords) {
    return;
  }
  if (nativeArcs_) {
    diagnostics_->report(DiagnosticKind::SplineAsChords, method->span(),
                         fmt::format("this curve's arcs are cut as the controller's arcs: "
                                     "method={} is cut as arcs and straight feed moves within the "
                                     "cut's tolerance",
                                     word));
  } else if (!options_.splineInterpolation && !blocksAsked) {
    diagnostics_->report(DiagnosticKind::SplineAsChords, method->span(),
                         fmt::format("this target has no spline interpolation: method={} is cut "
                                     "as straight feed moves within the cut's tolerance",
                                     word));
  }
}

bool PartLowering::rampEntry(const CutStmt& cut) {
  const Modifier* entry = findModifier(cut, "entry");
  if (entry == nullptr) {
    return false;
  }
  std::string word = entry->value ? wordOf(*entry->value) : "";
  if (word != "plunge" && word != "ramp") {
    unsupported(entry->span(), fmt::format("entry={}", word));
  }
  return word == "ramp";
}

Scalar PartLowering::cutFeed(const CutStmt& cut) {
  if (const Expr* expression = modifierValue(cut, "feed")) {
    return feedRate(*expression);
  }
  if (!feed_) {
    fail(cut.span, "this cut has no feed rate", DiagnosticKind::NoFeed);
  }
  return *feed_;
}

std::optional<double> PartLowering::chordTolerance(const CutStmt& cut) {
  if (modifierValue(cut, "samples") != nullptr || modifierValue(cut, "spacing") != nullptr) {
    return std::nullopt;
  }
  const Expr* expression = modifierValue(cut, "tolerance");
  return expression == nullptr ? defaultTolerance : constantNumber(*expression, "this tolerance");
}

ToleranceBudget PartLowering::toleranceBudget(const CutStmt& cut) {
  ToleranceBudget budget;
  budget.tolerance = chordTolerance(cut).value_or(std::numeric_limits<double>::quiet_NaN());
  budget.increment = options_.coordinateIncrement;
  return budget;
}

std::size_t PartLowering::sampleCount(const CutStmt& cut) {
  const Expr* expression = modifierValue(cut, "samples");
  double samples = constantNumber(*expression, "samples=");
  if (!(samples >= 2 && samples <= maximumPointsPerCut) || samples != std::floor(samples)) {
    fail(expression->span,
         fmt::format("samples={:g} is not a whole number from 2 to {:g}", samples,
                     maximumPointsPerCut),
         DiagnosticKind::InvalidSamples);
  }
  return static_cast<std::size_t>(samples);
}

void PartLowering::checkSpacing(const CutStmt& cut, const geom::Curve& curve, double spacing) {
  double count = geom::arcLength(curve) / spacing;
  if (!(count <= maximumPointsPerCut)) {
    fail(cut.span,
         fmt::format("spacing={:g} would put {:.0f} points on this curve; the limit is {:.0f}",
                     spacing, count, maximumPointsPerCut),
         DiagnosticKind::ProgramTooLarge);
  }
}

geom::CurveSamples PartLowering::samplesFor(const CutStmt& cut, const geom::Curve& curve) {
  try {
    if (modifierValue(cut, "samples") != nullptr) {
      return geom::sampleUniformParameter(curve, sampleCount(cut));
    }
    if (const Expr* expression = modifierValue(cut, "spacing")) {
      double spacing = constantNumber(*expression, "spacing=");
      checkSpacing(cut, curve, spacing);
      return geom::sampleEqualArcLength(curve, spacing);
    }
    // A controller that rounds every coordinate to its increment takes up to
    // half an increment per axis of the tolerance (LoweringOptions).
    return chordsWithinBudget(cut, curve, toleranceBudget(cut).forPoints());
  } catch (const geom::GeometryError& error) {
    fail(cut.curve->span, fmt::format("cannot discretise this curve: {}", error.what()),
         DiagnosticKind::DegenerateCurve);
  }
}

geom::CurveSamples PartLowering::checkedSamplesFor(const CutStmt& cut, const geom::Curve& curve) {
  geom::CurveSamples samples = samplesFor(cut, curve);
  for (const Eigen::Vector3d& point : samples.points) {
    if (!point.allFinite()) {
      fail(cut.curve->span, "this curve has a point that is not a finite number",
           DiagnosticKind::NonFiniteValue);
    }
  }
  if (samples.parameters.size() < 2) {
    fail(cut.curve->span, "this curve gave fewer than two points", DiagnosticKind::TooFewPoints);
  }
  return samples;
}

double PartLowering::largestNumberInUnits() const {
  return partUnits(part_) == PartUnits::Inches ? options_.largestNumber / 10
                                               : options_.largestNumber;
}

double PartLowering::largestCoordinateInUnits() const {
  return std::min(largestNumberInUnits(), options_.largestCoordinate);
}

void PartLowering::checkCutBounds(const CutStmt& cut, const geom::Curve& curve, double margin) {
  std::string_view unit = partUnits(part_) == PartUnits::Inches ? "inch" : "mm";
  double largest = largestCoordinateInUnits();
  if (const Expr* depth = modifierValue(cut, "depth")) {
    Value atDefaults = evaluate(*depth, environment_);
    if (atDefaults.type.kind == TypeKind::Num && !(std::abs(atDefaults.number) <= largest)) {
      fail(depth->span,
           fmt::format("the depth {:g} {} is beyond this target's number range of +-{} {}",
                       atDefaults.number, unit, largest, unit),
           DiagnosticKind::CoordinateRange);
    }
  }
  geom::DiscretisationEstimate estimate;
  try {
    estimate = geom::estimateDiscretisation(curve, 0.0);
  } catch (const geom::GeometryError& error) {
    fail(cut.curve->span, fmt::format("cannot discretise this curve: {}", error.what()),
         DiagnosticKind::DegenerateCurve);
  }
  if (!std::isfinite(estimate.largestCoordinate)) {
    fail(cut.curve->span, "this curve has a point that is not a finite number",
         DiagnosticKind::NonFiniteValue);
  }
  if (estimate.largestCoordinate - margin > largest) {
    fail(cut.curve->span,
         fmt::format("this curve reaches a coordinate of {:g} {} at the values compiled with; "
                     "this target's number range is +-{} {}",
                     estimate.largestCoordinate, unit, largest, unit),
         DiagnosticKind::CoordinateRange);
  }
}

void PartLowering::checkChordCount(const CutStmt& cut, const geom::Curve& curve, double tolerance) {
  double chords = 0;
  try {
    chords = geom::estimateDiscretisation(curve, tolerance).chords;
  } catch (const geom::GeometryError& error) {
    fail(cut.curve->span, fmt::format("cannot discretise this curve: {}", error.what()),
         DiagnosticKind::DegenerateCurve);
  }
  if (!(chords <= static_cast<double>(maximumChordsPerCut))) {
    tooManyChords(cut, "this curve", chords, tolerance);
  }
}

void PartLowering::tooManyChords(const CutStmt& cut, std::string_view path, double chords,
                                 double tolerance) {
  std::string_view unit = partUnits(part_) == PartUnits::Inches ? "inch" : "mm";
  fail(cut.span,
       fmt::format("{} needs about {:.3g} chords to keep within {:.3g} {} of it; the limit of "
                   "one cut is {}",
                   path, chords, tolerance, unit, maximumChordsPerCut),
       DiagnosticKind::ProgramTooLarge);
}

geom::CurveSamples PartLowering::chordsWithinBudget(const CutStmt& cut, const geom::Curve& curve,
                                                    double budget) {
  checkChordCount(cut, curve, budget);
  try {
    return chordsWithinTolerance(curve, budget, cut.span, cut.curve->span);
  } catch (const CurveLapError& error) {
    reportCurveLapError(error, *diagnostics_);
    throw LoweringFailed{};
  }
}

std::vector<double> PartLowering::passDepths(const CutStmt& cut) {
  const Expr* depthExpression = modifierValue(cut, "depth");
  const Expr* stepExpression = modifierValue(cut, "step");
  if (depthExpression == nullptr && stepExpression == nullptr) {
    return {0.0};
  }
  if (depthExpression == nullptr || stepExpression == nullptr) {
    fail(cut.span, "a sweep needs both depth= and step=", DiagnosticKind::SweepIncomplete);
  }
  double depth = constantNumber(*depthExpression, "the sweep depth");
  double step = constantNumber(*stepExpression, "the sweep step");
  if (!(step > 0) || !(depth >= step) || !(depth / step <= maximumPointsPerCut)) {
    fail(cut.span, "cannot lower this sweep: it needs 0 < step <= depth");
  }
  // -S, -2S, ... ending exactly at -D.
  std::vector<double> depths;
  for (int k = 1;; ++k) {
    double z = k * step;
    if (z >= depth - 1e-9 * depth) {
      depths.push_back(depth);
      return depths;
    }
    depths.push_back(z);
  }
}

// Each piece's (each knot span's) share of the lap's length, as the
// legalisations of a ramp lap measure it (lapRegionShares).
std::vector<RampSegment> PartLowering::rampSegments(const CutCurve& curve, const CutStmt& cut) {
  CurveTableEntry entry = curveTableEntryOn(cut, curve.geometry);
  for (std::size_t p = 0; p < curve.pieces.size(); ++p) {
    entry.pieces.push_back(pieceLayout(curve.pieces[p], curve.pieceStarts[p]));
  }
  std::vector<LapRegionShare> shares;
  try {
    shares = lapRegionShares(entry, *curve.geometry);
  } catch (const CurveLapError& error) {
    fail(error.span, error.what(), DiagnosticKind::DegenerateCurve);
  }
  std::vector<RampSegment> segments;
  for (std::size_t p = 0; p < curve.pieces.size(); ++p) {
    for (std::size_t s = 0; s < entry.pieces[p].regionCount(); ++s) {
      const LapRegionShare& share = shares[entry.regionOf(p, s)];
      segments.push_back({p, s, share.before, share.share});
    }
  }
  return segments;
}

RampSegment PartLowering::rampSegmentOf(const std::vector<RampSegment>& segments, std::size_t piece,
                                        std::size_t span) {
  for (const RampSegment& segment : segments) {
    if (segment.piece == piece && segment.span == span) {
      return segment;
    }
  }
  return {piece, span, 1.0, 0.0}; // not reached: every segment is listed
}

void PartLowering::checkRampCloses(const CutCurve& curve, const CutStmt& cut) {
  geom::ParameterRange domain = curve.geometry->domain();
  if (!((curve.geometry->point(domain.t0) - curve.geometry->point(domain.t1)).norm() <= 1e-6)) {
    unsupported(findModifier(cut, "entry")->span(), "entry=ramp on a curve that does not close");
  }
}

bool PartLowering::blocksAskedBy(const CutStmt& cut) const {
  return !nativeArcs_ && !runtimeOffset_ && splineKindOfMethod(methodOf(cut)).has_value();
}

HostCut PartLowering::beginHostCut(const CutStmt& cut, bool blocksAsked) {
  // The curve's points are chosen at its defaults, whatever IR evaluates it.
  fixParameters(*cut.curve, cut.curve->span, "this curve's points");
  checkMethod(cut, blocksAsked);
  bool ramp = rampEntry(cut);
  if (!safe_) {
    fail(cut.span, "this cut has no safe height; write 'safe z=Z' before it",
         DiagnosticKind::NoSafeHeight);
  }
  return {cutFeed(cut), ramp};
}

bool PartLowering::beginCutMoves(CutGeometry geometry) {
  ensureOrigin();
  // The cut's first rapid climbs to the safe height: the first Z move, which
  // activates a new tool's length offset (before a pass loop: sweeps.cpp).
  bool activatesLengthOffset = machine_.lengthOffsetPending;
  machine_.lengthOffsetPending = false;
  double tolerance = geometry.tolerance;
  if (std::isfinite(tolerance) && tolerance > 0 && machine_.contouring != tolerance) {
    builder_.contouring(tolerance);
    machine_.contouring = tolerance;
  }
  geometry.increment = options_.coordinateIncrement;
  if (options_.controllerLoops) {
    geometry.controllerDigits = std::max(options_.literalSignificantDigits, 0);
  }
  if (splineKindOfMethod(geometry.method)) { // what choose-curve-blocks reads
    geometry.printedBlocks = options_.nurbsBlocks        ? PrintedBlocks::Nurbs
                             : options_.polynomialBlocks ? PrintedBlocks::Polynomial
                             : options_.splineBlocks     ? PrintedBlocks::Spline
                                                         : PrintedBlocks::None;
    geometry.splineEnds = options_.splineEnds;
  }
  auto index = static_cast<std::uint32_t>(cuts_.size());
  cuts_.push_back(std::move(geometry));
  builder_.cutBegin(index);
  return activatesLengthOffset;
}

void PartLowering::noteMethodSpan(const CutStmt& cut) {
  if (const Modifier* method = findModifier(cut, "method")) {
    cuts_.back().methodSpan = method->span();
  }
}

void PartLowering::markCutBeside(std::shared_ptr<const geom::Curve> drawn, double toolRadius) {
  cuts_.back().drawnCurve = std::move(drawn);
  cuts_.back().toolRadius = toolRadius;
}

void PartLowering::lowerCut(const CutStmt& cut) {
  stepsLeftToTheLegalisation_ = false; // whatever the cut before left
  nativeArcs_ = false;                 // read by checkMethod and blocksAskedBy
  if (lowerOffsetCut(cut)) {
    return;
  }
  // The curve is built once for whichever way lowers the cut. Arc pieces
  // are printed as circles (native_arcs.cpp), not fitted arcs.
  CutCurve curve = cutCurve(cut);
  checkCutBounds(cut, *curve.geometry);
  bool nativeArcs = wantsNativeArcs(cut) && hasArcPiece(curve);
  // A method= spline asks for the target's curve blocks, which
  // choose-curve-blocks makes of the chords or steps lowered here for every
  // target (blocksAsked), after the curve's arcs cut as arcs.
  nativeArcs_ = nativeArcs; // checkMethod says so
  // Fitted arcs are asked of the laps either way below; fit-arcs decides.
  arcsAsked_ = nativeArcs ? std::nullopt : arcsAskedBy(cut);
  if (lowerControllerCut(cut, curve)) {
    arcsAsked_.reset();
    return;
  }
  std::size_t firstEntry = builder_.function().curves.size();
  if (nativeArcs) {
    lowerHostArcCut(cut, curve);
  } else {
    lowerCurveLaps(cut, curve);
  }
  if (stepsLeftToTheLegalisation_ && singleStepsLeftToTheLegalisation_) {
    for (std::size_t entry = firstEntry; entry < builder_.function().curves.size(); ++entry) {
      singleStepCurves_.insert(static_cast<std::uint32_t>(entry));
    }
  }
  arcsAsked_.reset();
}

// The cut's passes, each lap along the curve a curve.lap whose points the
// target's legalisation chooses (expand-curve-laps).
void PartLowering::lowerCurveLaps(const CutStmt& cut, const CutCurve& curve) {
  bool blocksAsked = blocksAskedBy(cut);
  auto [feed, ramp] = beginHostCut(cut, blocksAsked);
  CurveTableEntry entry = curveTableEntry(cut, curve, arcsAsked_);
  entry.blocksAsked = blocksAsked;
  if (ramp) {
    checkRampCloses(curve, cut);
  }

  // Feed and safe height once, visible in every loop of the cut.
  ValueId feedValue = arithmetic_.value(feed);
  ValueId safeValue = arithmetic_.value(*safe_);
  bool activatesLengthOffset = beginCutMoves(
      {curve.geometry, chordTolerance(cut).value_or(std::numeric_limits<double>::quiet_NaN()),
       cut.span, methodOf(cut)});
  noteMethodSpan(cut);
  // Level laps ask for arcs where the cut does; a ramp lap is chords.
  std::uint32_t table = builder_.addCurve(entry);
  std::uint32_t rampTable = table;
  if (ramp && entry.arcsAsked) {
    entry.arcsAsked.reset();
    rampTable = builder_.addCurve(std::move(entry));
  }
  // The lap starts and ends where the curve does; the passes are a loop
  // (sweeps.cpp), over depth= and step= as the controller computes them on
  // the targets that run loops (editable there), else over numbers.
  geom::ParameterRange domain = curve.geometry->domain();
  SampleLocation first = locate(curve, domain.t0);
  SampleLocation end = locate(curve, domain.t1);
  CurvePoint start = pointAt(curve, first.piece, first.span, Scalar::of(first.local), cut);
  CurvePoint finish = pointAt(curve, end.piece, end.span, Scalar::of(end.local), cut);
  SweepStart from{arithmetic_.value(start.x), arithmetic_.value(start.y), safeValue,
                  activatesLengthOffset, start.z};
  emitSweep(cut, ramp, from, {arithmetic_.value(finish.x), arithmetic_.value(finish.y)}, feedValue,
            [&](ValueId zFrom, ValueId zTo) {
              emitCurveLap(curve, zFrom == zTo ? table : rampTable, zFrom, zTo, feedValue, cut);
            });
}

// The cut's curve for the function's curve table: its pieces' parameter
// ranges and knot spans, how its points are chosen (checked here, where the
// cut's own errors are reported, as far as that takes no more than an
// estimate), and the NURBS spans the host computes as points; asking for
// `arcs` where given.
CurveTableEntry PartLowering::curveTableEntry(const CutStmt& cut, const CutCurve& curve,
                                              std::optional<ArcsAsked> arcs) {
  CurveTableEntry entry = wholeCurveTableEntry(cut, curve);
  entry.arcsAsked = arcs;
  // A controller that rounds every coordinate to its increment takes up to
  // half an increment per axis of the tolerance (LoweringOptions).
  chooseSampling(entry, cut, *curve.geometry, toleranceBudget(cut).forPoints());
  return entry;
}

void PartLowering::chooseSampling(CurveTableEntry& entry, const CutStmt& cut,
                                  const geom::Curve& curve, double chordTolerance) {
  if (modifierValue(cut, "samples") != nullptr) {
    entry.sampling = CurveSampling::Samples;
    entry.amount = static_cast<double>(sampleCount(cut));
  } else if (const Expr* expression = modifierValue(cut, "spacing")) {
    entry.sampling = CurveSampling::Spacing;
    entry.amount = constantNumber(*expression, "spacing=");
    checkSpacing(cut, curve, entry.amount);
  } else {
    entry.amount = chordTolerance;
    // Arcs may keep a curve that chords cannot (fit-arcs), and the
    // controller's steps have bounds of their own.
    if (!entry.arcsAsked && !stepsLeftToTheLegalisation_) {
      checkChordCount(cut, curve, entry.amount);
    }
  }
}

// An entry for the cut's whole curve, its pieces laid out; its points not
// yet chosen.
CurveTableEntry PartLowering::wholeCurveTableEntry(const CutStmt& cut, const CutCurve& curve) {
  if (curve.beside) {
    return curve.beside->layout; // the offset's pieces (offset_laps.cpp)
  }
  CurveTableEntry entry = curveTableEntryOn(cut, curve.geometry);
  for (std::size_t p = 0; p < curve.pieces.size(); ++p) {
    addPieceLayout(entry, curve.pieces[p], curve.pieceStarts[p], cut);
  }
  return entry;
}

// An entry for `geometry` (the cut's curve, or a piece of it), its
// parameter range and where its errors are reported; no pieces yet.
CurveTableEntry PartLowering::curveTableEntryOn(const CutStmt& cut,
                                                std::shared_ptr<const geom::Curve> geometry) {
  CurveTableEntry entry;
  geom::ParameterRange domain = geometry->domain();
  entry.from = domain.t0;
  entry.to = domain.t1;
  entry.curveSpan = cut.curve->span;
  entry.cutSpan = cut.span;
  entry.geometry = std::move(geometry);
  return entry;
}

// One piece of the cut's curve alone, its points within the cut's chord
// tolerance; a ramp lap along it descends by its share of the whole lap's
// descent (`shares`, empty for none).
CurveTableEntry PartLowering::pieceCurveTableEntry(const CutStmt& cut, const CutCurve& curve,
                                                   std::size_t piece,
                                                   const std::vector<RampSegment>& shares) {
  const CurvePiece& own = curve.pieces[piece];
  CurveTableEntry entry =
      curveTableEntryOn(cut, std::make_shared<TransformedCurve>(own.geometry, own.transform));
  addPieceLayout(entry, own, entry.from, cut);
  entry.amount = toleranceBudget(cut).forPoints();
  if (!stepsLeftToTheLegalisation_) { // the controller's steps have bounds of their own
    checkChordCount(cut, *entry.geometry, entry.amount);
  }
  if (!shares.empty()) {
    entry.progressFrom = rampSegmentOf(shares, piece, 0).before;
    entry.progressShare = 0;
    for (const RampSegment& segment : shares) {
      entry.progressShare += segment.piece == piece ? segment.share : 0;
    }
  }
  return entry;
}

// Where a piece starts in the whole curve's parameter, its own range and
// its knot spans.
CurvePieceLayout PartLowering::pieceLayout(const CurvePiece& piece, double start) {
  geom::ParameterRange own = piece.geometry->domain();
  CurvePieceLayout layout{start, own.t0, own.t1};
  for (const geom::PolynomialSpan& span : piece.spans) {
    layout.spans.emplace_back(span.t0, span.t1);
  }
  return layout;
}

void PartLowering::addPieceLayout(CurveTableEntry& entry, const CurvePiece& piece, double start,
                                  const CutStmt& cut) {
  // Counted only for a piece with knot spans: a path of many lines and arcs
  // would count its regions once per piece.
  std::size_t firstRegion = piece.spans.empty() ? 0 : entry.regionCount();
  for (std::size_t s = 0; s < piece.spans.size(); ++s) {
    if (piece.value->kind == CurveKind::Nurbs &&
        !spanLiteralsFit(cleanedSpan(piece.spans[s]), cut, piece.transform.stretch())) {
      entry.hostPointRegions.push_back(firstRegion + s);
    }
  }
  entry.pieces.push_back(pieceLayout(piece, start));
}

// One lap as a curve.lap: a region per piece in [firstPiece, endPiece) (per
// knot span of a NURBS piece) computing the point at its parameter, z going
// from zFrom to zTo.
void PartLowering::emitCurveLap(const CutCurve& curve, std::uint32_t table, ValueId zFrom,
                                ValueId zTo, ValueId feed, const CutStmt& cut,
                                std::size_t firstPiece, std::size_t endPiece) {
  if (curve.beside) {
    emitBesideLapAt(*curve.beside, table, {zFrom, zTo, feed}, cut);
    return;
  }
  emitCurveLapAt(curve, table, {zFrom, zTo, feed}, curvePointOf(curve, cut), firstPiece, endPiece);
}

PartLowering::LapPointOf PartLowering::curvePointOf(const CutCurve& curve, const CutStmt& cut) {
  return [this, &curve, &cut](std::size_t piece, std::size_t span, Scalar local) {
    return pointAt(curve, piece, span, local, cut);
  };
}

void PartLowering::emitCurveLapAt(const CutCurve& curve, std::uint32_t table,
                                  std::vector<ValueId> operands, const LapPointOf& pointOf,
                                  std::size_t firstPiece, std::size_t endPiece) {
  std::vector<std::pair<std::size_t, std::size_t>> places; // piece and span of each region
  endPiece = std::min(endPiece, curve.pieces.size());
  for (std::size_t p = firstPiece; p < endPiece; ++p) {
    std::size_t spans = std::max<std::size_t>(curve.pieces[p].spans.size(), 1);
    for (std::size_t s = 0; s < spans; ++s) {
      places.emplace_back(p, s);
    }
  }
  emitLapRegions(table, std::move(operands), places.size(), [&](std::size_t region, Scalar local) {
    return pointOf(places[region].first, places[region].second, local);
  });
}

void PartLowering::emitLapRegions(std::uint32_t table, std::vector<ValueId> operands,
                                  std::size_t regions, const RegionPointOf& pointOf) {
  std::vector<ValueId> computedSteps(operands.begin() + 3, operands.end());
  Scalar local = Scalar::of(
      builder_.beginCurveLap(table, operands[0], operands[1], operands[2], computedSteps),
      ValueType::F64);
  for (std::size_t r = 0; r < regions; ++r) {
    LapRegionPoint region = pointOf(r, local);
    const CurvePoint& point = region.point;
    ValueId x = arithmetic_.value(point.x);
    ValueId y = arithmetic_.value(point.y);
    ValueId z = arithmetic_.value(point.z);
    if (region.toCentre) {
      ValueId i = arithmetic_.value(region.toCentre->x);
      builder_.curveArc(x, y, z, i, arithmetic_.value(region.toCentre->y));
    } else if (region.walkStep) {
      builder_.curveWalk(x, y, z, arithmetic_.value(*region.walkStep));
    } else {
      builder_.curvePoint(x, y, z);
    }
  }
}

} // namespace cncc::ir::lowering
