// What a `curve.lap` does: the points it moves to, chosen on the curve of
// its table entry (curve_table.h). The interpreter runs a lap with these,
// and the legalisation that writes a lap out as tables and loops
// (expandCurveLaps) uses the same, so both give the same path.
#pragma once

#include "cncc/frontend/source_span.h"
#include "cncc/geom/arc_fitting.h"
#include "cncc/geom/curve.h"
#include "cncc/geom/discretisation.h"
#include "cncc/ir/ir.h"

#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace cncc::ir {

// Why a lap's points could not be chosen, at the source it names.
class CurveLapError : public std::runtime_error {
public:
  enum class Kind {
    ProgramTooLarge,
    DegenerateCurve,
    NonFiniteValue,
    TooFewPoints,
    InvalidTolerance,
    LiteralRounding
  };
  CurveLapError(Kind kind, frontend::SourceSpan span, const std::string& message)
      : std::runtime_error(message), kind(kind), span(span) {}
  Kind kind;
  frontend::SourceSpan span;
};

// The value of a value defined outside a lap (a parameter, a constant, an
// enclosing loop's variable) that its regions read; nullopt when unknown.
using OutsideValue = std::function<std::optional<double>(ValueId)>;

namespace detail {
struct RegionProgram; // curve_lap_curve.cpp
}

// The point region `region` of `lap` computes at a parameter, compiled once
// (its pure instructions evaluated with the interpreter's arithmetic; what
// it reads from outside the lap is a constant, or asked of `outside` once).
// The constructor throws CurveLapError (at the entry's curve) for a value
// neither a constant nor known to `outside`, or an instruction that is not
// arithmetic; a point, for a table read outside the table.
class LapRegionEvaluator {
public:
  LapRegionEvaluator(const Function& function, const Instruction& lap, std::size_t region,
                     const OutsideValue& outside);
  Eigen::Vector3d operator()(double t) const;
  // A region that ends in curve.arc: the offset from its point to the centre.
  Eigen::Vector2d toCentre(double t) const;

private:
  std::shared_ptr<const detail::RegionProgram> program_;
};

// The whole curve of a lap's table entry as a geom curve in the whole
// curve's parameter: the entry's geometry when it has one, otherwise its
// regions interpreted (`lap` is the curve.lap instruction; `outside` gives
// what they read from outside the lap, param included; a constant is read
// from the IR). Per piece a curve in its own parameter (a NURBS piece's
// knot spans its breakpoints), joined as a geom::CompositeCurve when there
// are several; the curve keeps what it evaluates and may outlive the
// function. Throws CurveLapError (at the entry's curve) when a region reads
// a value `outside` does not know, holds an operation that is not pure
// arithmetic, or the pieces do not join as the entry lays them out.
std::shared_ptr<const geom::Curve> lapCurve(const Function& function, const Instruction& lap,
                                            const OutsideValue& outside);
// The same for `entry` in place of the lap's own (the entry a legalisation
// gives the lap: bound-controller-steps').
std::shared_ptr<const geom::Curve> lapCurve(const Function& function, const Instruction& lap,
                                            const CurveTableEntry& entry,
                                            const OutsideValue& outside);

// The bounds of one cut's points: the chords a tolerance may choose (the
// farthest-reach walk costs tens of microseconds a chord, and a program of
// this many blocks a cut is beyond any real 2.5D part), and the curve
// points a choice may ask (a curve that turns faster than any sampling
// resolves makes every chord cost thousands).
inline constexpr std::size_t maximumChordsPerCut = 100'000;

// How far apart (mm) the end of one piece of a path and the start of the
// next may be: rounding in the pieces' own evaluation (and in a lap's
// regions, whose arithmetic is not the source's), not a gap in the part.
inline constexpr double pathJoinTolerance = 1e-6;
inline constexpr std::size_t maximumCurveEvaluations = 20'000'000;
// The points one cut's arc fit may ask of its curve.
inline constexpr std::size_t maximumArcFitEvaluations = 5'000'000;

// The fewest chords within `tolerance` of the curve (geom's farthest-reach
// walk), within the bounds above. Throws CurveLapError at the cut (a bound)
// or at the curve (a curve that cannot be discretised).
geom::CurveSamples chordsWithinTolerance(const geom::Curve& curve, double tolerance,
                                         frontend::SourceSpan cutSpan,
                                         frontend::SourceSpan curveSpan);

// Throws CurveLapError (NonFiniteValue, at the curve) where one of `points`
// or the curve at a few probes along it is not finite: a search over a
// curve that is not would run to its bound before it failed.
void checkFiniteAlong(const CurveTableEntry& entry, const geom::Curve& curve,
                      std::span<const Eigen::Vector3d> points = {});

// The whole-curve parameters of the lap's points, the curve's start first
// and its end last, as the entry's sampling says; bounded (a limit of
// points and of curve evaluations). Throws CurveLapError.
std::vector<double> lapParameters(const CurveTableEntry& entry, const geom::Curve& curve);

// A region of a lap (a piece, or a knot span of a NURBS piece): where it
// starts in the lap's length and its share of it (fractions of the whole).
struct LapRegionShare {
  double before = 0;
  double share = 0;
};

