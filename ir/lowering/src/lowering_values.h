// The values the lowering computes with: scalars that are constants or IR
// values, lowered CDL values, a cut's curve and its pieces, the runs of its
// samples, an arc piece as native arcs move on it.
#pragma once

#include "affine.h"

#include "cncc/frontend/sema.h"
#include "cncc/frontend/value.h"
#include "cncc/geom/curve.h"
#include "cncc/geom/evaluation_budget.h"
#include "cncc/geom/polynomial_span.h"
#include "cncc/ir/builder.h"
#include "cncc/ir/curve_lap.h"
#include "cncc/ir/curve_lap_offset_steps.h"
#include "cncc/ir/curve_lap_steps.h"

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <vector>

namespace cncc::ir::lowering {

// A number or bool of the lowering: a constant not yet written to the IR
// (`value` invalid), or an IR value. Constants are written where they are
// used, so arithmetic on them folds without leaving dead instructions.
struct Scalar {
  ValueId value;
  double constant = 0;
  ValueType type = ValueType::F64;

  static Scalar of(double number) { return {ValueId{}, number, ValueType::F64}; }
  static Scalar ofBool(bool yes) { return {ValueId{}, yes ? 1.0 : 0.0, ValueType::Bool}; }
  static Scalar of(ValueId id, ValueType type) { return {id, 0, type}; }
  bool isConstant() const { return !value.valid(); }
  // The same constant, or the same IR value.
  bool sameAs(const Scalar& other) const {
    return isConstant() ? other.isConstant() && other.constant == constant : other.value == value;
  }
};

// A lowered CDL value: a num or bool (one scalar) or a point (three).
struct Lowered {
  frontend::TypeKind kind = frontend::TypeKind::Num;
  std::vector<Scalar> values;
};

using Bindings = std::map<const frontend::Declaration*, Lowered>;

// Thrown to abandon the lowering after its diagnostic has been reported.
struct LoweringFailed {};

// Thrown where a controller loop's body would need its variable as a
// compile-time number: the loop is unrolled instead.
struct NeedsUnrolling {};

// A point of a curve.
struct CurvePoint {
  Scalar x, y, z;
};

// What a region of a curve.lap computes: its point, and for a region cut as
// an arc of a circle the offset from the point to the centre (z: 0), for a
// walked region the step to the next point.
struct LapRegionPoint {
  LapRegionPoint(CurvePoint at) : point(at) {} // NOLINT: a point is a region's point
  LapRegionPoint(CurvePoint at, CurvePoint centre) : point(at), toCentre(centre) {}
  CurvePoint point;
  std::optional<CurvePoint> toCentre;
  // A walked region's: the step from the parameter to the next point.
  std::optional<Scalar> walkStep = std::nullopt;
};

// One smooth piece of a cut's curve: a line, an arc, a polar or param
// curve, or a NURBS (then split into polynomial spans), with the transform
// that the enclosing translate/rotate/scale calls make.
struct CurvePiece {
  std::shared_ptr<const frontend::CurveValue> value;
  // The piece before its transform, in its own parameter.
  std::shared_ptr<const geom::Curve> geometry;
  std::vector<geom::PolynomialSpan> spans; // NURBS only
  Affine transform;
};

// A cut's curve: its pieces in order, and the whole of it as one geom curve
// (transforms applied; a path's pieces joined) whose parameter the samples
// use.
struct BesideCurve;
struct CutCurve {
  std::vector<CurvePiece> pieces;
  std::shared_ptr<const geom::Curve> geometry;
  // Where each piece starts in the whole curve's parameter, and the end.
  std::vector<double> pieceStarts;
  // A curve beside the cut's (an offset, `geometry`, without pieces of its
  // own): how its laps compute it from the drawn curve (offset_laps.cpp).
  std::shared_ptr<const BesideCurve> beside = nullptr;
};

// Where a sample of the whole curve lies: its piece, the NURBS span in the
// piece (0 otherwise) and the parameter that piece's IR evaluates at (the
// span's u in [0, 1], or the piece's own t).
struct SampleLocation {
  std::size_t piece = 0;
  std::size_t span = 0;
  double local = 0;
};

// The points a search over a cut's curve (the chord walk, a spline fit) may
// ask of it (curve_lap.h): a few seconds of a curve the front end evaluates.
using ir::maximumCurveEvaluations;
// The points the searches for the fewest uniform steps of a controller
// cut's pieces may ask of its curve, over the cut (curve_lap_steps.h).
using ir::maximumStepSearchEvaluations;
// The points the checks of a controller offset's step counts may ask of
// the exact offsets, over one cut (curve_lap_offset_steps.h).
using geom::EvaluationsCharged;
using ir::maximumOffsetStepEvaluations;

// How far apart the pieces of a path may end and start (curve_lap.h).
using ir::pathJoinTolerance;

// An arc piece as native_arcs.cpp moves on it: its point at a fraction (0
// to 1) of the piece, transformed, the helix's own z included; the way from
// there to its centre; and the angle it turns (to - from: counter-clockwise
// when positive).
struct ArcPath {
  std::function<CurvePoint(Scalar fraction)> pointAt;
  // From the point at a fraction to the centre, transformed (z: 0).
  std::function<CurvePoint(Scalar fraction)> toCentre;
  // A constant arc's own parameter, 0 to its length (as its lap region's),
  // which the loop of its blocks steps (emitArcBlocks), one literal a step:
  // the same two at a parameter. 0 (and none) for an arc the program
  // computes, whose blocks are a lap region's (controller_cuts.cpp).
  double parameterLength = 0;
  std::function<CurvePoint(Scalar parameter)> pointAtParameter;
  std::function<CurvePoint(Scalar parameter)> toCentreAtParameter;
  Scalar sweep;
  // The radius the controller moves on, transformed (a constant when known).
  Scalar radius;
  // The direction it turns with the part's defaults (the sweep's sign).
  bool turnsCounterClockwise = true;
};
// An arc's move.arc blocks: how many (a number, or what the program
// computes), which way they turn, whether each is a whole turn.
struct ArcBlocks {
  Scalar count;
  bool counterClockwise = true;
  bool wholeTurns = false;
};
// The height added to an arc's own z at a fraction of it (the pass, a ramp).
using ArcHeight = std::function<Scalar(Scalar fraction)>;

// An arc in numbers, in its length's parameter.
struct ArcNumbers {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius = 0;
  double startAngle = 0;
  double turnPerLength = 0;
  double startZ = 0;
  double climbPerLength = 0;
};

// A region of a lap beside the curve whose offset the host computes
// (offset_laps.cpp): its piece of the offset, and unless that is a line or
// an arc the drawn piece whose offset it is (the knot span and the share of
// it, u = spanFrom + spanShare t).
struct HostBesideRegion {
  const geom::Curve* part = nullptr;
  std::optional<std::size_t> drawn;
  std::size_t span = 0;
  double spanFrom = 0;
  double spanShare = 1;
};

// The offset the host computes as the laps compute it (offset_laps.cpp):
// its pieces laid out in the curve table (`layout`, its points not yet
// chosen: geometry the offset), the region of each, the drawn curve they
// compute from and the distance (left positive).
struct BesideCurve {
  CurveTableEntry layout;
  std::vector<HostBesideRegion> regions;
  CutCurve drawn;
  double distance = 0;
};

// A region of a lap beside the curve whose offset the controller computes
// (controller_offset_laps.cpp): a segment's offset, or the arc about the
// convex corner of a join.
struct BesideRegion {
  std::optional<std::size_t> segment;
  std::size_t join = 0;
};

// A pass's height in a cut's sweep, and the one above it (where a ramp lap
// starts); `loop`: in a pass loop (else the one pass of a cut without one).
struct SweepHeights {
  Scalar z;
  Scalar previous;
  bool loop = false;
};

// Where a cut's passes start (the rapid over the start at the safe height),
// and whether that rapid is the first Z move after a tool change: then it
// comes before a pass loop the program computes, which may run no times.
struct SweepStart {
  ValueId x;
  ValueId y;
  ValueId safe;
  bool activatesLengthOffset = false;
  Scalar z = Scalar::of(0); // of the curve's start, above the pass's height
};

// A smooth segment of a cut's curve (a piece, or a knot span of a NURBS
// piece): a ramp lap descends along each segment in proportion to the
// segment's own parameter, each taking a share of the descent in
// proportion to its length (`before` and `share` as fractions of the
// curve's length).
struct RampSegment {
  std::size_t piece = 0;
  std::size_t span = 0;
  double before = 0;
  double share = 0;
};

} // namespace cncc::ir::lowering
