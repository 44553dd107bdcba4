// The part and its statements. Control flow is decided here, at compile
// time, from the values the host backends run with: a `for` is unrolled
// with its variable a constant in each copy, an `if` lowers only the branch
// its condition chooses. For controllers that run loops themselves, a `for`
// or `if` over parameters is tried as a controller loop or branch first
// (runtime_control.cpp).
#include "part_lowering.h"

#include <fmt/format.h>

#include <algorithm>

namespace cncc::ir::lowering {

using namespace frontend;

namespace {

// Bounds on what unrolling may produce, so that a loop of a billion
// iterations is a diagnostic rather than an exhausted machine.
constexpr std::size_t maximumUnrolledIterations = 100'000;

} // namespace

PartLowering::PartLowering(const CheckedProgram& program, const PartItem& part,
                           DiagnosticEngine& diagnostics, const LoweringOptions& options)
    : program_(program), part_(part), diagnostics_(&diagnostics), options_(options),
      evaluator_(program, scratch_), builder_(std::string(part.name)) {}

LoweredPart PartLowering::run() {
  // What no statement makes (the parameters, the set-up before the first
  // statement and at the end) comes from the part itself.
  builder_.setSpan(part_.nameSpan);
  lowerParameters();
  lowerBlock(part_.body);
  endMachineSettings();
  Function function = builder_.finish();
  for (const FixedParameter& fixed : fixedParameters_) {
    for (ir::Parameter& parameter : function.parameters) {
      parameter.fixed = parameter.fixed || parameter.name == fixed.name;
    }
  }
  function.cuts = std::move(cuts_);
  return {std::move(function), std::move(fixedParameters_)};
}

void PartLowering::unsupported(SourceSpan span, std::string_view what) {
  fail(span, fmt::format("{} is not supported by this version's lowering", what));
}

void PartLowering::fail(SourceSpan span, std::string message, DiagnosticKind kind) {
  diagnostics_->report(kind, span, std::move(message));
  throw LoweringFailed{};
}

void PartLowering::checkSize(SourceSpan span) {
  if (isTooLarge(builder_.function())) {
    fail(span, functionTooLargeMessage(), DiagnosticKind::ProgramTooLarge);
  }
}

void PartLowering::lowerParameters() {
  for (const frontend::Parameter& parameter : part_.parameters) {
    if (parameter.declaration == nullptr || !parameter.declaration->value ||
        parameter.declaration->value->type.kind != TypeKind::Num) {
      unsupported(parameter.nameSpan, "a parameter without a numeric value");
    }
    double value = parameter.declaration->value->number;
    std::uint32_t index = builder_.addParameter(std::string(parameter.name), value);
    bindings_[parameter.declaration] = {TypeKind::Num,
                                        {Scalar::of(builder_.parameter(index), ValueType::F64)}};
    environment_[parameter.declaration] = Value::ofNumber(value);
    parameterNames_[parameter.declaration] = {std::string(parameter.name)};
  }
}

void PartLowering::lowerBlock(const Block& block) {
  for (const StmtPtr& statement : block.statements) {
    lowerStatement(*statement);
    checkSize(statement->span);
  }
}

void PartLowering::lowerStatement(const Stmt& statement) {
  SpanScope span(builder_, statement.span);
  switch (statement.kind) {
  case StmtKind::Units:
    return; // partUnits() reads it; the IR's numbers are in the part's units
  case StmtKind::Tool:
    return lowerTool(as<ToolStmt>(statement));
  case StmtKind::Feed:
    feed_ = feedRate(*as<ValueStmt>(statement).value);
    return;
  case StmtKind::Spindle:
    builder_.spindle(arithmetic_.value(spindleSpeed(*as<ValueStmt>(statement).value)));
    return;
  case StmtKind::Safe:
    for (const Argument& setting : as<SafeStmt>(statement).settings) {
      if (setting.name == "z") {
        safe_ = number(*setting.value);
      }
    }
    return;
  case StmtKind::Origin:
    return lowerOrigin(as<OriginStmt>(statement));
  case StmtKind::Coolant:
    return lowerCoolant(as<CoolantStmt>(statement));
  case StmtKind::Let:
    return lowerLet(as<LetStmt>(statement));
  case StmtKind::Cut:
    return lowerCut(as<CutStmt>(statement));
  case StmtKind::For:
    return lowerFor(as<ForStmt>(statement));
  case StmtKind::If:
    return lowerIf(as<IfStmt>(statement));
  case StmtKind::Error:
    fail(statement.span, "cannot lower a statement that did not parse");
  }
}

void PartLowering::ensureOrigin() {
  if (!machine_.originChosen) {
    builder_.origin(54);
    machine_.originChosen = true;
  }
}

Scalar PartLowering::feedRate(const Expr& expression) {
  bool inches = partUnits(part_) == PartUnits::Inches;
  std::string_view unit = inches ? "inch/min" : "mm/min";
  Scalar feed =
      withinMachineLimit(expression, options_.maximumFeed / (inches ? 25.4 : 1.0), "feed", unit);
  Value atDefaults = evaluate(expression, environment_);
  if (atDefaults.type.kind == TypeKind::Num && !(atDefaults.number <= largestNumberInUnits())) {
    fail(expression.span,
         fmt::format("the feed {:g} {} is beyond this target's number range of {} {}",
                     atDefaults.number, unit, largestNumberInUnits(), unit),
         DiagnosticKind::CoordinateRange);
  }
  return feed;
}

Scalar PartLowering::spindleSpeed(const Expr& expression) {
  return withinMachineLimit(expression, options_.maximumSpindleSpeed, "spindle speed", "rpm");
}

Scalar PartLowering::withinMachineLimit(const Expr& expression, double limit, std::string_view what,
                                        std::string_view unit) {
  Scalar value = number(expression);
  if (limit > 0) {
    Value atDefaults = evaluate(expression, environment_);
    if (atDefaults.type.kind == TypeKind::Num && atDefaults.number > limit) {
      fail(expression.span,
           fmt::format("the {} {:g} {} is over this machine's maximum of {:g} {}", what,
                       atDefaults.number, unit, limit, unit),
           DiagnosticKind::MachineLimit);
    }
  }
  return value;
}

void PartLowering::lowerOrigin(const OriginStmt& origin) {
  if (origin.extended != 0) {
    if (origin.extended > options_.maximumExtendedWorkOffset) {
      fail(origin.extendedSpan,
           options_.maximumExtendedWorkOffset == 0
               ? std::string("this target's machine has no extended work offsets (G54.1 P..)")
               : fmt::format("this target's machine has extended work offsets P1 .. P{}",
                             options_.maximumExtendedWorkOffset),
           DiagnosticKind::MachineCapability);
    }
    builder_.origin(54.1, static_cast<std::uint32_t>(origin.extended));
  } else {
    builder_.origin(origin.group);
  }
  machine_.originChosen = true;
}

void PartLowering::lowerCoolant(const CoolantStmt& coolant) {
  if (coolant.mode == frontend::CoolantMode::Through && !options_.throughSpindleCoolant) {
    fail(coolant.modeSpan,
         "this target's machine has no code for through-spindle coolant (it differs from "
         "machine to machine)",
         DiagnosticKind::MachineCapability);
  }
  static_assert(static_cast<int>(frontend::CoolantMode::Through) ==
                static_cast<int>(ir::CoolantMode::Through));
  auto mode = static_cast<ir::CoolantMode>(static_cast<std::uint32_t>(coolant.mode));
  ensureOrigin();
  builder_.coolant(mode);
  machine_.coolant = mode;
}

void PartLowering::activateLengthOffset() {
  if (machine_.lengthOffsetPending && safe_) {
    // Z alone: X and Y are where the tool change left them.
    builder_.climb(arithmetic_.value(*safe_));
    machine_.lengthOffsetPending = false;
  }
}

void PartLowering::endMachineSettings() {
  if (machine_.contouring != 0.0) {
    builder_.contouring(0);
  }
  if (machine_.coolant != ir::CoolantMode::Off) {
    builder_.coolant(ir::CoolantMode::Off);
  }
  builder_.home();
}

void PartLowering::lowerTool(const ToolStmt& tool) {
  ensureOrigin();
  if (machine_.contouring != 0.0) { // the new tool's cuts choose their own
    builder_.contouring(0);
    machine_.contouring = 0.0;
  }
  double toolNumber = constantNumber(*tool.number, "the tool number");
  Scalar diameter = Scalar::of(0);
  std::optional<Scalar> spindle;
  std::uint32_t lengthRegister = 0;
  radiusRegister_ = static_cast<std::uint32_t>(toolNumber);
  for (const Argument& setting : tool.settings) {
    if (setting.name == "radius") {
      radiusRegister_ =
          static_cast<std::uint32_t>(constantNumber(*setting.value, "the radius offset register"));
    } else if (setting.name == "length") {
      lengthRegister =
          static_cast<std::uint32_t>(constantNumber(*setting.value, "the length offset register"));
    } else if (setting.name == "diameter") {
      diameter = number(*setting.value);
      toolDiameter_ = setting.value.get();
    } else if (setting.name == "spindle") {
      spindle = spindleSpeed(*setting.value);
    } else if (setting.name == "feed") {
      feed_ = feedRate(*setting.value);
    }
  }
  builder_.tool(toolNumber, arithmetic_.value(diameter), lengthRegister);
  machine_.lengthOffsetPending = true;
  if (spindle) {
    builder_.spindle(arithmetic_.value(*spindle));
  }
}

void PartLowering::lowerLet(const LetStmt& let) {
  Value value = evaluate(*let.value, environment_);
  if (let.declaration == nullptr || value.isError()) {
    fail(let.value->span, "cannot evaluate this value for lowering");
  }
  environment_[let.declaration] = value;
  bindings_.erase(let.declaration); // a let in a loop body: the previous copy's
  letValues_[let.declaration] = let.value.get();
  if (std::set<std::string> parameters = parametersOf(*let.value); !parameters.empty()) {
    parameterNames_[let.declaration] = std::move(parameters);
  } else {
    parameterNames_.erase(let.declaration);
  }
  TypeKind kind = value.type.kind;
  if (kind == TypeKind::Num || kind == TypeKind::Bool || kind == TypeKind::Point) {
    std::optional<Lowered> lowered = tryLower(*let.value, bindings_, environment_);
    // A let that folded to a constant stays in the environment only.
    if (lowered) {
      bool constant = true;
      for (const Scalar& scalar : lowered->values) {
        constant = constant && scalar.isConstant();
      }
      if (!constant) {
        bindings_[let.declaration] = *lowered;
      }
    }
  }
}

void PartLowering::lowerFor(const ForStmt& loop) {
  if (lowerControllerFor(loop)) {
    return;
  }
  Value range = evaluate(*loop.range, environment_);
  fixParameters(*loop.range, loop.range->span, "this loop bound");
  if (range.type.kind != TypeKind::Range || loop.declaration == nullptr) {
    fail(loop.range->span, "cannot evaluate this range for lowering");
  }
  if (range.low != std::floor(range.low) || range.high != std::floor(range.high)) {
    fail(loop.range->span, "a loop's bounds must be whole numbers", DiagnosticKind::NotInteger);
  }
  auto tooLarge = [&] {
    fail(loop.span,
         fmt::format("the part's loops run more than {} times in all; it is too large to "
                     "compile",
                     maximumUnrolledIterations),
         DiagnosticKind::ProgramTooLarge);
  };
  // Refused before the first iteration when the count alone is too large:
  // each iteration may lower a whole cut.
  double count = std::max(0.0, range.high - range.low + 1);
  if (!(count + static_cast<double>(unrolledIterations_) <=
        static_cast<double>(maximumUnrolledIterations))) {
    tooLarge();
  }
  // Inclusive of both ends, step 1; none when high < low.
  for (double i = range.low; i <= range.high; ++i) {
    if (++unrolledIterations_ > maximumUnrolledIterations) {
      tooLarge();
    }
    environment_[loop.declaration] = Value::ofNumber(i);
    lowerBlock(loop.body);
  }
}

void PartLowering::lowerIf(const IfStmt& conditional) {
  if (lowerControllerIf(conditional)) {
    return;
  }
  Value condition = evaluate(*conditional.condition, environment_);
  fixParameters(*conditional.condition, conditional.condition->span, "this condition");
  if (condition.type.kind != TypeKind::Bool) {
    fail(conditional.condition->span, "cannot evaluate this condition for lowering");
  }
  // `else if` is an else block holding one if statement.
  lowerBlock(condition.boolean ? conditional.thenBlock : conditional.elseBlock);
}

} // namespace cncc::ir::lowering