// Each region's share, from the lengths of the regions on `curve`. Throws
// CurveLapError (a curve that cannot be measured).
std::vector<LapRegionShare> lapRegionShares(const CurveTableEntry& entry, const geom::Curve& curve);
// Each region's share of the descent a lap in steps makes: its share of the
// lap, within the lap's own share of a longer descent (progressFrom,
// progressShare: a piece between arcs).
std::vector<LapRegionShare> descentShares(const CurveTableEntry& entry, const geom::Curve& curve);

// For each of `parameters`, the share of the lap's length done there
// (0 at the start, 1 at the end): each piece or knot span takes a share of
// the descent in proportion to its length, spread over it in proportion to
// its own parameter. Throws CurveLapError.
std::vector<double> lapProgress(const CurveTableEntry& entry, const geom::Curve& curve,
                                const std::vector<double>& parameters);

// One move of a lap cut as arcs: a line to `end`, or an arc turning
// `turn` about the centre `centreOffset` from where it starts.
struct LapArcMove {
  Eigen::Vector2d end = Eigen::Vector2d::Zero();
  std::optional<ArcTurn> turn;
  Eigen::Vector2d centreOffset = Eigen::Vector2d::Zero();
};

// The moves of a lap cut as arcs (CurveSampling::Arcs) from `start`, every
// number on the entry's grid, in the plane z = planeZ (raised by the lap's
// height); moves that round to no movement are left out.
struct LapArcs {
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  double planeZ = 0;
  std::vector<LapArcMove> moves;
};

// Arcs and lines as moves on the grid: an arc too flat or too short to
// print as one (sagitta under half a grid step, chord under two) is a line.
LapArcs arcMovesOnGrid(const std::vector<geom::ArcSegment>& segments, double grid);

// Tangent-continuous arcs and lines within the options' tolerance of a
// curve in a plane z = const (geom::fitArcs), asking at most
// maximumArcFitEvaluations points of it. Throws CurveLapError: a curve that
// leaves its plane or cannot be fitted (at `curveSpan`), a fit past the
// bound (at `cutSpan`).
geom::ArcFit fitArcsWithinBudget(const geom::Curve& curve, const geom::ArcFitOptions& options,
                                 frontend::SourceSpan cutSpan, frontend::SourceSpan curveSpan);

// The arcs of a lap cut as arcs: `curve` fitted within the entry's
// tolerance (at most maximumArcFitEvaluations points of it). Throws
// CurveLapError: a curve that leaves its plane or cannot be fitted (at the
// curve), or a fit past the bound (at the cut).
LapArcs lapArcs(const CurveTableEntry& entry, const geom::Curve& curve);

// The arcs an entry asks for in place of its chords or steps (arcsAsked),
// `curve` fitted within the asked tolerance; or why no fit keeps them (the
// curve leaves its plane or cannot be fitted, the fit is past its bound).
std::variant<LapArcs, std::string> askedLapArcs(const CurveTableEntry& entry,
                                                const geom::Curve& curve);

// The arcs-as-chords warning's text: why a cut asking for arcs gets chords
// (the lowering's reasons and fit-arcs' alike).
std::string arcsAsChordsMessage(std::string_view problem);

// `fit-arcs`: every curve.lap cut as arcs written out as its move.arc and
// move.feed ops (lapArcs), each lap at its height, and so is every lap of
// an entry that asks for arcs (arcsAsked) where a fit keeps them (the cut
// then has arcMoves Fitted); where none does, the function gets an
// arcs-as-chords warning and the entry asks no more, its laps left to
// their expansion. The other laps stay. Throws CurveLapError.
bool fitLapArcs(Function& function);

// One point of a lap cut in steps: the region that computes it and its
// parameter there.
struct LapStep {
  std::size_t region = 0;
  double local = 0;
  double fraction = 1; // of the region's steps done: i / N
};

// How one region of a lap cut in steps is cut: N steps over its parameter
// range [from, to], or one step to its end (`single`: a count of one known
// when the program is written). A region of the entry's own count runs over
// its piece's range; one whose steps the program computes, over the values
// of the lap's operands.
struct StepRange {
  double from = 0;
  double to = 1;
  double count = 1;
  bool single = true;
};

// The entry's ranges; the k-th region whose steps the program computes
// takes `computed(k)`.
std::vector<StepRange> lapStepRanges(const CurveTableEntry& entry,
                                     const std::function<StepRange(std::size_t)>& computed);

// The points of a lap cut in steps (CurveSampling::Steps), in order: per
// region of N steps, from + i (to - from) / N for i = 1, 2, .. while i <= N
// (as the loop the controller runs computes them); a single step, its end.
// (An arc region's are its blocks' ends; a walked region's are not known
// before it runs.)
std::vector<LapStep> lapSteps(const std::vector<StepRange>& ranges);

