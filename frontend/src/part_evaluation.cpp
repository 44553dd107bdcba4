// Runs each part's body at compile time with its parameters at their
// defaults (or -D values), the way the machine will run it, and checks what
// only values show: feeds, tools, sweeps, tolerances, loop bounds.
#include "part_evaluation.h"

#include <cmath>
#include <fmt/format.h>

namespace cncc::frontend {

using namespace std::string_view_literals;

namespace {

// A loop runs at most this many times during checking; the checks of later
// iterations repeat the earlier ones.
constexpr double maximumCheckedIterations = 1000;
// And a part's body runs at most this many statements in all (nested loops).
constexpr std::size_t maximumCheckedStatements = 100'000;
// Below a hundredth of a micrometre no controller can follow, and the
// number of points grows without bound.
constexpr double minimumTolerance = 1e-5;
constexpr double maximumSamples = 1'000'000;
// A T word has at most 8 digits (Fanuc's longest; a machine's own limit may
// be lower).
constexpr int toolNumberDigits = 8;
constexpr double largestToolNumber = 99'999'999;
// The tool offset registers `length=` and `radius=` can name: H1 .. H999 and
// D1 .. D999 on the controllers the compiler prints for.
constexpr double maximumOffsetRegister = 999;

// What `length=` and `radius=` choose, for messages.
std::string_view offsetRegisterRole(std::string_view setting) {
  if (setting == "length"sv) {
    return "tool length offset";
  }
  if (setting == "radius"sv) {
    return "tool radius offset";
  }
  return {};
}

class PartEvaluator {
public:
  // `assigned`, when given, collects the declarations whose values are set.
  PartEvaluator(Evaluator& evaluator, const PartItem& part,
                std::vector<const Declaration*>* assigned = nullptr)
      : evaluator_(evaluator), context_(evaluator.context()), part_(part), assigned_(assigned) {}

  void run() {
    Bindings environment;
    // -D sets the chosen part's parameters; the file's other parts are
    // checked with their defaults.
    const PartItem* selected = context_.program.selectedPart;
    bool takesDefines = selected == nullptr || selected == &part_;
    for (const Parameter& parameter : part_.parameters) {
      if (parameter.declaration == nullptr) {
        continue;
      }
      Value value = parameter.defaultValue
                        ? evaluator_.evaluate(*parameter.defaultValue, Bindings())
                        : Value{};
      auto define = context_.options.defines.find(parameter.name);
      if (takesDefines && define != context_.options.defines.end()) {
        value = Value::ofNumber(define->second);
      }
      if (value.type.kind == TypeKind::Num) {
        assign(parameter.declaration, value);
        environment.bind(parameter.declaration, std::move(value));
      }
    }
    walk(part_.body, environment);
  }

private:
  void assign(const Declaration* declaration, const Value& value) {
    context_.mutableDeclaration(declaration).value = value;
    if (assigned_ != nullptr) {
      assigned_->push_back(declaration);
    }
  }

  // Lets bind in the block's own frame, so they end with the block.
  void walk(const Block& block, const Bindings& outer) {
    Bindings environment(&outer);
    for (const StmtPtr& statement : block.statements) {
      if (evaluator_.exhausted() || ++statements_ > maximumCheckedStatements) {
        return;
      }
      walkStatement(*statement, environment);
    }
  }

  std::optional<double> number(const Expr& expression, const Bindings& environment) {
    double result = 0;
    Value other;
    if (!evaluator_.evaluateAsNumber(expression, environment, result, other)) {
      return std::nullopt;
    }
    return result;
  }

  // Checks value > 0 and reports `what` otherwise.
  std::optional<double> positive(const Expr& expression, const Bindings& environment,
                                 std::string_view what) {
    return positiveDescribed(expression, environment, [what] { return std::string(what); });
  }

  // `describe` names the value; called only for a message.
  template <typename Describe>
  std::optional<double> positiveDescribed(const Expr& expression, const Bindings& environment,
                                          Describe describe) {
    std::optional<double> value = number(expression, environment);
    if (value && !(*value > 0)) {
      evaluator_.report(DiagnosticKind::ValueNotPositive, expression.span,
                        fmt::format("{} is {:g}; it must be greater than 0", describe(), *value));
      return std::nullopt;
    }
    return value;
  }

