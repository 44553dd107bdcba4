// A cut's passes (`depth=D step=S`), the same loop on every target: trip
// k = 1 .. ceil(D / S) cuts at z = -min(k S, D) and starts with
// `pass.begin z`. Where D or S reads a part parameter the program computes
// the count, round(D / S + 0.49999999) (a controller's editable
// parameters; the host's interpreter runs the same IR); elsewhere they are
// numbers and so is the count. The host runs the loop as it prints (its
// trips are the passes of the source map, sweep_pass.h). A cut without
// depth= and step= is one pass at z = 0, after the comment "cut"; so is a
// sweep of one pass at its depth, where that is a number.
#include "part_lowering.h"

#include "cncc/ir/printed_grid.h"

namespace cncc::ir::lowering {

using namespace frontend;

namespace {

// ceil(depth / step) for the pass count, as round(x + offset): a ratio
// within 1e-8 above a whole number counts as that number (as passDepths'
// 1e-9 relative rule does), and the literal fits 8 significant digits.
constexpr double passCountOffset = 0.49999999;

} // namespace

bool PartLowering::readsRunTimeValues(const Expr* expression) const {
  return expression != nullptr &&
         (dependsOn(*expression, bindings_) || !parametersOf(*expression).empty());
}

SweepHeights PartLowering::beginSweep(const CutStmt& cut, bool ramp, const SweepStart& start) {
  const Expr* depthExpression = modifierValue(cut, "depth");
  const Expr* stepExpression = modifierValue(cut, "step");
  if (depthExpression == nullptr && stepExpression == nullptr) {
    builder_.comment("cut");
    return {Scalar::of(0), Scalar::of(0), false};
  }
  // Computed by the program where they read parameters, on every target
  // (the host's interpreter runs the same loop).
  bool computed = readsRunTimeValues(depthExpression) || readsRunTimeValues(stepExpression);
  // The checks (both given, 0 < step <= depth) at the defaults; fixed
  // numbers where the program does not compute them.
  checkingDefaults_ = computed;
  std::vector<double> depths = passDepths(cut); // S, 2S, .. D
  checkingDefaults_ = false;
  if (!computed && depths.size() == 1) { // one pass at the depth, no loop
    builder_.comment("cut");
    return {Scalar::of(-depths.back()), Scalar::of(0), false};
  }
  if (start.activatesLengthOffset) {
    // The first Z move after a tool change, which activates its length
    // offset, before the pass loop: where the controller runs the loop, its
    // first pass would activate it again at every pass (and a loop whose
    // count the program computes might run no times).
    builder_.rapid(start.x, start.y, start.safe);
  }
  Scalar depth = computed ? number(*depthExpression) : Scalar::of(depths.back());
  Scalar step = computed ? number(*stepExpression) : Scalar::of(depths.front());
  Scalar count =
      computed ? arithmetic_.unary(Opcode::Round,
                                   arithmetic_.add(arithmetic_.binary(Opcode::Div, depth, step),
                                                   Scalar::of(passCountOffset)))
               : Scalar::of(static_cast<double>(depths.size()));
  ValueId trips = arithmetic_.value(count);
  ValueId k = builder_.beginLoop(builder_.constant(1), trips, LoopRole::Passes);
  Scalar pass = Scalar::of(k, ValueType::F64);
  SweepHeights heights{passDepth(pass, step, depth), Scalar::of(0), true};
  if (ramp) { // from the pass above
    heights.previous = passDepth(arithmetic_.binary(Opcode::Sub, pass, Scalar::of(1)), step, depth);
  }
  builder_.passBegin(arithmetic_.value(heights.z));
  return heights;
}

void PartLowering::endSweep(const SweepHeights& sweep) {
  if (sweep.loop) {
    builder_.endLoop();
  }
}

void PartLowering::emitSweep(const CutStmt& cut, bool ramp, const SweepStart& start,
                             std::array<ValueId, 2> finish, ValueId feed, const SweepLap& lap,
                             const CompensatedLeads* leads) {
  // A lead arc at a pass's height (its arcs are in the curve's plane).
  auto leadArc = [&](const geom::ArcSegment& arc, Scalar passZ) {
    emitArcLap({arc}, planeHeight(leads->leadIn.end.z(), passZ), feed);
  };
  SweepHeights sweep = beginSweep(cut, ramp, start);
  Scalar entry = ramp ? sweep.previous : sweep.z;
  ValueId z = arithmetic_.value(sweep.z);
  builder_.rapid(start.x, start.y, start.safe);
  builder_.feed(start.x, start.y, arithmetic_.value(arithmetic_.add(entry, start.z)), feed);
  if (leads != nullptr) {
    leadArc(leads->leadIn, entry);
  }
  if (ramp) {
    PassScope rampLap(builder_, {.number = 0, .count = 0, .ramp = true});
    builder_.comment("ramp");
    lap(arithmetic_.value(entry), z);
  }
  lap(z, z);
  if (leads != nullptr) {
    leadArc(leads->leadOut, sweep.z);
  }
  builder_.rapid(finish[0], finish[1], start.safe); // the retract
  endSweep(sweep);
}

ValueId PartLowering::planeHeight(double planeZ, Scalar passZ) {
  if (passZ.isConstant()) {
    return builder_.constant(onPrintedGrid(planeZ + passZ.constant, options_.coordinateIncrement));
  }
  return arithmetic_.value(arithmetic_.add(Scalar::of(planeZ), passZ));
}

Scalar PartLowering::heightOf(ValueId z) {
  const Instruction& definition = builder_.function().definition(z);
  return definition.opcode == Opcode::Const ? Scalar::of(definition.number)
                                            : Scalar::of(z, ValueType::F64);
}

// z = -min(k step, depth) = (|k step - depth| - k step - depth) / 2, one
// expression where the controller has no min.
Scalar PartLowering::passDepth(Scalar pass, Scalar step, Scalar depth) {
  Scalar reached = arithmetic_.multiply(pass, step);
  Scalar gap = arithmetic_.unary(Opcode::Abs, arithmetic_.binary(Opcode::Sub, reached, depth));
  return arithmetic_.multiply(
      Scalar::of(0.5),
      arithmetic_.binary(Opcode::Sub, arithmetic_.binary(Opcode::Sub, gap, reached), depth));
}

} // namespace cncc::ir::lowering
