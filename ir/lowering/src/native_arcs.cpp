// Arcs as the controller's circular interpolation: every `arc` piece of a
// cut (alone, in a path, under translate/rotate/scale, with z = a .. b as a
// helix) becomes `move.arc` blocks, exact, with no tolerance spent. The
// transforms keep an arc an arc and its turning direction (a scale has one
// factor, so no mirror).
//
// The blocks of an arc that turns by D radians:
// - D constant and a whole number k of turns: k blocks, each ending exactly
//   where it starts (a full circle, the end written with the start's values
//   so that no rounding makes it a sliver);
// - D constant otherwise: the fewest blocks of at most 2 pi - 0.01 each (a
//   block close to a full turn would end too near its start to say which);
// - D computed on the controller (a number of turns that is a parameter):
//   half turns at most, ceil(|D| / pi) of them, in a loop the controller
//   runs, turning as the defaults turn it (values that turn it the other
//   way stop the program with an alarm, as do values that leave it no
//   radius, before the cut starts).
// A piece's own z (a helix) and the pass depth or ramp descent add up.
#include "part_lowering.h"

#include "cncc/geom/line_arc_curves.h"
#include "cncc/ir/arc_blocks.h"

#include <Eigen/LU>

#include <fmt/format.h>

#include <cmath>
#include <numbers>

