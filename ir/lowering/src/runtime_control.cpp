// `for` and `if` when the bounds or the condition depend on part
// parameters: the loop and the branches a controller runs (a WHILE over the
// range and an IF over the branches, so that the operator's edit reaches
// the part), on every target (LoweringOptions::controllerLoops, or
// keepLoops on the host's, whose legalisation unroll-host-control writes
// them out).
//
// The body is lowered once with the loop variable an IR value (and, for
// the compile-time checks and the planning that needs numbers, its first
// value). Where something in the body needs the variable as a number at
// compile time (the points of a curve built from it that the controller
// cannot compute, a tolerance, a tool number), NeedsUnrolling abandons the
// attempt: the lowering goes back to its state before the loop and unrolls
// it, fixing what the bounds read, as the references do. A branch is
// likewise tried and, when either branch cannot be lowered, chosen at
// compile time. Diagnostics of an attempt are held until it succeeds.
#include "part_lowering.h"

#include <algorithm>

#include <fmt/format.h>

#include <cmath>
#include <functional>

namespace cncc::ir::lowering {

using namespace frontend;

struct LoweringState {
  FunctionBuilder builder;
  Bindings bindings;
  Environment environment;
  std::optional<Scalar> feed, safe;
  MachineSettings machine;
  std::vector<CutGeometry> cuts;
  std::size_t unrolledIterations = 0;
  std::map<const Declaration*, std::set<std::string>> parameterNames;
  std::map<const Declaration*, const Expr*> letValues;
  std::vector<FixedParameter> fixedParameters;
  DiagnosticEngine* diagnostics = nullptr;
  DiagnosticEngine held{0};
};

namespace {

constexpr std::string_view markerPrefix = "for-variable ";

// Whether the instruction is a loop in the printed program: a loop, or a
// curve.lap, which its legalisation writes out as loops (one deep), unless
// it is cut in single steps (its entry's, or chords choose-controller-steps
// cuts so: `singleSteps`).
bool printsAsLoop(const Function& function, const Instruction& instruction,
                  const std::set<std::uint32_t>& singleSteps) {
  if (instruction.opcode != Opcode::CurveLap) {
    return instruction.opcode == Opcode::Loop;
  }
  if (singleSteps.contains(instruction.index)) {
    return false;
  }
  const CurveTableEntry& entry = function.curves[instruction.index];
  return entry.sampling != CurveSampling::Steps ||
         std::any_of(entry.regionSteps.begin(), entry.regionSteps.end(),
                     [](int steps) { return steps != 1; });
}

int loopNesting(const Function& function, const Region& region,
                const std::set<std::uint32_t>& singleSteps) {
  int deepest = 0;
  for (InstructionId id : region.instructions) {
    const Instruction& instruction = function.instructions[id];
    for (const Region& inner : instruction.regions) {
      int own = loopNesting(function, inner, singleSteps) +
                (printsAsLoop(function, instruction, singleSteps) ? 1 : 0);
      deepest = std::max(deepest, own);
    }
  }
  return deepest;
}

void replay(const DiagnosticEngine& from, DiagnosticEngine& to) {
  for (const Diagnostic& diagnostic : from.diagnostics()) {
    Diagnostic* copy = to.report(diagnostic.kind, diagnostic.span, diagnostic.message);
    for (const DiagnosticNote& note : diagnostic.notes) {
      if (copy != nullptr) {
        to.addNote(copy, note.span, note.message);
      }
    }
  }
}

} // namespace

std::string PartLowering::loopVariableMarker(const Declaration* declaration) {
  return fmt::format("{}{}@{}", markerPrefix, declaration->name,
                     static_cast<const void*>(declaration));
}

bool PartLowering::isLoopVariableMarker(std::string_view name) {
  return name.starts_with(markerPrefix);
}

LoweringState PartLowering::saveState() {
  return {builder_,         bindings_,   environment_,        feed_,           safe_,
          machine_,         cuts_,       unrolledIterations_, parameterNames_, letValues_,
          fixedParameters_, diagnostics_};
}

void PartLowering::restoreState(LoweringState& state) {
  builder_ = std::move(state.builder);
  bindings_ = std::move(state.bindings);
  environment_ = std::move(state.environment);
  feed_ = state.feed;
  safe_ = state.safe;
  machine_ = state.machine;
  cuts_ = std::move(state.cuts);
  unrolledIterations_ = state.unrolledIterations;
  parameterNames_ = std::move(state.parameterNames);
  letValues_ = std::move(state.letValues);
  fixedParameters_ = std::move(state.fixedParameters);
  diagnostics_ = state.diagnostics;
  // The entries the attempt added are gone, and so are its marks.
  auto kept = static_cast<std::uint32_t>(builder_.function().curves.size());
  singleStepCurves_.erase(singleStepCurves_.lower_bound(kept), singleStepCurves_.end());
}

// Runs `lowering` as an attempt: its diagnostics are held, and when it
// throws NeedsUnrolling or LoweringFailed (an error the unrolled or
// compile-time lowering reports for the values really taken), the lowering
// goes back to where it was and the attempt returns false.
bool PartLowering::attempt(const std::function<void(LoweringState&)>& lowering) {
  LoweringState state = saveState();
  diagnostics_ = &state.held;
  try {
    lowering(state);
  } catch (const NeedsUnrolling&) {
    restoreState(state);
    return false;
  } catch (const LoweringFailed&) {
    restoreState(state);
    return false;
  } catch (const TripChangesModes& changed) {
    restoreState(state);
    modesAtLoopHead_ = changed.atHead;
    return false;
  }
  diagnostics_ = state.diagnostics;
  replay(state.held, *diagnostics_);
  return true;
}

bool PartLowering::lowerControllerFor(const ForStmt& loop) {
  if (!(options_.controllerLoops || options_.keepLoops) || checkingDefaults_ ||
      loop.declaration == nullptr || loop.range->kind != ExprKind::Range ||
      parametersOf(*loop.range).empty()) {
    return false;
  }
  const auto& range = as<RangeExpr>(*loop.range);
  Value defaults = evaluate(*loop.range, environment_);
  if (defaults.type.kind != TypeKind::Range || defaults.low != std::floor(defaults.low) ||
      defaults.high != std::floor(defaults.high)) {
    return false; // the unrolling reports it
  }
  ensureOrigin(); // before the loop, which may run no times
  activateLengthOffset();
  // The body is lowered for the modes in force when each trip starts: those
  // before the loop that a trip leaves as it found them. Where a trip
  // changes one, the body is lowered again: for the contouring a trip ends
  // in, set before the loop (a trip's cuts then set only what differs, as
  // a programmer sets G05 P10000 once before the WHILE), and for the coolant
  // unknown (a second trip starts with the first's).
  for (int round = 0;; ++round) {
    MachineSettings atHead = machine_;
    bool lowered = attempt([&](LoweringState&) {
      Scalar low = number(*range.low);
      Scalar high = number(*range.high);
      ValueId variable = builder_.beginLoop(arithmetic_.value(low), arithmetic_.value(high));
      bindings_[loop.declaration] = {TypeKind::Num, {Scalar::of(variable, ValueType::F64)}};
      environment_[loop.declaration] = Value::ofNumber(defaults.low);
      parameterNames_[loop.declaration] = {loopVariableMarker(loop.declaration)};
      lowerBlock(loop.body);
      builder_.endLoop();
      if (!machine_.sameModes(atHead) && round == 0) {
        std::optional<double> endsIn = machine_.contouring;
        atHead.keepModesAgreedWith(machine_);
        atHead.contouring = endsIn;
        throw TripChangesModes{atHead};
      }
      machine_.keepModesAgreedWith(atHead); // after no trip, or after some
      if (options_.maximumLoopNesting > 0 &&
          loopNesting(builder_.function(), builder_.function().body, singleStepCurves_) >
              options_.maximumLoopNesting) {
        throw NeedsUnrolling{};
      }
    });
    if (lowered) {
      bindings_.erase(loop.declaration);
      return true;
    }
    if (!modesAtLoopHead_) {
      return false;
    }
    if (modesAtLoopHead_->contouring && machine_.contouring != modesAtLoopHead_->contouring) {
      builder_.contouring(*modesAtLoopHead_->contouring);
    }
    machine_ = *modesAtLoopHead_;
    modesAtLoopHead_.reset();
  }
}

bool PartLowering::lowerControllerIf(const IfStmt& conditional) {
  if (!(options_.controllerLoops || options_.keepLoops) || checkingDefaults_ ||
      parametersOf(*conditional.condition).empty()) {
    return false;
  }
  std::optional<Lowered> condition = tryLower(*conditional.condition, bindings_, environment_);
  if (!condition || condition->kind != TypeKind::Bool || condition->values.front().isConstant()) {
    return false;
  }
  ensureOrigin();
  activateLengthOffset();
  return attempt([&](LoweringState& before) {
    Scalar test = condition->values.front();
    builder_.beginIf(arithmetic_.value(test));
    MachineSettings atEntry = machine_;
    lowerBlock(conditional.thenBlock);
    std::optional<Scalar> thenFeed = feed_, thenSafe = safe_;
    MachineSettings afterThen = machine_;
    feed_ = before.feed;
    safe_ = before.safe;
    machine_ = atEntry; // the else branch starts where the then branch did
    builder_.beginElse();
    lowerBlock(conditional.elseBlock);
    builder_.endIf();
    machine_.keepModesAgreedWith(afterThen);
    // A length offset one branch activated may be pending after the other.
    machine_.lengthOffsetPending = machine_.lengthOffsetPending || afterThen.lengthOffsetPending;
    // A feed or safe height set in a branch holds after the if: chosen by
    // the condition when both are numbers, else the branch is decided here.
    auto merged = [&](const std::optional<Scalar>& fromThen,
                      const std::optional<Scalar>& fromElse) -> std::optional<Scalar> {
      bool same = fromThen.has_value() == fromElse.has_value() &&
                  (!fromThen || (fromThen->isConstant() && fromElse->isConstant()
                                     ? fromThen->constant == fromElse->constant
                                     : fromThen->value == fromElse->value));
      if (same) {
        return fromThen;
      }
      if (!fromThen || !fromElse || !fromThen->isConstant() || !fromElse->isConstant()) {
        throw NeedsUnrolling{};
      }
      return arithmetic_.select(test, *fromThen, *fromElse);
    };
    feed_ = merged(thenFeed, feed_);
    safe_ = merged(thenSafe, safe_);
  });
}

} // namespace cncc::ir::lowering
