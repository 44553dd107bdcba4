// The lowering's private parts: one PartLowering per part, its members
// implemented by concern in statements.cpp, expressions.cpp, curves.cpp and
// cuts.cpp of this folder (and the others it names); the values it computes
// with are in lowering_values.h and arithmetic.h, the plans of cuts beside
// their curves in beside_curve.h.
#pragma once

#include "affine.h"
#include "arithmetic.h"
#include "beside_curve.h"
#include "cncc/ir/tolerance_budget.h"
#include "lowering_values.h"

#include "cncc/frontend/sema.h"
#include "cncc/frontend/value.h"
#include "cncc/geom/arc_fitting.h"
#include "cncc/geom/curve.h"
#include "cncc/geom/discretisation.h"
#include "cncc/geom/nurbs_curve.h"
#include "cncc/geom/polynomial_span.h"
#include "cncc/ir/builder.h"
#include "cncc/ir/polynomial_move.h"
#include "cncc/lowering/lowering.h"

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace cncc::ir::lowering {

// The lowering's state, to go back to when a controller loop or branch
// cannot be lowered as one (runtime_control.cpp).
struct LoweringState;

// The modal machine settings the lowering has emitted so far, as far as it
// knows: where a controller loop or branch may leave a mode one way or
// another, it is unknown (nullopt), and the next cut or the part's end sets
// it again.
struct MachineSettings {
  bool originChosen = false;
  // A tool change whose length offset no Z move has activated yet: the next
  // cut's first rapid does, unless a controller loop or branch comes first.
  bool lengthOffsetPending = false;
  std::optional<double> contouring = 0.0; // its tolerance; 0: off
  std::optional<CoolantMode> coolant = CoolantMode::Off;

  // The modes known both here and in `other` (where control flow joins).
  void keepModesAgreedWith(const MachineSettings& other) {
    if (contouring != other.contouring) {
      contouring.reset();
    }
    if (coolant != other.coolant) {
      coolant.reset();
    }
  }
  bool sameModes(const MachineSettings& other) const {
    return contouring == other.contouring && coolant == other.coolant;
  }
};

// Thrown by a controller loop's first lowering whose trip leaves a mode
// other than it found it: the modes to lower the body for again.
struct TripChangesModes {
  MachineSettings atHead;
};

// What of a cut depends on a part parameter (cuts.cpp, parameterUse).
struct ParameterUse {
  std::string what;
  std::string parameter;
};

// What a cut computed on the host starts with (cuts.cpp, beginHostCut).
struct HostCut {
  Scalar feed;
  bool ramp = false;
};

// The frontend's evaluator, renewed every so many evaluations: each
// evaluator has a step budget against pathological inputs, which the
// thousands of evaluations of a curve's points would otherwise exhaust.
class RenewingEvaluator {
public:
  RenewingEvaluator(const frontend::CheckedProgram& program,
                    frontend::DiagnosticEngine& diagnostics)
      : program_(program), diagnostics_(diagnostics) {}

  frontend::Value evaluate(const frontend::Expr& expression,
                           const frontend::Environment& environment);

private:
  static constexpr int evaluationsPerEvaluator = 1000;
  const frontend::CheckedProgram& program_;
  frontend::DiagnosticEngine& diagnostics_;
  std::unique_ptr<frontend::ExpressionEvaluator> evaluator_;
  int evaluations_ = 0;
};

struct ControllerSegment; // controller_cuts.cpp

// A translate/rotate/scale chain as controller arithmetic:
// p -> (linear * p.xy + offset, zScale * p.z), row-major linear.
struct RuntimeTransform {
  std::array<Scalar, 4> linear{Scalar::of(1), Scalar::of(0), Scalar::of(0), Scalar::of(1)};
  std::array<Scalar, 2> offset{Scalar::of(0), Scalar::of(0)};
  Scalar zScale = Scalar::of(1);
  // At least the largest stretch of the linear part (the product of the
  // scale factors' sizes; rotations and translations stretch nothing).
  Scalar norm = Scalar::of(1);

  bool isConstant() const;
};

// A smooth piece of a cut's curve as the controller computes it: the
// builtin call that makes it (polar, param, line, arc, nurbs, ...), the
// bindings its expressions lower under (the arguments of the fns around
// it, as IR values where they depend on parameters) and its transform.
struct SymbolicPiece {
  const frontend::CallExpr* call = nullptr;
  Bindings bindings;
  frontend::Environment environment;
  RuntimeTransform transform;
  // Whether anything of the piece depends on a value the controller
  // computes, and whether its own shape (not only its transform) does.
  bool dependent = false;
  bool shapeDependent = false;
};

// Whether the expression names a bound declaration anywhere inside.
bool dependsOn(const frontend::Expr& expression, const Bindings& bindings);

class PartLowering {
public:
  PartLowering(const frontend::CheckedProgram& program, const frontend::PartItem& part,
               frontend::DiagnosticEngine& diagnostics, const LoweringOptions& options);

  LoweredPart run();

private:
  [[noreturn]] void unsupported(frontend::SourceSpan span, std::string_view what);
  [[noreturn]] void
  fail(frontend::SourceSpan span, std::string message,
       frontend::DiagnosticKind kind = frontend::DiagnosticKind::UnsupportedConstruct);
  void checkSize(frontend::SourceSpan span);

  // statements.cpp
  void lowerParameters();
  void lowerBlock(const frontend::Block& block);
  void lowerStatement(const frontend::Stmt& statement);
  void lowerTool(const frontend::ToolStmt& tool);
  void lowerLet(const frontend::LetStmt& let);
  void lowerFor(const frontend::ForStmt& loop);
  void lowerIf(const frontend::IfStmt& conditional);

  // runtime_control.cpp: `for` and `if` that the controller runs, when
  // their bounds or condition depend on parameters.
  bool lowerControllerFor(const frontend::ForStmt& loop);
  bool lowerControllerIf(const frontend::IfStmt& conditional);
  bool attempt(const std::function<void(LoweringState&)>& lowering);
  LoweringState saveState();
  void restoreState(LoweringState& state);
  // The name parametersOf gives a controller loop's variable.
  static std::string loopVariableMarker(const frontend::Declaration* declaration);
  static bool isLoopVariableMarker(std::string_view name);

  // fixed_parameters.cpp
  std::set<std::string> parametersOf(const frontend::Expr& expression) const;
  // Records the parameters `expression` reads as fixed at their defaults by
  // this use (`what`, such as "loop bound"), warning on controller targets.
  void fixParameters(const frontend::Expr& expression, frontend::SourceSpan use,
                     std::string_view what);
  // Throws NeedsUnrolling when `names` hold a controller loop's variable:
  // what reads it as a number needs the loop unrolled.
  static void unrollForLoopVariables(const std::set<std::string>& names);

  // expressions.cpp
  frontend::Value evaluate(const frontend::Expr& expression,
                           const frontend::Environment& environment);
  double constantNumber(const frontend::Expr& expression, std::string_view what);
  Scalar number(const frontend::Expr& expression);
  // A feed rate or spindle speed: a number within the machine's maximum
  // (LoweringOptions) at the values the part is compiled with.
  Scalar feedRate(const frontend::Expr& expression);
  Scalar spindleSpeed(const frontend::Expr& expression);
  Scalar withinMachineLimit(const frontend::Expr& expression, double limit, std::string_view what,
                            std::string_view unit);
  std::optional<Lowered> constantOf(const frontend::Value& value);
  std::optional<Lowered> tryLower(const frontend::Expr& expression, const Bindings& bindings,
                                  const frontend::Environment& environment);
  std::optional<Lowered> lowerDirect(const frontend::Expr& expression, const Bindings& bindings,
                                     const frontend::Environment& environment);
  std::optional<Lowered> lowerUnary(const frontend::UnaryExpr& unary, const Bindings& bindings,
                                    const frontend::Environment& environment);
  std::optional<Lowered> lowerBinary(const frontend::BinaryExpr& binary, const Bindings& bindings,
                                     const frontend::Environment& environment);
  std::optional<Lowered> lowerIfElse(const frontend::IfElseExpr& choice, const Bindings& bindings,
                                     const frontend::Environment& environment);
  std::optional<Lowered> lowerCall(const frontend::CallExpr& call, const Bindings& bindings,
                                   const frontend::Environment& environment);
  std::optional<Lowered> lowerIndex(const frontend::IndexExpr& index, const Bindings& bindings,
                                    const frontend::Environment& environment);

  // curves.cpp
  CutCurve cutCurve(const frontend::CutStmt& cut);
  void addPieces(const std::shared_ptr<const frontend::CurveValue>& value, const Affine& transform,
                 const frontend::CutStmt& cut, CutCurve& curve);
  CurvePiece leafPiece(const std::shared_ptr<const frontend::CurveValue>& value,
                       const frontend::CutStmt& cut);
  std::shared_ptr<const geom::Curve>
  analyticCurve(const std::shared_ptr<const frontend::CurveValue>& curve);
  void joinPieces(CutCurve& curve, const frontend::CutStmt& cut);
  SampleLocation locate(const CutCurve& curve, double t) const;
  // Where the piece's own parameter lies (its NURBS span and the span's u).
  static SampleLocation locateInPiece(const CutCurve& curve, std::size_t piece, double own);
  CurvePoint pointAt(const CutCurve& curve, std::size_t piece, std::size_t span, Scalar local,
                     const frontend::CutStmt& cut);
  CurvePoint untransformedPointAt(const CurvePiece& piece, std::size_t span, Scalar local,
                                  const frontend::CutStmt& cut);
  CurvePoint spanPointAt(const geom::PolynomialSpan& span, Scalar u);
  // Whether the controller, reading the span's power-basis coefficients to
  // its significant digits, stays within a quarter of the cut's tolerance.
  // `stretch`: how much the transform the controller applies after the
  // span lengthens it (the rounding moves the points that much more).
  bool spanLiteralsFit(const geom::PolynomialSpan& span, const frontend::CutStmt& cut,
                       double stretch);
  CurvePoint transformed(const Affine& transform, const CurvePoint& point);
  CurvePoint linePointAt(const Eigen::Vector3d& from, const Eigen::Vector3d& to, double length,
                         Scalar local);
  CurvePoint arcPointAt(const ArcNumbers& arc, Scalar local);

  // cuts.cpp
  void lowerCut(const frontend::CutStmt& cut);
  // Its points fixed at the defaults, its method and entry checked, a safe
  // height and a feed required.
  // `blocksAsked`: choose-curve-blocks says where the method= is chords.
  HostCut beginHostCut(const frontend::CutStmt& cut, bool blocksAsked = false);
  // Enters the cut into the part's cut table and starts its moves: the
  // controller's contouring mode for its tolerance, then `cut.begin`;
  // returns whether the cut's first Z move activates a tool's length offset.
  bool beginCutMoves(CutGeometry geometry);
  // The cut just begun runs beside `drawn` at `toolRadius` (side=).
  void markCutBeside(std::shared_ptr<const geom::Curve> drawn, double toolRadius);
  // The default work offset (G54) when none has been chosen yet: before
  // the first tool change or move.
  void ensureOrigin();
  // Before a controller loop or branch: a pending length offset activated
  // by a rapid to the safe height over the origin, so that the printed
  // program activates it before its branches.
  void activateLengthOffset();
  void lowerOrigin(const frontend::OriginStmt& origin);
  void lowerCoolant(const frontend::CoolantStmt& coolant);
  // At the end of the part: contouring and coolant off, Z to the machine's
  // reference.
  void endMachineSettings();
  void checkMethod(const frontend::CutStmt& cut, bool blocksAsked = false);
  // Whether the cut's laps ask choose-curve-blocks for the target's curve
  // blocks: a method= spline, on its own curve, with no arcs cut as arcs.
  bool blocksAskedBy(const frontend::CutStmt& cut) const;
  // The cut just begun (beginCutMoves) notes where its method= is written.
  void noteMethodSpan(const frontend::CutStmt& cut);
  // The first of the cut's curve and `toolDiameter` that depends on a part
  // parameter; nullopt when none does (depth= and step= may: the sweep's
  // pass loop computes them). A controller loop's variable unrolls the loop
  // instead (NeedsUnrolling).
  std::optional<ParameterUse> parameterUse(const frontend::CutStmt& cut,
                                           const frontend::Expr* toolDiameter = nullptr);
  bool rampEntry(const frontend::CutStmt& cut);
  Scalar cutFeed(const frontend::CutStmt& cut);
  std::optional<double> chordTolerance(const frontend::CutStmt& cut);
  // The cut's tolerance and the printed grid's share of it (computed here only).
  ToleranceBudget toleranceBudget(const frontend::CutStmt& cut);
  std::size_t sampleCount(const frontend::CutStmt& cut);
  geom::CurveSamples samplesFor(const frontend::CutStmt& cut, const geom::Curve& curve);
  // spacing= that would put more points on the curve than a cut may have.
  void checkSpacing(const frontend::CutStmt& cut, const geom::Curve& curve, double spacing);
  void lowerCurveLaps(const frontend::CutStmt& cut, const CutCurve& curve);
  CurveTableEntry curveTableEntry(const frontend::CutStmt& cut, const CutCurve& curve,
                                  std::optional<ArcsAsked> arcs = std::nullopt);
  // How the entry's points are chosen on `curve`: samples=, spacing= or
  // within `chordTolerance` (checked here as far as an estimate goes, but
  // for an entry asking for arcs, which may keep what chords cannot).
  void chooseSampling(CurveTableEntry& entry, const frontend::CutStmt& cut,
                      const geom::Curve& curve, double chordTolerance);
  CurveTableEntry wholeCurveTableEntry(const frontend::CutStmt& cut, const CutCurve& curve);
  CurveTableEntry curveTableEntryOn(const frontend::CutStmt& cut,
                                    std::shared_ptr<const geom::Curve> geometry);
  CurveTableEntry pieceCurveTableEntry(const frontend::CutStmt& cut, const CutCurve& curve,
                                       std::size_t piece, const std::vector<RampSegment>& shares);
  CurvePieceLayout pieceLayout(const CurvePiece& piece, double start);
  void addPieceLayout(CurveTableEntry& entry, const CurvePiece& piece, double start,
                      const frontend::CutStmt& cut);
  void emitCurveLap(const CutCurve& curve, std::uint32_t table, ValueId zFrom, ValueId zTo,
                    ValueId feed, const frontend::CutStmt& cut, std::size_t firstPiece = 0,
                    std::size_t endPiece = SIZE_MAX);
  // The lap's regions compute `pointOf(piece, span, local)`; the lap takes
  // `operands` (z from, z to, feed, then the ranges and counts of the regions
  // whose steps the program computes).
  using LapPointOf =
      std::function<LapRegionPoint(std::size_t piece, std::size_t span, Scalar local)>;
  // The curve's own point (pointAt), as a host cut's lap computes it.
  LapPointOf curvePointOf(const CutCurve& curve, const frontend::CutStmt& cut);
  void emitCurveLapAt(const CutCurve& curve, std::uint32_t table, std::vector<ValueId> operands,
                      const LapPointOf& pointOf, std::size_t firstPiece = 0,
                      std::size_t endPiece = SIZE_MAX);
  // The same for a lap of `regions` regions, region r computing `pointOf(r, local)`.
  using RegionPointOf = std::function<LapRegionPoint(std::size_t region, Scalar local)>;
  void emitLapRegions(std::uint32_t table, std::vector<ValueId> operands, std::size_t regions,
                      const RegionPointOf& pointOf);
  // The same, every point finite and at least two of them (else an error).
  geom::CurveSamples checkedSamplesFor(const frontend::CutStmt& cut, const geom::Curve& curve);
  // Before any point is computed: the curve and the depth within the
  // target's number range. With a `margin` (a cut beside the curve at that
  // distance), only a curve past the range by more than it: the offset
  // then is too (drawnClearance, before its clearance is checked).
  void checkCutBounds(const frontend::CutStmt& cut, const geom::Curve& curve, double margin = 0);
  // Before the chords are chosen: no more than a cut may have.
  void checkChordCount(const frontend::CutStmt& cut, const geom::Curve& curve, double tolerance);
  [[noreturn]] void tooManyChords(const frontend::CutStmt& cut, std::string_view path,
                                  double chords, double tolerance);
  // The chords of `curve` within `budget`, checked and bounded as above; an
  // error at the cut when they cannot be found.
  geom::CurveSamples chordsWithinBudget(const frontend::CutStmt& cut, const geom::Curve& curve,
                                        double budget);
  // The target's largest number in the part's units.
  double largestNumberInUnits() const;
  double largestCoordinateInUnits() const; // LoweringOptions::largestCoordinate, at most the above
  std::vector<double> passDepths(const frontend::CutStmt& cut);
  // sweeps.cpp: the cut's passes, a pass loop on every target (depth and
  // step computed by the program where they read parameters, else fixed
  // numbers), until endSweep.
  SweepHeights beginSweep(const frontend::CutStmt& cut, bool ramp, const SweepStart& start);
  // Whether the expression reads a part parameter or a value the program
  // computes (a controller loop's variable); false for none.
  bool readsRunTimeValues(const frontend::Expr* expression) const;
  void endSweep(const SweepHeights& sweep);
  // The whole sweep of laps along a curve: each pass a rapid over the
  // start, a feed down to it (to the pass above with entry=ramp, then the
  // ramp lap `lap(above, z)`), the lap `lap(z, z)`, a rapid over `finish`.
  // With `leads` (lead=R beside the curve) the lead-in arc follows the
  // plunge, at the height a ramp starts from, and the lead-out arc the lap:
  // `start` and `finish` are then theirs.
  using SweepLap = std::function<void(ValueId zFrom, ValueId zTo)>;
  void emitSweep(const frontend::CutStmt& cut, bool ramp, const SweepStart& start,
                 std::array<ValueId, 2> finish, ValueId feed, const SweepLap& lap,
                 const CompensatedLeads* leads = nullptr);
  Scalar passDepth(Scalar pass, Scalar step, Scalar depth); // -min(pass step, depth)
  // The height of a plane at `planeZ` lowered to a pass's z: a number on the
  // printed grid, or the controller's sum (which it rounds itself).
  ValueId planeHeight(double planeZ, Scalar passZ);
  // A height value as a Scalar: the number where it is a constant.
  Scalar heightOf(ValueId z);
  std::vector<RampSegment> rampSegments(const CutCurve& curve, const frontend::CutStmt& cut);
  static RampSegment rampSegmentOf(const std::vector<RampSegment>& segments, std::size_t piece,
                                   std::size_t span);
  void checkRampCloses(const CutCurve& curve, const frontend::CutStmt& cut);
  // native_arcs.cpp
  static bool wantsNativeArcs(const frontend::CutStmt& cut);
  static bool hasArcPiece(const CutCurve& curve);
  void lowerHostArcCut(const frontend::CutStmt& cut, const CutCurve& curve);
  ArcPath constantArcPath(const CutCurve& curve, std::size_t piece, const frontend::CutStmt& cut);
  ArcPath symbolicArcPath(const SymbolicPiece& piece, const frontend::CurveValue& value);
  // The program stops with `message` where `condition` holds.
  void alarmWhen(Scalar condition, std::string message);
  void guardArc(const ArcPath& arc);
  ArcBlocks arcBlocks(const ArcPath& arc, const frontend::CutStmt& cut);
  void emitArc(const ArcPath& arc, const ArcHeight& height, ValueId feed,
               const frontend::CutStmt& cut);
  void emitArcBlocks(const ArcPath& arc, ArcTurn turn, Scalar count, bool fullTurns,
                     const ArcHeight& height, ValueId feed);
  void emitArcBlock(const ArcPath& arc, ArcTurn turn, Scalar from, Scalar to, bool fullTurn,
                    const ArcHeight& height, ValueId feed, std::optional<Scalar> done = {});
  CurvePoint radiusTowardsCentre(Scalar radius, Scalar from, Scalar sweep, Scalar fraction);

  // nurbs_weights.cpp: per weight of a nurbs(...) cut, the part parameter
  // it is (its value), or nullopt for a number; and those read nowhere else
  // in the curve (CurveTableEntry::parameterWeights).
  std::vector<std::optional<ValueId>> parameterWeights(const frontend::CutStmt& cut,
                                                       const CutCurve& curve);
  std::vector<CurveTableEntry::ParameterWeight> ownWeightParameters(const frontend::CutStmt& cut,
                                                                    const CutCurve& curve);

  // offset_cuts.cpp: cuts beside the curve (side=left|right).
  bool lowerOffsetCut(const frontend::CutStmt& cut);
  // The signed offset (the tool's radius, > 0 to the left), after checking
  // what the offset needs; an error at the cut otherwise.
  double offsetDistance(const frontend::CutStmt& cut, const frontend::Modifier& side,
                        bool controller);
  // The exact offset of the cut's curve, or tool-too-large at the cut.
  // With `drawn`, the drawn curve sampled for the clearance check (else
  // sampled here).
  geom::PiecesOffset checkedOffset(const frontend::CutStmt& cut, const CutCurve& curve,
                                   double distance, const DrawnClearance* drawn = nullptr);
  // The cut's drawn pieces (of `curve`) sampled for clearance checks within
  // its tolerance, once the curve is within the number range (less
  // `distance`) and the chords of their offset by `distance` are estimated
  // within the limit; coordinate-range or program-too-large at the cut past
  // either.
  DrawnClearance drawnClearance(const frontend::CutStmt& cut, const CutCurve& curve,
                                const std::vector<std::shared_ptr<const geom::Curve>>& pieces,
                                double distance);
  void checkOffsetChordCount(const frontend::CutStmt& cut,
                             const std::vector<std::shared_ptr<const geom::Curve>>& pieces,
                             double distance, double tolerance);
  [[noreturn]] void offsetCheckTooLarge(const frontend::CutStmt& cut, std::size_t limit);
  std::optional<CompensatedLeads> hostLeads(const frontend::CutStmt& cut, const CutCurve& curve,
                                            const geom::Curve& offset, double distance);
  void warnSplineOffsetWithLeads(const frontend::CutStmt& cut);
  // arcs=true, or --arcs on a target that prints arcs, without arcs=false.
  bool asksFittedArcs(const frontend::CutStmt& cut);
  geom::CurveSamples offsetSamples(const frontend::CutStmt& cut, const geom::Curve& offset);
  // The chord tolerance of an offset's points (less a reader's rounding).
  double offsetChordTolerance(const frontend::CutStmt& cut);
  // offset_laps.cpp: the offset as its laps compute it, each of its pieces
  // beside a drawn piece or a corner's arc; its entry cut as points; a lap
  // of it.
  std::shared_ptr<const BesideCurve> besideCurve(const frontend::CutStmt& cut,
                                                 const CutCurve& curve,
                                                 const geom::PiecesOffset& offset, double distance);
  // The offset's points within the cut's budget (as numbers on a
  // controller), its level laps asking for `arcs` where given, and for the
  // target's curve blocks where `blocksAsked`.
  std::uint32_t besideChordsCurve(const frontend::CutStmt& cut, const BesideCurve& beside,
                                  std::optional<ArcsAsked> arcs = std::nullopt,
                                  bool blocksAsked = false);
  std::uint32_t chosenPointsCurve(const frontend::CutStmt& cut, const BesideCurve& beside,
                                  const std::vector<double>& parameters);
  // The lap with its operands (z from, z to, feed, then a NURBS block's weights).
  void emitBesideLapAt(const BesideCurve& beside, std::uint32_t table,
                       std::vector<ValueId> operands, const frontend::CutStmt& cut);
  LapRegionPoint besidePoint(const BesideCurve& beside, const HostBesideRegion& region,
                             Scalar local, const frontend::CutStmt& cut);
  void lowerHostOffsetCut(const frontend::CutStmt& cut, double distance);
  HostOffsetLaps hostOffsetLaps(const frontend::CutStmt& cut,
                                const std::shared_ptr<const geom::Curve>& offset,
                                const BesideCurve& beside, bool ramp);
  void emitHostOffsetLap(const HostOffsetLaps& laps, const BesideCurve& beside, ValueId zFrom,
                         ValueId zTo, ValueId feed, const frontend::CutStmt& cut);

  // compensated_cuts.cpp: comp=controller, the curve itself with the
  // controller's cutter radius compensation (G41/G42 D.., G40) and tangent
  // lead arcs.
  void lowerCompensatedCut(const frontend::CutStmt& cut, const frontend::Modifier& comp,
                           double distance);
  double leadRadius(const frontend::CutStmt& cut, double toolRadius);
  // An error at lead= (at the cut without one) where the tool, its centre on
  // either of `centre`'s arcs (the tool centre's lead arcs), would come
  // nearer than its radius to `contour`, the curve cut: the lead crosses the
  // part.
  void checkLeadClearance(const frontend::CutStmt& cut, const CompensatedLeads& centre,
                          const geom::Curve& contour, double toolRadius);
  void emitCompensatedPass(const CompensatedLeads& leads, ValueId safe, Scalar passZ, ValueId feed,
                           const std::function<void(ValueId z)>& contour);
  std::array<ValueId, 2> printedPoint(const Eigen::Vector3d& point);
  // G39 (corner.arc) at convex corners (LoweringOptions::compensationCornerArcs).
  void emitCornerArc(const Eigen::Vector3d& tangent);
  std::vector<std::uint32_t> stretchCurves(const frontend::CutStmt& cut, const BesideCurve& drawn,
                                           const std::vector<double>& parameters,
                                           const std::vector<ChordCorner>& corners);
  void emitArcLapWithCorners(const std::vector<geom::ArcSegment>& segments, double offset,
                             ValueId z, ValueId feed);

  // arc_cuts.cpp
  // The arcs (fit-arcs fits them) the cut asks of its level laps; nullopt,
  // warning arcs-as-chords, where the cut stands in the way.
  std::optional<ArcsAsked> arcsAskedBy(const frontend::CutStmt& cut);
  std::optional<std::string> arcCutProblem(const frontend::CutStmt& cut);
  void reportArcsAsChords(const frontend::CutStmt& cut, std::string_view problem);
  // Each piece's curve table entry, its points within the cut's chord
  // budget (descending by `shares` when not empty); an arc piece has none
  // (it is cut as move.arc).
  std::vector<std::optional<std::uint32_t>>
  pieceCurveTables(const frontend::CutStmt& cut, const CutCurve& curve,
                   const std::vector<RampSegment>& shares);
  Eigen::Vector2d emitArcLap(const std::vector<geom::ArcSegment>& segments, ValueId z,
                             ValueId feed);

  // controller_cuts.cpp
  bool lowerControllerCut(const frontend::CutStmt& cut, const CutCurve& curve);
  bool chordsTheLegalisationSteps(const frontend::CutStmt& cut, const CutCurve& curve,
                                  bool uniformSteps, const ToleranceBudget& tolerances);
  bool cutInSingleSteps(const CutCurve& curve, double budget);
  bool oneStepKeeps(const geom::Curve& geometry, double from, double to, double budget,
                    std::size_t& evaluated);
  // A lap cut in steps: its curve table entry and the ranges and counts of
  // its regions whose steps the program computes.
  struct SteppedLap {
    std::uint32_t table = 0;
    std::vector<ValueId> computedSteps;
    std::vector<BesideRegion> besideRegions = {};
  };
  // An arc segment's region: its blocks in the entry, their count an
  // operand where the program computes it or the arc is symbolic.
  void addArcRegion(CurveTableEntry& entry, SteppedLap& lap, const ControllerSegment& segment,
                    const CutCurve& curve, const frontend::CutStmt& cut);
  LapRegionPoint arcRegionPoint(const CutCurve& curve, const ControllerSegment& segment,
                                Scalar local, const frontend::CutStmt& cut);
  void addWalkRegion(CurveTableEntry& entry, SteppedLap& lap, const ControllerSegment& segment);
  static bool countsItsSteps(const ControllerSegment& segment);
  LapRegionPoint steppedRegionPoint(const CutCurve& curve, const ControllerSegment& segment,
                                    Scalar local, const frontend::CutStmt& cut);
  // The chord tolerance uniform steps are measured within: `budget` less
  // the literals' share of the increment (0: counts samples= gave).
  double measuredBudget(double budget) const;
  SteppedLap steppedLap(const frontend::CutStmt& cut, const CutCurve& curve,
                        const std::vector<ControllerSegment>& segments, double budget);
  void emitSteppedLap(const CutCurve& curve, const SteppedLap& lap,
                      const std::vector<ControllerSegment>& segments, ValueId zFrom, ValueId zTo,
                      ValueId feed, const frontend::CutStmt& cut);
  bool offsetOnControllerWanted(const frontend::CutStmt& cut, const CutCurve& curve);
  bool lowerControllerOffsetCut(const frontend::CutStmt& cut, double compiledDistance,
                                bool runtime);
  void guardRuntimeRadius(const RuntimeOffset& offset);
  bool runtimeOffsetRefused(bool runtime, frontend::SourceSpan span, std::string_view what);
  double largestFittingRadius(const std::vector<std::shared_ptr<const geom::Curve>>& pieces,
                              double compiledDistance, const DrawnClearance& drawn);
  bool planOffsetSteps(const CutCurve& curve, std::vector<ControllerSegment>& segments,
                       double budget);
  // base + value * factor, a constant factor's sign as a subtraction.
  Scalar plusScaled(Scalar base, Scalar value, Scalar factor);
  CurvePoint besideAt(const CurvePoint& point, const Eigen::Vector2d& normal);
  CurvePoint offsetSegmentEnd(const CutCurve& curve, const ControllerSegment& segment, bool atEnd,
                              const CurvePoint& point);
  // point + distance (-y', x') / |C'|, C' the derivative of the point in `variable`.
  CurvePoint offsetAlongDerivative(const CurvePoint& point, ValueId variable, Scalar distance,
                                   const frontend::CutStmt& cut);
  // controller_offset_laps.cpp
  SteppedLap besideSteppedLap(const frontend::CutStmt& cut, const CutCurve& curve,
                              const std::vector<ControllerSegment>& segments, double budget);
  LapRegionPoint besideRegionPoint(const CutCurve& curve,
                                   const std::vector<ControllerSegment>& segments,
                                   const BesideRegion& region, Scalar local,
                                   const frontend::CutStmt& cut);
  LapRegionPoint offsetArcRegionPoint(const CutCurve& curve, const ControllerSegment& segment,
                                      Scalar local, const frontend::CutStmt& cut);
  LapRegionPoint cornerArcRegionPoint(const PieceJoin& join, Scalar fraction);
  CurvePoint pointBetween(const CurvePoint& from, const CurvePoint& to, Scalar fraction);
  std::optional<std::vector<ControllerSegment>>
  planControllerSegments(const CutCurve& curve, const frontend::CutStmt& cut, double budget,
                         const std::vector<SymbolicPiece>* symbolic,
                         std::optional<int> uniformSteps);
  bool symbolicPiecesUsable(const std::vector<SymbolicPiece>& pieces, const CutCurve& curve);
  Scalar stepsOf(const ControllerSegment& segment);
  std::optional<std::vector<std::optional<Lowered>>> symbolicList(const frontend::Expr& expression);
  std::optional<std::vector<std::optional<Lowered>>>
  symbolicList(const frontend::Expr& expression, const Bindings& bindings,
               const frontend::Environment& environment);
  const frontend::Expr* curveArgument(const frontend::CutStmt& cut, std::string_view name);
  CurvePoint segmentEndPoint(const CutCurve& curve, const ControllerSegment& segment, bool atEnd,
                             const frontend::CutStmt& cut);
  std::optional<Scalar> polarStepCount(const SymbolicPiece& piece,
                                       const frontend::CurveValue& value, double budget);
  using SymbolicList = std::vector<std::optional<Lowered>>;
  void planSplitSpan(const CurvePiece& piece, const SymbolicList* weights,
                     const SymbolicList* points, ControllerSegment& segment, double budget,
                     Scalar norm);
  struct NurbsLists {
    std::optional<SymbolicList> points, weights;
  };
  std::optional<NurbsLists> nurbsLists(const SymbolicPiece& piece);
  void guardWeights(const SymbolicList& weights);
  CurvePoint movedSplitSpanPoint(const ControllerSegment& segment, Scalar u);
  Scalar hornerOf(const std::vector<double>& polynomial, Scalar u);
  // rational_span_walk.cpp
  // The order-th derivative of a split span's homogeneous point (x, y, z, w) at u.
  std::array<Scalar, 4> splitSpanDerivative(const ControllerSegment& segment, Scalar u, int order);
  // The step from u whose chord keeps the budget; `point` is the homogeneous point at u.
  Scalar rationalSpanStep(const ControllerSegment& segment, Scalar u,
                          const std::array<Scalar, 4>& point);
  // The span's loop, its parameter advanced by rationalSpanStep; moveTo
  // gets each point and its parameter (the share of the span done).

  // symbolic_curves.cpp
  std::optional<std::vector<SymbolicPiece>> symbolicPieces(const frontend::Expr& curve);
  bool collectSymbolicPieces(const frontend::Expr& curve, const Bindings& bindings,
                             const frontend::Environment& environment,
                             const RuntimeTransform& outer, std::vector<SymbolicPiece>& pieces,
                             int depth);
  std::optional<RuntimeTransform> ownTransform(const frontend::CallExpr& call,
                                               const Bindings& bindings,
                                               const frontend::Environment& environment);
  RuntimeTransform composed(const RuntimeTransform& outer, const RuntimeTransform& inner);
  CurvePoint applied(const RuntimeTransform& transform, const CurvePoint& point);
  std::optional<Scalar> symbolicNumber(const frontend::Expr* expression, const Bindings& bindings,
                                       const frontend::Environment& environment);
  // The point of a line or arc piece at s in [0, 1], of a polar or param
  // piece at its own t; transformed.
  std::vector<Scalar> symbolicPoint(const SymbolicPiece& piece, std::string_view name);
  CurvePoint symbolicLineRegionPoint(const SymbolicPiece& piece, Scalar local);
  CurvePoint symbolicPointAt(const SymbolicPiece& piece, const frontend::CurveValue& value,
                             Scalar local);
  // The parameter range the piece's loop runs over: t0 .. t1 of an analytic
  // curve, 0 .. 1 for a line or an arc.
  std::pair<Scalar, Scalar> symbolicRange(const SymbolicPiece& piece);
  // The two ends of a range written out (`a .. b`) as the controller computes them.
  std::pair<Scalar, Scalar> symbolicBounds(const frontend::Expr& range, const SymbolicPiece& piece,
                                           std::string_view what);
  // An arc's heights at its start and end (z = a .. b; 0 and 0 without).
  std::pair<Scalar, Scalar> symbolicHeights(const SymbolicPiece& piece,
                                            const frontend::CurveValue& value);
  Scalar times(Scalar left, Scalar right);
  Scalar magnitude(Scalar value);

  // curvature_bounds.cpp
  // The controller's step count for a dependent line, arc, polar or param
  // piece, from a bound of |C''| over its range; nullopt when the piece's
  // expressions are beyond the bounds this version derives.
  // round(steps + 0.5): at least ceil(steps), and 1 for no steps; one
  // inline ROUND on the controller.
  Scalar roundedUpSteps(Scalar steps);
  std::optional<Scalar> symbolicStepCount(const SymbolicPiece& piece,
                                          const frontend::CurveValue& value, double budget);
  std::optional<Scalar> analyticCurvatureBound(const SymbolicPiece& piece,
                                               const frontend::CurveValue& value);
  CurvePoint splitSpanPoint(const ControllerSegment& segment, Scalar u);
  // A NURBS segment's point at its span's u, moved by its transform.
  CurvePoint nurbsSegmentPoint(const CutCurve& curve, const ControllerSegment& segment, Scalar u,
                               const frontend::CutStmt& cut);

  const frontend::CheckedProgram& program_;
  const frontend::PartItem& part_;
  // The program's diagnostics, or a buffer while a controller loop or
  // branch is tried.
  frontend::DiagnosticEngine* diagnostics_;
  const LoweringOptions& options_;
  // Diagnostics of speculative evaluations (their failures are handled here).
  frontend::DiagnosticEngine scratch_{0};
  RenewingEvaluator evaluator_;
  FunctionBuilder builder_;
  Arithmetic arithmetic_{builder_, options_.literalSignificantDigits > 0};
  Bindings bindings_;
  frontend::Environment environment_;
  std::optional<Scalar> feed_;
  std::optional<Scalar> safe_;
  // The current tool's diameter= (null before the first tool).
  const frontend::Expr* toolDiameter_ = nullptr;
  // The current tool's radius offset register (radius=, default its number).
  std::uint32_t radiusRegister_ = 0;
  MachineSettings machine_;
  // Set by an attempt that a loop's trip changing modes ended (attempt()).
  std::optional<MachineSettings> modesAtLoopHead_;
  std::vector<CutGeometry> cuts_;
  std::size_t unrolledIterations_ = 0;
  // The parameters each parameter or let declaration reads, and each let's
  // value (for the transforms of a named curve).
  std::map<const frontend::Declaration*, std::set<std::string>> parameterNames_;
  std::map<const frontend::Declaration*, const frontend::Expr*> letValues_;
  std::vector<FixedParameter> fixedParameters_;
  // Set while the defaults are only checked, not built into the program.
  bool checkingDefaults_ = false;
  std::optional<RuntimeOffset> runtimeOffset_;
  // What the cut being lowered asks its level laps for (arcsAskedBy).
  std::optional<ArcsAsked> arcsAsked_;
  bool nativeArcs_ = false; // the cut being lowered prints its arcs as arcs
  // The cut being lowered is chords choose-controller-steps cuts in steps:
  // its counts are bounded there, not by an estimate of its chords; and
  // whether it cuts each of its pieces in one step.
  bool stepsLeftToTheLegalisation_ = false;
  bool singleStepsLeftToTheLegalisation_ = false;
  // The curve table entries of such cuts cut in single steps: their laps
  // print no loop (runtime_control.cpp's nesting).
  std::set<std::uint32_t> singleStepCurves_;
};

// Small helpers shared by the files.
const frontend::Modifier* findModifier(const frontend::CutStmt& cut, std::string_view name);
const frontend::Expr* modifierValue(const frontend::CutStmt& cut, std::string_view name);
std::string wordOf(const frontend::Expr& expression);
// The cut's method= word, empty without one.
std::string methodOf(const frontend::CutStmt& cut);
// A knot span without the rounding noise of the conversion: a weight that is
// constant makes the span polynomial (its coordinates divided by it).
geom::PolynomialSpan cleanedSpan(geom::PolynomialSpan span);

} // namespace cncc::ir::lowering