namespace cncc::ir::lowering {

using namespace frontend;

namespace {

// Blocks written out one after the other; more go in a loop.
constexpr int largestUnrolledArc = 4;
// ceil(x) as round(x + offset), a whole x staying itself (see controller_cuts.cpp).
constexpr double wholeBlocksOffset = 0.49999999;

bool isArcPiece(const CurvePiece& piece) {
  return piece.value->kind == CurveKind::Arc;
}

} // namespace

bool PartLowering::wantsNativeArcs(const CutStmt& cut) {
  return modifierValue(cut, "samples") == nullptr && modifierValue(cut, "spacing") == nullptr;
}

bool PartLowering::hasArcPiece(const CutCurve& curve) {
  for (const CurvePiece& piece : curve.pieces) {
    if (isArcPiece(piece)) {
      return true;
    }
  }
  return false;
}

ArcPath PartLowering::constantArcPath(const CutCurve& curve, std::size_t piece,
                                      const CutStmt& cut) {
  const CurvePiece& own = curve.pieces[piece];
  const CurveValue& value = *own.value;
  double length = static_cast<const geom::ArcCurve&>(*own.geometry).length();
  ArcPath path;
  path.pointAt = [this, &curve, piece, &cut, length](Scalar fraction) {
    return pointAt(curve, piece, 0, arithmetic_.multiply(fraction, Scalar::of(length)), cut);
  };
  path.sweep = Scalar::of(value.endAngle - value.startAngle);
  path.turnsCounterClockwise = value.endAngle > value.startAngle;
  path.radius =
      Scalar::of(value.arcRadius * std::sqrt(std::abs(own.transform.linear.determinant())));
  auto toCentre = [this, &own, &value](Scalar sweep, Scalar fraction) {
    Affine direction = own.transform;
    direction.offset = Eigen::Vector2d::Zero();
    return transformed(direction,
                       radiusTowardsCentre(Scalar::of(value.arcRadius),
                                           Scalar::of(value.startAngle), sweep, fraction));
  };
  path.toCentre = [toCentre, sweep = path.sweep](Scalar fraction) {
    return toCentre(sweep, fraction);
  };
  path.parameterLength = length;
  path.pointAtParameter = [this, &curve, piece, &cut](Scalar parameter) {
    return pointAt(curve, piece, 0, parameter, cut);
  };
  path.toCentreAtParameter =
      [toCentre, turnPerLength = Scalar::of((value.endAngle - value.startAngle) / length)](
          Scalar parameter) { return toCentre(turnPerLength, parameter); };
  return path;
}

ArcPath PartLowering::symbolicArcPath(const SymbolicPiece& piece, const CurveValue& value) {
  auto number = [&](std::string_view name) {
    std::optional<Scalar> result =
        symbolicNumber(builtinArgument(*piece.call, name), piece.bindings, piece.environment);
    if (!result) {
      unsupported(piece.call->span, fmt::format("this arc's {} on the controller", name));
    }
    return *result;
  };
  Scalar from = number("from");
  ArcPath path;
  path.sweep = arithmetic_.binary(Opcode::Sub, number("to"), from);
  path.turnsCounterClockwise = value.endAngle > value.startAngle;
  path.pointAt = [this, &piece, &value](Scalar fraction) {
    return symbolicPointAt(piece, value, fraction);
  };
  Scalar radius = number("radius");
  path.radius = times(radius, piece.transform.norm);
  path.toCentre = [this, &piece, radius, from, sweep = path.sweep](Scalar fraction) {
    RuntimeTransform direction = piece.transform;
    direction.offset = {Scalar::of(0), Scalar::of(0)};
    return applied(direction, radiusTowardsCentre(radius, from, sweep, fraction));
  };
  return path;
}

// -r (cos a, sin a) at a = from + sweep fraction: from the arc's point to its
// centre, before the transform.
CurvePoint PartLowering::radiusTowardsCentre(Scalar radius, Scalar from, Scalar sweep,
                                             Scalar fraction) {
  Scalar angle = arithmetic_.add(from, times(sweep, fraction));
  Scalar negated = arithmetic_.unary(Opcode::Neg, radius);
  return {times(negated, arithmetic_.unary(Opcode::Cos, angle)),
          times(negated, arithmetic_.unary(Opcode::Sin, angle)), Scalar::of(0)};
}

// A full turn starts and ends where the arc starts: every one of them the
// same values, so that no rounding of a computed angle leaves a sliver.
// `from` and `to` are fractions of the arc, or with `done` (the fraction
// done at `to`) its own parameter.
void PartLowering::emitArcBlock(const ArcPath& arc, ArcTurn turn, Scalar from, Scalar to,
                                bool fullTurn, const ArcHeight& height, ValueId feed,
                                std::optional<Scalar> done) {
  const auto& pointAt = done ? arc.pointAtParameter : arc.pointAt;
  CurvePoint end = pointAt(to);
  if (fullTurn) {
    from = Scalar::of(0);
    CurvePoint start = pointAt(from);
    end.x = start.x;
    end.y = start.y;
  }
  CurvePoint centre = done ? arc.toCentreAtParameter(from) : arc.toCentre(from);
  Scalar z = arithmetic_.add(height(done.value_or(to)), end.z);
  // One emitting call a statement (README "Emitting in order").
  ValueId x = arithmetic_.value(end.x);
  ValueId y = arithmetic_.value(end.y);
  ValueId zValue = arithmetic_.value(z);
  ValueId centreX = arithmetic_.value(centre.x);
  ValueId centreY = arithmetic_.value(centre.y);
  builder_.arc(turn, x, y, zValue, centreX, centreY, feed);
}

// `count` blocks of equal turn of a constant arc (lowerHostArcCut's):
// block j from (j - 1) / count to j / count of it.
void PartLowering::emitArcBlocks(const ArcPath& arc, ArcTurn turn, Scalar count, bool fullTurns,
                                 const ArcHeight& height, ValueId feed) {
  if (count.isConstant() && count.constant <= largestUnrolledArc) {
    auto blocks = static_cast<int>(count.constant);
    for (int j = 1; j <= blocks; ++j) {
      emitArcBlock(arc, turn, Scalar::of(static_cast<double>(j - 1) / blocks),
                   Scalar::of(static_cast<double>(j) / blocks), fullTurns, height, feed);
    }
    return;
  }
  ValueId blocks = arithmetic_.value(count);
  ValueId j = builder_.beginLoop(builder_.constant(1), blocks, LoopRole::Curve);
  Scalar index = Scalar::of(j, ValueType::F64);
  // In a loop, block j ends at j (length / count) of the arc's own
  // parameter, as a lap region's arc blocks do, the fraction done j / count.
  Scalar step = arithmetic_.binary(Opcode::Div, Scalar::of(arc.parameterLength), count);
  Scalar from = arithmetic_.multiply(arithmetic_.binary(Opcode::Sub, index, Scalar::of(1)), step);
  Scalar to = arithmetic_.multiply(index, step);
  Scalar done = arithmetic_.binary(Opcode::Div, index, count);
  emitArcBlock(arc, turn, from, to, fullTurns, height, feed, done);
  builder_.endLoop();
}

// What the program computes of an arc is checked before the cut starts: a
// radius the values leave none of, or a turn the other way than the
// defaults', stops it with an alarm, as the controller would alarm at the
// arc (or cut it mirrored).
void PartLowering::alarmWhen(Scalar condition, std::string message) {
  builder_.beginIf(arithmetic_.value(condition));
  builder_.alarm(std::move(message));
  builder_.endIf();
}

void PartLowering::guardArc(const ArcPath& arc) {
  if (!arc.radius.isConstant()) {
    alarmWhen(arithmetic_.binary(Opcode::Le, arc.radius, Scalar::of(0)),
              "the radius of an arc is not positive");
  }
  if (!arc.sweep.isConstant()) {
    alarmWhen(arithmetic_.binary(arc.turnsCounterClockwise ? Opcode::Lt : Opcode::Gt, arc.sweep,
                                 Scalar::of(0)),
              arc.turnsCounterClockwise ? "an arc turns clockwise, not as its defaults"
                                        : "an arc turns counter-clockwise, not as its defaults");
  }
}

// The blocks of an arc: how many, which way, whether whole turns.
ArcBlocks PartLowering::arcBlocks(const ArcPath& arc, const CutStmt& cut) {
  if (arc.sweep.isConstant()) {
    double sweep = arc.sweep.constant;
    ArcBlockCount count = arcBlockCount(sweep);
    if (!(count.blocks <= maximumArcBlocks)) {
      fail(cut.curve->span, arcTurnsPastTheLimit(count), DiagnosticKind::ProgramTooLarge);
    }
    return {Scalar::of(count.blocks), sweep > 0, count.wholeTurns};
  }
  // Half turns at most, as many as the turn the program runs with needs.
  Scalar count = arithmetic_.unary(
      Opcode::Round, arithmetic_.add(arithmetic_.binary(Opcode::Div, magnitude(arc.sweep),
                                                        Scalar::of(std::numbers::pi)),
                                     Scalar::of(wholeBlocksOffset)));
  return {count, arc.turnsCounterClockwise, false};
}

void PartLowering::emitArc(const ArcPath& arc, const ArcHeight& height, ValueId feed,
                           const CutStmt& cut) {
  ArcBlocks blocks = arcBlocks(arc, cut);
  emitArcBlocks(arc, blocks.counterClockwise ? ArcTurn::CounterClockwise : ArcTurn::Clockwise,
                blocks.count, blocks.wholeTurns, height, feed);
}

std::vector<std::optional<std::uint32_t>>
PartLowering::pieceCurveTables(const CutStmt& cut, const CutCurve& curve,
                               const std::vector<RampSegment>& shares) {
  std::vector<std::optional<std::uint32_t>> tables(curve.pieces.size());
  for (std::size_t p = 0; p < curve.pieces.size(); ++p) {
    if (!isArcPiece(curve.pieces[p])) {
      tables[p] = builder_.addCurve(pieceCurveTableEntry(cut, curve, p, shares));
    }
  }
  return tables;
}

// A cut with arc pieces (and neither samples= nor spacing=) on a target
// that computes on the host: each arc piece as move.arc, each other
// piece a curve.lap of its own, its points chosen on the piece alone
// (chord tolerance).
void PartLowering::lowerHostArcCut(const CutStmt& cut, const CutCurve& curve) {
  // Named, not structured bindings: the lambdas below capture them.
  HostCut begun = beginHostCut(cut);
  Scalar feed = begun.feed;
  bool ramp = begun.ramp;
  if (ramp) {
    checkRampCloses(curve, cut);
  }
  ToleranceBudget budget = toleranceBudget(cut);
  std::vector<RampSegment> shares = ramp ? rampSegments(curve, cut) : std::vector<RampSegment>{};

  // The other pieces' curves.
  std::vector<std::optional<std::uint32_t>> tables = pieceCurveTables(cut, curve, shares);
  ValueId feedValue = arithmetic_.value(feed);
  ValueId safeValue = arithmetic_.value(*safe_);
  bool activatesLengthOffset =
      beginCutMoves({curve.geometry, budget.tolerance, cut.span, methodOf(cut), CutArcs::Native});

  // One lap from zFrom to zTo (the descent shared by length, as cuts.cpp
  // does); a level lap's two heights are one value.
  auto lap = [&](ValueId zFrom, ValueId zTo) {
    for (std::size_t p = 0; p < curve.pieces.size(); ++p) {
      if (!isArcPiece(curve.pieces[p])) {
        emitCurveLap(curve, *tables[p], zFrom, zTo, feedValue, cut, p, p + 1);
        continue;
      }
      RampSegment segment = ramp ? rampSegmentOf(shares, p, 0) : RampSegment{p, 0, 1.0, 0.0};
      ArcHeight height = [&, segment](Scalar fraction) {
        if (zFrom == zTo) {
          // A height that is a number adds to the arc's z as a lap's does.
          const Instruction& level = builder_.function().definition(zTo);
          return level.opcode == Opcode::Const ? Scalar::of(level.number)
                                               : Scalar::of(zTo, ValueType::F64);
        }
        Scalar to = Scalar::of(zTo, ValueType::F64);
        Scalar from = Scalar::of(zFrom, ValueType::F64);
        Scalar done = arithmetic_.add(Scalar::of(segment.before),
                                      arithmetic_.multiply(Scalar::of(segment.share), fraction));
        return arithmetic_.add(
            from, arithmetic_.multiply(arithmetic_.binary(Opcode::Sub, to, from), done));
      };
      emitArc(constantArcPath(curve, p, cut), height, feedValue, cut);
    }
  };
  geom::ParameterRange domain = curve.geometry->domain();
  Eigen::Vector3d start = curve.geometry->point(domain.t0);
  Eigen::Vector3d finish = curve.geometry->point(domain.t1);
  SweepStart from{builder_.constant(start.x()), builder_.constant(start.y()), safeValue,
                  activatesLengthOffset, Scalar::of(start.z())};
  emitSweep(cut, ramp, from, {builder_.constant(finish.x()), builder_.constant(finish.y())},
            feedValue, lap);
}

} // namespace cncc::ir::lowering
