// Builds a Function instruction by instruction, with an insertion point
// that enters and leaves the regions of loops and ifs.
#pragma once

#include "cncc/ir/ir.h"

#include <utility>

namespace cncc::ir {

class FunctionBuilder {
public:
  explicit FunctionBuilder(std::string name);

  std::uint32_t addParameter(std::string name, double defaultValue);
  std::uint32_t addTable(std::vector<double> values);

  ValueId constant(double value);
  ValueId constantBool(bool value);
  ValueId parameter(std::uint32_t index);
  ValueId tableLoad(std::uint32_t table, ValueId index);
  // Any operation of fixed operands whose result type the table gives.
  ValueId operation(Opcode opcode, std::vector<ValueId> operands);
  ValueId unary(Opcode opcode, ValueId operand) { return operation(opcode, {operand}); }
  ValueId binary(Opcode opcode, ValueId left, ValueId right) {
    return operation(opcode, {left, right});
  }

  // `%i = loop %low, %high { ... }`: returns the induction variable; the
  // insertion point moves into the body until endLoop().
  ValueId beginLoop(ValueId low, ValueId high, LoopRole role = LoopRole::Statement);
  void endLoop();
  // Ends the loop being built with `loop.next %next` (its variable advances
  // to `next` while below high) and leaves it.
  void endLoopAdvancingTo(ValueId next);
  // `if %c { ... } else { ... }`: the insertion point moves into the then
  // region; beginElse() moves it to the else region; endIf() leaves.
  void beginIf(ValueId condition);
  void beginElse();
  void endIf();
  // `%t = curve.lap @curve, %zFrom, %zTo, %f { ... } piece { ... }`: returns
  // the regions' parameter; the insertion point moves into the first region.
  // Each region is ended by curvePoint(), which moves to the next region
  // and, after the last, leaves the lap.
  std::uint32_t addCurve(CurveTableEntry entry);
  ValueId beginCurveLap(std::uint32_t curve, ValueId zFrom, ValueId zTo, ValueId feedRate,
                        const std::vector<ValueId>& computedSteps = {});
  void curvePoint(ValueId x, ValueId y, ValueId z);
  // The point of a region cut as an arc, and the offset from it to the centre.
  void curveArc(ValueId x, ValueId y, ValueId z, ValueId toCentreX, ValueId toCentreY);
  // The point of a walked region, and the step from its parameter to the next.
  void curveWalk(ValueId x, ValueId y, ValueId z, ValueId step);

  void rapid(ValueId x, ValueId y, ValueId z);
  // `move.climb %z`: a rapid along Z alone, X and Y where they are.
  void climb(ValueId z);
  void feed(ValueId x, ValueId y, ValueId z, ValueId feedRate);
  // `move.arc`: to (x, y, z) about the centre at (i, j) from the current
  // position, turning `turn`; a full turn when it ends where it starts.
  void arc(ArcTurn turn, ValueId x, ValueId y, ValueId z, ValueId i, ValueId j, ValueId feedRate);
  // `move.nurbs @table, %z, %f, %weights...` (nurbs_move.h).
  void nurbs(std::uint32_t table, ValueId z, ValueId feedRate, const std::vector<ValueId>& weights);
  // `move.spline @table, %z, %f` (spline_move.h).
  void spline(std::uint32_t table, ValueId z, ValueId feedRate);
  void spindle(ValueId speed);
  // lengthRegister 0: the dialect's default register for the tool.
  void tool(double number, ValueId diameter, std::uint32_t lengthRegister = 0);
  // code 54 .. 59, or 54.1 with `extended` its P number.
  void origin(double code, std::uint32_t extended = 0);
  void coolant(CoolantMode mode);
  // tolerance 0 switches the mode off.
  void contouring(double tolerance);
  // G41 (offset > 0) or G42 (offset < 0) with radius register `offsetRegister`,
  // or G40 (offset 0, register 0).
  void compensation(double offset, std::uint32_t offsetRegister);
  // G39 at the corner where the last move ended, towards the next move's
  // start direction (dx, dy).
  void cornerArc(ValueId dx, ValueId dy);
  void home();
  void comment(std::string text);
  // `pass.begin %z`: a pass of a sweep starts at height z.
  void passBegin(ValueId z);
  // `alarm "text"`: the program stops with this message.
  void alarm(std::string text);
  // `cut.begin index`: the moves that follow belong to cut `index`.
  void cutBegin(std::uint32_t index);

  // The CDL span every instruction appended from now on comes from.
  void setSpan(frontend::SourceSpan span) { span_ = span; }
  frontend::SourceSpan span() const { return span_; }
  // The written-out sweep pass every instruction appended from now on is for.
  void setPass(SweepPass pass) { pass_ = pass; }
  SweepPass pass() const { return pass_; }

  Function finish();
  const Function& function() const { return function_; }

private:
  InstructionId append(Instruction instruction, ValueType resultType);
  Region& currentRegion();
  void endLapRegion();

  Function function_;
  // The regions being filled: (instruction, region index); empty = body.
  std::vector<std::pair<InstructionId, std::size_t>> insertion_;
  frontend::SourceSpan span_;
  SweepPass pass_;
};

// Sets the builder's span for the life of the scope (a statement being
// lowered), then puts the one before it back.
class SpanScope {
public:
  SpanScope(FunctionBuilder& builder, frontend::SourceSpan span)
      : builder_(builder), outer_(builder.span()) {
    builder_.setSpan(span);
  }
  ~SpanScope() { builder_.setSpan(outer_); }
  SpanScope(const SpanScope&) = delete;
  SpanScope& operator=(const SpanScope&) = delete;

private:
  FunctionBuilder& builder_;
  frontend::SourceSpan outer_;
};

// Sets the builder's sweep pass for the life of the scope (one pass of a
// cut written out), then puts the one before it back.
class PassScope {
public:
  PassScope(FunctionBuilder& builder, SweepPass pass) : builder_(builder), outer_(builder.pass()) {
    builder_.setPass(pass);
  }
  ~PassScope() { builder_.setPass(outer_); }
  PassScope(const PassScope&) = delete;
  PassScope& operator=(const PassScope&) = delete;

private:
  FunctionBuilder& builder_;
  SweepPass outer_;
};

} // namespace cncc::ir
