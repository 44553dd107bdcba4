// The function's curve table: for each `curve.lap @c` the shape of the
// cut's curve (its pieces, their parameter ranges and NURBS knot spans) and
// how the lap's points are chosen on it. The points themselves are computed
// by the regions of the `curve.lap` (one per piece, or per knot span of a
// NURBS piece), so the IR holds the whole curve; the table holds what the
// regions cannot say: where each region's parameter lies on the whole curve.
#pragma once

#include "cncc/frontend/source_span.h"
#include "cncc/ir/spline_blocks_kind.h"

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace cncc::geom {
class Curve;
} // namespace cncc::geom

namespace cncc::ir {

// One piece of a cut's curve (a line, an arc, a polar or param curve, a
// NURBS): where it starts in the whole curve's parameter, and its own
// parameter range. A NURBS piece lists its knot spans (ranges of its own
// parameter); each is a region of its own whose parameter is the span's
// u in [0, 1]. Any other piece is one region whose parameter is its own.
struct CurvePieceLayout {
  double start = 0;
  double from = 0;
  double to = 1;
  std::vector<std::pair<double, double>> spans = {};

  std::size_t regionCount() const { return spans.empty() ? 1 : spans.size(); }
};

// Where a parameter of the whole curve lies: the region (piece and span)
// and the parameter that region computes its point at.
struct CurveLocation {
  std::size_t region = 0;
  std::size_t piece = 0;
  std::size_t span = 0;
  double local = 0;
};

// How a lap's points are chosen on the whole curve: within a chord
// tolerance (the farthest reach of each chord), a number of points at equal
// steps of the parameter, or points at equal arc length. Or the lap is not
// points but tangent-continuous arcs and lines within a tolerance, every
// end and centre on the printed grid (a level lap in a plane z = const, on
// a target that prints G02/G03). Or each region is cut in its own number of
// uniform steps of its parameter by a loop the controller runs (a level lap
// of pieces without knot spans, on a target that runs loops), an arc region
// in blocks of the controller's circular interpolation, a walked region by
// a step the program computes at each point. Or the lap
// is the target's own curve blocks, whose data the lowering fitted within
// the cut's tolerance and put in a table of the function: a NURBS block
// (G06.2, move.nurbs, the lap's operands after its three the weights),
// Sinumerik spline blocks (move.spline) or the cubic spans of Heidenhain
// SPL blocks (a move.polynomial each); or blocks the legalisation
// write-curve-blocks fits (an entry that names no table).
enum class CurveSampling {
  ChordTolerance,
  Samples,
  Spacing,
  Arcs,
  Steps,
  NurbsBlocks,
  SplineBlocks,
  PolynomialBlocks,
};

// The most uniform steps one region of a lap cut in steps may take.
inline constexpr int maximumStepsPerRegion = 100'000;

// A region's count that the legalisation chooses (curve_lap_steps.h): the
// fewest uniform steps within the entry's amount, measured on the curve
// (a region that one chord cuts gets its count, 1, from the lowering).
inline constexpr int stepsChosenByLegalisation = -1;

// How a controller reads a lap's parameter steps: literals of `digits`
// significant digits (its cut's controllerDigits); the counts whose rounded
// step moves the lap's last point past a quarter of the cut's `tolerance`
// are refused (checkStepDrift, curve_lap_steps.h).
struct StepReading {
  int digits = 0;
  double tolerance = 0;
};

// A region of a lap cut in steps that is an arc of a circle: its count is
// a number of move.arc blocks (the controller's circular interpolation),
// each turning by an equal share of the region, counter-clockwise or not;
// blocks of whole turns each end exactly where the region starts (with its
// values, so no rounding leaves a sliver). The region ends in curve.arc,
// which gives the offset from each point to the centre too.
struct ArcRegion {
  std::size_t region = 0;
  bool counterClockwise = true;
  bool wholeTurns = false;
};

// Sinumerik spline blocks that write-curve-blocks fits: which, how an A or
// C spline begins and ends, and whether they follow a ramp lap, whose last
// chord (through the last two chosen points, on the grid) an automatic
// start continues tangentially.
struct SplineBlocksFit {
  SplineKind kind = SplineKind::BSpline;
  SplineEnds ends = SplineEnds::Automatic;
  bool afterRamp = false;
};

// Steps beside a curve whose tool radius the program reads: each region
// whose count is left to the legalisation takes N(r) = N0 sqrt(1 + q r)
// steps at the radius r, a count the program computes. The legalisation
// measures N0 and q on the regions themselves (curve_lap_offset_steps.h):
// their points at the tool-centre distance d = side r (the lap's last
// operand, after the computed steps', which the regions read), at radius 0
// and around `compiledRadius` (below `largestRadius`, the most the tool
// fits with; infinite without such a limit).
struct OffsetStepGrowth {
  double side = 1;
  double compiledRadius = 0;
  double largestRadius = 0;
};

// Arcs a cut asks for (arcs=true, or --arcs) on a lap cut otherwise in
// chords or steps: the legalisation fit-arcs fits the lap's curve with
// tangent-continuous arcs within `tolerance` (the rounding of every end and
// centre to `grid` already taken off) and writes them out; where no fit
// keeps them (a curve that leaves its plane, a fit past its bound) it warns
// (arcs-as-chords) and leaves the lap to its own expansion. Level laps only.
// An arc of a radius over `largestRadius` (its centre offsets past the
// target's number range) is a line in the fit.
struct ArcsAsked {
  double tolerance = 0;
  double grid = 0;
  double largestRadius = std::numeric_limits<double>::infinity();
};

struct CurveTableEntry {
  std::vector<CurvePieceLayout> pieces;
  // The whole curve's parameter range (the first piece's start to the last
  // piece's end; a single piece's own range).
  double from = 0;
  double to = 1;
  CurveSampling sampling = CurveSampling::ChordTolerance;
  // The chord tolerance (what the points must keep, the printed rounding
  // already taken off), the number of points, the spacing in mm, the arcs'
  // tolerance (the rounding of their ends and centres taken off), or the
  // chord tolerance the steps keep (the printed rounding and the literals'
  // share taken off; 0: counts the cut gave, samples=), or
  // the tolerance the blocks keep (Sinumerik spline blocks: the cut's
  // whole tolerance, which the fit shares with the rounding itself; 0 when
  // samples= or spacing= chose the chosen points they go through).
  double amount = 0;
  // Arcs and fitted blocks: the printed grid their numbers are put on (0: none).
  double grid = 0;
  // Blocks: the function's table that holds their data (as move.nurbs or
  // move.spline reads it, or polynomialMoveTable's spans).
  std::optional<std::uint32_t> blockTable = std::nullopt;
  // Spline blocks without a table: how write-curve-blocks fits them.
  std::optional<SplineBlocksFit> splineFit = std::nullopt;
  // Steps: each region's number of uniform steps (the first point is where
  // the region starts: the end of the one before, or the lap's start); 0
  // where the program computes them: the region's range and count are then
  // operands of the lap (start, end, count after the lap's three);
  // stepsChosenByLegalisation where the legalisation measures them.
  std::vector<int> regionSteps = {};
  // Steps: the regions cut as arcs of a circle, in order of region.
  std::vector<ArcRegion> arcRegions = {};
  // Steps: the regions walked from their start by a step computed at each
  // point (each ends in curve.walk, which gives the step too) to their end:
  // the next point is at min(u + step, end); its count is the most steps
  // the walk takes. In order of region.
  std::vector<std::size_t> walkRegions = {};
  // The `curve` expression and the `cut` statement: where a failure to
  // choose the points is reported.
  frontend::SourceSpan curveSpan;
  frontend::SourceSpan cutSpan;
  // A lap over a part of a longer lap (one piece of a path whose arcs are
  // cut as arcs) descends by its share of the longer lap's descent: its
  // progress is progressFrom + progressShare * its own.
  double progressFrom = 0;
  double progressShare = 1;
  // Regions (by index over the whole lap) whose points the host computes
  // into tables even on a target that evaluates the curve in the program:
  // a NURBS span whose coefficients the controller would read too coarsely.
  std::vector<std::size_t> hostPointRegions = {};
  // Every point the host computes, printed as numbers, a feed move each,
  // where a controller computes the program (a cut beside its curve whose
  // offset the host computes: a controller keeps its numbers in a few
  // hundred variables, not in tables); on a host target, tables as others.
  bool pointsAsNumbers = false;
  // Steps: counts of an offset that grow with the tool radius (above).
  std::optional<OffsetStepGrowth> offsetGrowth = std::nullopt;
  // Chords or steps: arcs in their place where a fit keeps them (above).
  std::optional<ArcsAsked> arcsAsked = std::nullopt;
  // The same curve evaluated from the source, transforms applied (what the
  // regions compute, for choosing the points without interpreting them);
  // null in a function read from text, where the regions are interpreted.
  // It evaluates the checked program's expressions: valid while that lives
  // (the lowering's own expansion runs with it).
  std::shared_ptr<const geom::Curve> geometry = nullptr;
  // The parameters lapParameters gives, when the lowering chose them for
  // something else too (the points a spline is fitted to); null otherwise.
  // Spline blocks fitted by write-curve-blocks: the points chosen for the
  // cut (the ramp lap's before them), which samples= or spacing= makes the
  // blocks' own.
  std::shared_ptr<const std::vector<double>> chosenParameters = nullptr;
  // Chords the cut's method= (a spline) asks to be the target's curve
  // blocks: choose-curve-blocks makes them the blocks its cut prints
  // (CutGeometry::printedBlocks), where they can follow the lap.
  bool blocksAsked = false;
  // A NURBS of its own asking for blocks: the control points whose weight
  // is a part parameter read nowhere else in the curve, and the parameter
  // (by index). G06.2 keeps them the parameter's (write-curve-blocks).
  struct ParameterWeight {
    std::size_t point = 0;
    std::uint32_t parameter = 0;
  };
  std::vector<ParameterWeight> parameterWeights = {};