  std::optional<double> wholeNumber(const Expr& expression, const Bindings& environment,
                                    std::string_view what) {
    std::optional<double> value = number(expression, environment);
    if (value && *value != std::floor(*value)) {
      evaluator_.report(DiagnosticKind::NotInteger, expression.span,
                        fmt::format("{} must be a whole number, not {:g}", what, *value));
      return std::nullopt;
    }
    return value;
  }

  void walkStatement(const Stmt& statement, Bindings& environment) {
    switch (statement.kind) {
    case StmtKind::Units:
    case StmtKind::Origin:  // machine set-up: no value to check, nothing
    case StmtKind::Coolant: // on the tool path
    case StmtKind::Error:
      return;
    case StmtKind::Tool:
      walkTool(as<ToolStmt>(statement), environment);
      return;
    case StmtKind::Feed:
      feedKnown_ |= positive(*as<ValueStmt>(statement).value, environment, "the feed").has_value();
      return;
    case StmtKind::Spindle:
      positive(*as<ValueStmt>(statement).value, environment, "the spindle speed");
      return;
    case StmtKind::Safe:
      safeKnown_ = true;
      for (const Argument& setting : as<SafeStmt>(statement).settings) {
        positive(*setting.value, environment, "the safe height z (above the work surface)");
      }
      return;
    case StmtKind::Let: {
      const auto& let = as<LetStmt>(statement);
      Value value = evaluator_.evaluate(*let.value, environment);
      if (let.declaration != nullptr) {
        if (!let.declaration->value && !value.isError()) {
          assign(let.declaration, value);
        }
        environment.bind(let.declaration, std::move(value));
      }
      return;
    }
    case StmtKind::Cut:
      walkCut(as<CutStmt>(statement), environment);
      return;
    case StmtKind::For:
      walkFor(as<ForStmt>(statement), environment);
      return;
    case StmtKind::If: {
      const auto& conditional = as<IfStmt>(statement);
      Value condition = evaluator_.evaluate(*conditional.condition, environment);
      if (condition.type.kind == TypeKind::Bool) {
        walk(condition.boolean ? conditional.thenBlock : conditional.elseBlock, environment);
      }
      return;
    }
    }
  }

  void walkTool(const ToolStmt& tool, const Bindings& environment) {
    toolKnown_ = true;
    std::optional<double> toolNumber = wholeNumber(*tool.number, environment, "the tool number");
    if (toolNumber && *toolNumber < 1) {
      evaluator_.report(
          DiagnosticKind::ValueNotPositive, tool.number->span,
          fmt::format("the tool number is {:g}; tools are numbered from 1", *toolNumber));
    } else if (toolNumber && *toolNumber > largestToolNumber) {
      evaluator_.report(DiagnosticKind::RegisterOutOfRange, tool.number->span,
                        fmt::format("the tool number is {:g}; a T word holds at most {} digits, "
                                    "tools are numbered up to {:.0f}",
                                    *toolNumber, toolNumberDigits, largestToolNumber));
    }
    for (const Argument& setting : tool.settings) {
      if (std::string_view role = offsetRegisterRole(setting.name); !role.empty()) {
        checkOffsetRegister(setting, role, environment);
        continue;
      }
      std::optional<double> value = positiveDescribed(
          *setting.value, environment, [&] { return fmt::format("the tool's {}", setting.name); });
      if (setting.name == "feed"sv && value) {
        feedKnown_ = true;
      }
    }
  }