// The same for one region, each step given to `visit` as it is computed.
template <class Visit>
void forEachRegionStep(std::size_t region, const StepRange& range, const Visit& visit) {
  if (range.single) {
    visit(LapStep{region, range.to, 1});
    return;
  }
  double step = (range.to - range.from) / range.count;
  for (double i = 1; i <= range.count; ++i) {
    visit(LapStep{region, range.from + i * step, i / range.count});
  }
}

// `choose-controller-steps`: on a target whose controller computes the
// program's numbers (the cut's controllerDigits), every curve.lap of its
// own cut within a chord tolerance whose points are the regions' (not
// numbers, host regions or chosen parameters) and whose regions read only
// constants is cut in steps instead: each region's count
// left to expand-controller-loops, within the cut's tolerance less the
// rounding of two axes (a curve in the plane z = 0) or three and the
// literals' share. The other laps stay.
bool chooseControllerSteps(Function& function);
// Whether a curve lies in the plane z = 0 (z exactly 0 at five probes): a
// lap cut in steps along it is rounded on two axes, not three (the
// lowering's steps and choose-controller-steps' alike).
bool liesInThePlaneZero(const geom::Curve& curve);
// The entries choose-controller-steps gives, by their index in the curve
// table: what the interpreter runs their laps with too.
std::map<std::uint32_t, CurveTableEntry> controllerStepsEntries(const Function& function);

// `bound-controller-steps`: every curve.lap cut in steps within a
// tolerance whose cut the host computes (no controllerDigits: the host
// chooses chords, fewer than the uniform steps), and every one whose
// counts, at the values the part is compiled with, come past
// maximumStepsPerRegion, cut at points chosen on the host within its
// tolerance instead: a chord entry of a piece per region, each over the
// range it had (a walk's end a curve.point), its regions the same; the
// parameters they read fixed (on a controller a parameter-fixed warning
// each). The other laps stay (samples=, arc regions, an offset's growth).
bool boundControllerSteps(Function& function);
// `unroll-host-control`: where the host computes the program (no cut has
// controller digits), each `for` loop written out trip by trip at its
// bounds' compiled values and each `if` whose branches cut replaced by the
// branch taken there, what they read fixed; each trip's cut its own (the
// cut table in the program's order, a cut of a branch not taken dropped)
// and each trip's curve.lap that reads the loop's variable an entry of its
// own without geometry. Throws CurveLapError past 100000 trips in
// all.
bool unrollHostControl(Function& function);
// `split-arc-laps`: on a cut the host computes, each curve.lap in steps with
// arc regions written as a lap per piece: an arc in its blocks at the
// compiled values (whole turns where it turns whole turns), each other
// piece in chords within the cut's tolerance; what the lap reads fixed.
// The other laps stay (a controller's, an offset's growth, a walk).
bool splitArcLaps(Function& function);
// The cut of a lap before any cut.begin.
inline constexpr std::uint32_t noCut = ~std::uint32_t{0};
// The chord entry bound-controller-steps gives the lap, of the function's
// cut `cut` (or noCut; its geometry the lap's over the ranges its regions had), or
// nullopt where the lap stays: what the interpreter runs too. `trip`: the
// values of the loop variables the lap reads in the trip being run, as
// unroll-host-control writes it out (map of value index to value).
std::optional<CurveTableEntry>
boundedStepsEntry(const Function& function, const Instruction& lap, std::uint32_t cut,
                  const std::map<std::uint32_t, double>* trip = nullptr);

// `expand-controller-loops`: every curve.lap cut in steps written out as a
// loop per region (its arithmetic at the loop's parameter, a feed move to
// the point), each lap at its height, or descending through its regions by
// their shares of its length (lapRegionShares) and in each in proportion
// to the steps done; the other laps stay. Throws CurveLapError.
bool expandControllerLoops(Function& function);

// `choose-curve-blocks`: every curve.lap of constants whose entry asks for
// curve blocks (blocksAsked: a cut's method= of a spline) given the entry
// of the blocks its cut prints (CutGeometry::printedBlocks) where they can
// follow it: Sinumerik spline blocks of a curve in a plane z = constant (a
// ramp lap chords through the points they are fitted to), Heidenhain SPL
// spans and G06.2 NURBS blocks (method=nurbs) of a cut without a ramp; the
// other laps stay chords. Throws CurveLapError where the tolerance leaves
// nothing past the rounding of the blocks' points.
bool chooseCurveBlocks(Function& function);

// `write-curve-blocks`: every curve.lap cut as the target's NURBS or spline
// blocks written out as the move.nurbs or move.spline of its entry's table,
// at its height and feed (a NURBS block's weights the lap's operands after
// its three); the other laps stay. Throws CurveLapError for a ramp lap.
bool writeCurveBlocks(Function& function);

// `expand-curve-laps`: every curve.lap written out as today's host form:
// per run of points in one region a loop over a table of the region's
// parameters (and of the ramp's progress), the region's arithmetic in its
// body, a feed move to each point; points the entry marks are host tables.
// Laps cut as blocks, as arcs or in steps are written out first
// (writeCurveBlocks, fitLapArcs, expandControllerLoops). The curve table is
// emptied once no lap refers to it. Throws CurveLapError.
bool expandCurveLaps(Function& function);

} // namespace cncc::ir