  // A lap cut as the target's NURBS or spline blocks.
  bool isBlocks() const {
    return sampling == CurveSampling::NurbsBlocks || sampling == CurveSampling::SplineBlocks ||
           sampling == CurveSampling::PolynomialBlocks;
  }
  std::size_t regionCount() const;
  // Steps: the regions whose range and count the program computes.
  std::size_t computedRegionCount() const;
  // The lap's operands its table entry wants: the two heights and the
  // feed, each computed region's range and count, an offset's distance.
  std::size_t lapOperandCount() const;
  // Steps: the region's arc, or null when its steps are chords.
  const ArcRegion* arcRegion(std::size_t region) const;
  bool isWalkRegion(std::size_t region) const;
  // The later piece at a join (as a composite curve evaluates it); a
  // parameter outside a piece's range is clamped into it.
  CurveLocation locate(double t) const;
  // The region index of a piece's span.
  std::size_t regionOf(std::size_t piece, std::size_t span) const;
  // The range of the parameter a region computes its point at: its piece's
  // own, or 0 .. 1 for a knot span (the span's u).
  std::pair<double, double> regionRange(std::size_t region) const;
  // The whole curve's parameter where a region's parameter is `local`.
  double wholeParameter(std::size_t region, double local) const;
  // Each region's piece and span, found in one walk over the pieces (a
  // lookup by region walks them each time: loops over the regions use these).
  struct RegionPlace {
    std::size_t piece = 0;
    std::size_t span = 0;
  };
  std::vector<RegionPlace> regionPlaces() const;
  std::pair<double, double> regionRange(const RegionPlace& place) const;
  double wholeParameter(const RegionPlace& place, double local) const;

private:
  // The piece a region belongs to and the region's span in it (0 for a
  // piece without spans); nullopt past the last region.
  std::optional<RegionPlace> placeOfRegion(std::size_t region) const;
};

} // namespace cncc::ir