  // `length=H` and `radius=R`: a whole number from 1 to 999, the first
  // problem reported.
  void checkOffsetRegister(const Argument& setting, std::string_view role,
                           const Bindings& environment) {
    std::optional<double> value = number(*setting.value, environment);
    if (!value) {
      return;
    }
    std::string what = fmt::format("'{}=' (the {} register)", setting.name, role);
    if (*value != std::floor(*value)) {
      evaluator_.report(DiagnosticKind::NotInteger, setting.value->span,
                        fmt::format("{} must be a whole number, not {:g}", what, *value));
    } else if (*value < 1) {
      evaluator_.report(DiagnosticKind::ValueNotPositive, setting.value->span,
                        fmt::format("{} is {:g}; registers are numbered from 1", what, *value));
    } else if (*value > maximumOffsetRegister) {
      evaluator_.report(DiagnosticKind::RegisterOutOfRange, setting.value->span,
                        fmt::format("{} is {:g}; the largest register is {:g}", what, *value,
                                    maximumOffsetRegister));
    }
  }

  void walkFor(const ForStmt& loop, Bindings& environment) {
    Value range = evaluator_.evaluate(*loop.range, environment);
    if (range.type.kind != TypeKind::Range || loop.declaration == nullptr) {
      return;
    }
    const auto& rangeExpression = as<RangeExpr>(*loop.range);
    for (const auto& [bound, expression] : {std::pair{range.low, rangeExpression.low.get()},
                                            {range.high, rangeExpression.high.get()}}) {
      if (bound != std::floor(bound)) {
        evaluator_.report(DiagnosticKind::NotInteger, expression->span,
                          fmt::format("a loop bound must be a whole number, not {:g}", bound));
        return;
      }
    }
    if (range.high < range.low) {
      evaluator_.report(DiagnosticKind::EmptyLoop, loop.range->span,
                        fmt::format("this loop never runs: {:g} .. {:g} counts up from {:g} and "
                                    "{:g} is smaller",
                                    range.low, range.high, range.low, range.high));
      return;
    }
    double last = std::min(range.high, range.low + maximumCheckedIterations - 1);
    for (double i = range.low;
         i <= last && !evaluator_.exhausted() && statements_ <= maximumCheckedStatements; ++i) {
      Bindings body(&environment);
      body.bind(loop.declaration, Value::ofNumber(i));
      walk(loop.body, body);
    }
  }

  // The numeric modifiers of the cut being walked; a later one of the same
  // name replaces an earlier one. Kept between cuts to reuse its storage.
  struct ModifierValue {
    std::string_view name;
    std::pair<double, const Modifier*> value;
  };
  const std::pair<double, const Modifier*>* modifierValue(std::string_view name) const {
    for (const ModifierValue& entry : modifierValues_) {
      if (entry.name == name) {
        return &entry.value;
      }
    }
    return nullptr;
  }
  void setModifierValue(std::string_view name, double value, const Modifier* modifier) {
    for (ModifierValue& entry : modifierValues_) {
      if (entry.name == name) {
        entry.value = {value, modifier};
        return;
      }
    }
    modifierValues_.push_back({name, {value, modifier}});
  }

  void walkCut(const CutStmt& cut, const Bindings& environment) {
    evaluator_.evaluate(*cut.curve, environment);
    modifierValues_.clear();
    for (const Modifier& modifier : cut.modifiers) {
      if (!modifier.value || modifier.name == "method"sv || modifier.name == "entry"sv ||
          modifier.name == "arcs"sv || modifier.name == "side"sv || modifier.name == "comp"sv) {
        continue;
      }
      if (std::optional<double> value = number(*modifier.value, environment)) {
        setModifierValue(modifier.name, *value, &modifier);
      }
    }
    checkSweep();
    if (const auto* tolerance = modifierValue("tolerance")) {
      auto [value, modifier] = *tolerance;
      if (!(value > 0)) {
        evaluator_.report(DiagnosticKind::InvalidTolerance, modifier->value->span,
                          fmt::format("the tolerance is {:g}; it must be greater than 0", value));
      } else if (value < minimumTolerance) {
        evaluator_.report(DiagnosticKind::InvalidTolerance, modifier->value->span,
                          fmt::format("the tolerance {:g} mm is below the {:g} mm the compiler "
                                      "can honour",
                                      value, minimumTolerance));
      }
    }
    if (const auto* samples = modifierValue("samples")) {
      auto [value, modifier] = *samples;
      if (value != std::floor(value) || value < 2 || value > maximumSamples) {
        evaluator_.report(DiagnosticKind::InvalidSamples, modifier->value->span,
                          fmt::format("samples={:g}: a cut needs a whole number of samples, from 2 "
                                      "to {:g}",
                                      value, maximumSamples));
      }
    }
    for (const char* name : {"spacing", "feed", "lead"}) {
      if (const auto* found = modifierValue(name); found != nullptr && !(found->first > 0)) {
        evaluator_.report(DiagnosticKind::ValueNotPositive, found->second->value->span,
                          fmt::format("{}={:g}: it must be greater than 0", name, found->first));
      }
    }
    checkSideHasTool(cut);
    // Reported once per part: the first cut shows what is missing.
    if (!toolKnown_ && !toolReported_) {
      toolReported_ = true;
      evaluator_.report(DiagnosticKind::NoTool, cut.span,
                        "this cut has no tool; write 'tool N diameter=D' before it");
    }
    if (!safeKnown_ && !safeReported_) {
      safeReported_ = true;
      evaluator_.report(DiagnosticKind::NoSafeHeight, cut.span,
                        "this cut has no safe height for rapid moves; write 'safe z=Z' before it");
    }
    bool hasFeedModifier = false;
    for (const Modifier& modifier : cut.modifiers) {
      hasFeedModifier |= modifier.name == "feed"sv;
    }
    if (!feedKnown_ && !hasFeedModifier && !feedReported_) {
      feedReported_ = true;
      evaluator_.report(DiagnosticKind::NoFeed, cut.span,
                        "this cut has no feed rate; give the tool 'feed=F', write 'feed F', or "
                        "add 'feed=F' to the cut");
    }
  }

  // A cut beside the curve runs at the tool's radius: a tool must be chosen.
  void checkSideHasTool(const CutStmt& cut) {
    if (toolKnown_) {
      return;
    }
    for (const Modifier& modifier : cut.modifiers) {
      if (modifier.name != "side"sv || !modifier.value || modifier.value->kind != ExprKind::Name) {
        continue;
      }
      std::string_view side = as<NameExpr>(*modifier.value).name;
      if (side == "left"sv || side == "right"sv) {
        toolReported_ = true; // this says it more precisely than no-tool
        evaluator_.report(DiagnosticKind::SideWithoutTool, modifier.span(),
                          fmt::format("side={} runs the tool at its radius beside the curve, but "
                                      "no tool diameter is known here; write 'tool N diameter=D' "
                                      "before this cut",
                                      side));
      }
    }
  }

  void checkSweep() {
    const auto* depth = modifierValue("depth");
    const auto* step = modifierValue("step");
    if (step != nullptr && !(step->first > 0)) {
      evaluator_.report(
          DiagnosticKind::SweepStep, step->second->value->span,
          fmt::format("the sweep step is {:g}; it must be greater than 0", step->first));
      return;
    }
    if (depth != nullptr && step != nullptr && !(depth->first >= step->first)) {
      evaluator_.report(DiagnosticKind::SweepDepth, depth->second->value->span,
                        fmt::format("the sweep depth {:g} is less than its step {:g}; the depth "
                                    "must be at least one step",
                                    depth->first, step->first));
    }
  }

  Evaluator& evaluator_;
  SemaContext& context_;
  const PartItem& part_;
  std::vector<const Declaration*>* assigned_;
  bool toolKnown_ = false;
  bool feedKnown_ = false;
  std::size_t statements_ = 0;
  bool toolReported_ = false;
  bool safeKnown_ = false;
  bool safeReported_ = false;
  bool feedReported_ = false;
  std::vector<ModifierValue> modifierValues_;
};

} // namespace

void evaluateConstants(Evaluator& evaluator) {
  for (const Module& module : evaluator.context().program.modules) {
    for (const ItemPtr& item : module.items) {
      if (item->kind == ItemKind::Const && as<ConstItem>(*item).declaration != nullptr) {
        evaluator.constantValue(as<ConstItem>(*item).declaration);
      }
    }
  }
}

void evaluatePart(Evaluator& evaluator, const PartItem& part,
                  std::vector<const Declaration*>* assigned) {
  PartEvaluator(evaluator, part, assigned).run();
}

} // namespace cncc::frontend
