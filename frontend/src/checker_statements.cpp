// The checker's part bodies: parameters, statements, settings and cut
// modifiers.
#include "checker.h"

#include <algorithm>
#include <fmt/format.h>

namespace cncc::frontend {

using namespace std::string_view_literals;

namespace {

// The settings of `tool` and `safe`.
constexpr ParameterSpec toolSettings[] = {
    {"diameter", true}, {"length", false}, {"radius", false}, {"spindle", false}, {"feed", false}};
constexpr ParameterSpec safeSettings[] = {{"z", true}};
// checkSettings keeps the settings seen in an array of this size.
constexpr std::size_t maxSettings = 5;
static_assert(std::size(toolSettings) <= maxSettings && std::size(safeSettings) <= maxSettings);

constexpr std::string_view methodChoices[] = {"linear", "aspline", "bspline", "cspline", "nurbs"};
constexpr std::string_view entryChoices[] = {"plunge", "ramp"};
constexpr std::string_view sideChoices[] = {"center", "left", "right"};
constexpr std::string_view compChoices[] = {"host", "controller"};

// Where the modifiers checkCut and checkModifier look at are in
// cutModifierNames(); the number of names for one that is not there.
struct ModifierPlaces {
  const std::vector<std::string>* names;
  std::size_t sweep, depth, step, samples, spacing, method, entry, arcs, side, comp, lead;
};

const ModifierPlaces& modifierPlaces() {
  static const ModifierPlaces places = [] {
    const std::vector<std::string>& names = cutModifierNames();
    auto place = [&](std::string_view name) {
      return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
    };
    return ModifierPlaces{&names,           place("sweep"),   place("depth"),  place("step"),
                          place("samples"), place("spacing"), place("method"), place("entry"),
                          place("arcs"),    place("side"),    place("comp"),   place("lead")};
  }();
  return places;
}

// The modifier seen at `place`, null when none (or no such modifier).
const Modifier* seenAt(std::span<const Modifier*> seen, std::size_t place) {
  return place < seen.size() ? seen[place] : nullptr;
}

// The word a choice modifier was given, empty when it is not a name.
std::string_view choiceWord(const Modifier* modifier) {
  if (modifier == nullptr || !modifier->value || modifier->value->kind != ExprKind::Name) {
    return {};
  }
  return as<NameExpr>(*modifier->value).name;
}

} // namespace

void Checker::checkPart(PartItem& part, const Scope& fileScope) {
  Scope scope(&fileScope);
  for (Parameter& parameter : part.parameters) {
    if (parameter.name.empty()) {
      continue;
    }
    if (scope.findLocal(parameter.name) != nullptr) {
      context_.report(DiagnosticKind::Redefinition, parameter.nameSpan,
                      fmt::format("parameter '{}' is declared twice", parameter.name));
      continue;
    }
    if (!parameter.defaultValue) {
      context_.report(DiagnosticKind::ParameterWithoutDefault, parameter.nameSpan,
                      fmt::format("part parameter '{}' needs a default value: write '{} = "
                                  "<number>'",
                                  parameter.name, parameter.name));
    } else {
      Type type = checkExpression(*parameter.defaultValue, fileScope);
      expectTypeOf(*parameter.defaultValue, type, TypeKind::Num,
                   [&] { return fmt::format("default of part parameter '{}'", parameter.name); });
    }
    warnIfShadowing(parameter.name, parameter.nameSpan, fileScope);
    Declaration& declaration = context_.declare(DeclarationKind::PartParameter, parameter.name,
                                                parameter.nameSpan, Type::num());
    declaration.part = &part;
    parameter.declaration = &declaration;
    scope.add(parameter.name, &declaration);
    context_.program.scopeExtents.push_back({part.body.span, &declaration});
  }
  checkBlock(part.body, scope);
}

void Checker::checkBlock(Block& block, const Scope& parent) {
  Scope scope(&parent);
  std::size_t firstLet = lets_.size();
  for (StmtPtr& statement : block.statements) {
    checkStatement(*statement, scope, block);
  }
  for (std::size_t i = firstLet; i < lets_.size(); ++i) {
    const Declaration* let = lets_[i];
    // A let whose value had an error is already reported.
    if (!context_.usedDeclarations.contains(let) && !let->name.starts_with("_") &&
        let->type.kind != TypeKind::Error) {
      context_.report(DiagnosticKind::UnusedLet, let->span,
                      fmt::format("'{}' is never used", let->name));
    }
  }
  lets_.resize(firstLet);
}

void Checker::checkStatement(Stmt& statement, Scope& scope, Block& block) {
  switch (statement.kind) {
  case StmtKind::Units:
  case StmtKind::Origin:  // the parser checked its offset
  case StmtKind::Coolant: // and its mode
  case StmtKind::Error:
    return;
  case StmtKind::Tool: {
    auto& tool = as<ToolStmt>(statement);
    expectNumber(*tool.number, scope, "tool number");
    checkSettings(tool.settings, toolSettings, scope, "tool", tool.span);
    checkOffsetRegisters(tool);
    return;
  }
  case StmtKind::Feed:
    expectNumber(*as<ValueStmt>(statement).value, scope, "feed");
    return;
  case StmtKind::Spindle:
    expectNumber(*as<ValueStmt>(statement).value, scope, "spindle speed");
    return;
  case StmtKind::Safe: {
    auto& safe = as<SafeStmt>(statement);
    checkSettings(safe.settings, safeSettings, scope, "safe", safe.span);
    return;
  }
  case StmtKind::Let:
    checkLet(as<LetStmt>(statement), scope, block);
    return;
  case StmtKind::Cut:
    checkCut(as<CutStmt>(statement), scope);
    return;
  case StmtKind::For:
    checkFor(as<ForStmt>(statement), scope);
    return;
  case StmtKind::If: {
    auto& conditional = as<IfStmt>(statement);
    Type type = checkExpression(*conditional.condition, scope);
    expectType(*conditional.condition, type, TypeKind::Bool, "condition of 'if'");
    checkBlock(conditional.thenBlock, scope);
    checkBlock(conditional.elseBlock, scope);
    return;
  }
  }
}

void Checker::checkSettings(NodeList<Argument>& settings, std::span<const ParameterSpec> allowed,
                            const Scope& scope, std::string_view owner, SourceSpan ownerSpan) {
  // The first setting given for each allowed one.
  std::array<const Argument*, maxSettings> seen{};
  for (Argument& setting : settings) {
    std::size_t place = allowed.size();
    for (std::size_t i = 0; i < allowed.size() && place == allowed.size(); ++i) {
      if (sameName(allowed[i].name, setting.name)) {
        place = i;
      }
    }
    expectNumberOf(*setting.value, scope,
                   [&] { return fmt::format("'{}' of '{}'", setting.name, owner); });
    if (place == allowed.size()) {
      context_.report(DiagnosticKind::UnknownArgument, setting.nameSpan,
                      fmt::format("'{}' has no setting '{}'; expected {}", owner, setting.name,
                                  joinNames(allowed)));
    } else if (const Argument* previous = seen[place]) {
      Diagnostic* diagnostic = context_.report(DiagnosticKind::DuplicateArgument, setting.nameSpan,
                                               fmt::format("'{}' is given twice", setting.name));
      context_.diagnostics.addNote(diagnostic, previous->nameSpan, "first given here");
    } else {
      seen[place] = &setting;
    }
  }
  for (std::size_t i = 0; i < allowed.size(); ++i) {
    if (allowed[i].required && seen[i] == nullptr) {
      context_.report(DiagnosticKind::MissingArgument, ownerSpan,
                      fmt::format("'{}' needs '{}='", owner, allowed[i].name));
    }
  }
}

// `length=` and `radius=` name registers of the controller's offset tables,
// which the program prints as they are: a part parameter, which may become a
// controller variable, cannot choose one. (Their values are checked when the
// part runs, part_evaluation.cpp.)
void Checker::checkOffsetRegisters(ToolStmt& tool) {
  for (Argument& setting : tool.settings) {
    bool isRegister = setting.name == "length"sv || setting.name == "radius"sv;
    if (!isRegister || setting.value->type.kind == TypeKind::Error ||
        !dependsOnPartParameter(*setting.value)) {
      continue;
    }
    context_.report(DiagnosticKind::NotConstant, setting.value->span,
                    fmt::format("'{}=' is the number of an offset register and must be a constant; "
                                "it cannot depend on a part parameter",
                                setting.name));
    setting.value->type = Type::error(); // reported: the part's run skips it
  }
}

bool Checker::dependsOnPartParameter(const Expr& expression) const {
  auto depends = [this](const Expr* child) {
    return child != nullptr && dependsOnPartParameter(*child);
  };
  switch (expression.kind) {
  case ExprKind::Name: {
    const Declaration* declaration = as<NameExpr>(expression).declaration;
    return declaration != nullptr && (declaration->kind == DeclarationKind::PartParameter ||
                                      parameterDependent_.contains(declaration));
  }
  case ExprKind::Unary:
    return depends(as<UnaryExpr>(expression).operand.get());
  case ExprKind::Binary: {
    const auto& binary = as<BinaryExpr>(expression);
    return depends(binary.left.get()) || depends(binary.right.get());
  }
  case ExprKind::Call:
    // A fn's body sees only its arguments and the file's constants.
    for (const Argument& argument : as<CallExpr>(expression).arguments) {
      if (depends(argument.value.get())) {
        return true;
      }
    }
    return false;
  case ExprKind::Point:
    return std::any_of(as<PointExpr>(expression).components.begin(),
                       as<PointExpr>(expression).components.end(),
                       [&](const ExprPtr& component) { return depends(component.get()); });
  case ExprKind::List:
    return std::any_of(as<ListExpr>(expression).elements.begin(),
                       as<ListExpr>(expression).elements.end(),
                       [&](const ExprPtr& element) { return depends(element.get()); });
  case ExprKind::Range: {
    const auto& range = as<RangeExpr>(expression);
    return depends(range.low.get()) || depends(range.high.get());
  }
  case ExprKind::Index: {
    const auto& index = as<IndexExpr>(expression);
    return depends(index.base.get()) || depends(index.index.get());
  }
  case ExprKind::Member:
    return depends(as<MemberExpr>(expression).base.get());
  case ExprKind::IfElse: {
    const auto& choice = as<IfElseExpr>(expression);
    return depends(choice.condition.get()) || depends(choice.thenValue.get()) ||
           depends(choice.elseValue.get());
  }
  case ExprKind::Number:
  case ExprKind::Bool:
  case ExprKind::String:
  case ExprKind::Error:
    return false;
  }
  return false;
}

void Checker::checkLet(LetStmt& let, Scope& scope, Block& block) {
  Type type = checkExpression(*let.value, scope);
  if (let.name.empty()) {
    return;
  }
  if (const Declaration* previous = scope.findLocal(let.name)) {
    Diagnostic* diagnostic =
        context_.report(DiagnosticKind::Redefinition, let.nameSpan,
                        fmt::format("'{}' is already defined in this block", let.name));
    context_.diagnostics.addNote(diagnostic, previous->span, "the first definition is here");
    return;
  }
  warnIfShadowing(let.name, let.nameSpan, *scope.parent());
  Declaration& declaration = context_.declare(DeclarationKind::Let, let.name, let.nameSpan, type);
  let.declaration = &declaration;
  if (dependsOnPartParameter(*let.value)) {
    parameterDependent_.insert(&declaration);
  }
  scope.add(let.name, &declaration);
  lets_.push_back(&declaration);
  context_.program.scopeExtents.push_back(
      {SourceSpan{let.span.file, let.span.end, block.span.end}, &declaration});
}

void Checker::warnIfShadowing(std::string_view name, SourceSpan span, const Scope& outer) {
  const Declaration* shadowed = outer.find(name);
  if (shadowed == nullptr) {
    return;
  }
  Diagnostic* diagnostic = context_.report(
      DiagnosticKind::ShadowedName, span,
      fmt::format("'{}' hides the {} of the same name", name, declarationKindName(shadowed->kind)));
  if (shadowed->span.valid()) {
    context_.diagnostics.addNote(diagnostic, shadowed->span, "which is defined here");
  }
}

void Checker::checkFor(ForStmt& loop, const Scope& scope) {
  Type type = checkExpression(*loop.range, scope);
  expectType(*loop.range, type, TypeKind::Range, "range of 'for' (write 'a .. b')");
  Scope bodyScope(&scope);
  if (!loop.variable.empty()) {
    warnIfShadowing(loop.variable, loop.variableSpan, scope);
    Declaration& declaration = context_.declare(DeclarationKind::LoopVariable, loop.variable,
                                                loop.variableSpan, Type::num());
    loop.declaration = &declaration;
    if (dependsOnPartParameter(*loop.range)) {
      parameterDependent_.insert(&declaration);
    }
    bodyScope.add(loop.variable, &declaration);
    context_.program.scopeExtents.push_back({loop.body.span, &declaration});
  }
  checkBlock(loop.body, bodyScope);
}

void Checker::checkCut(CutStmt& cut, const Scope& scope) {
  Type type = checkExpression(*cut.curve, scope);
  expectType(*cut.curve, type, TypeKind::Curve, "'curve' statement");
  const ModifierPlaces& places = modifierPlaces();
  seenModifiers_.assign(places.names->size(), nullptr);
  std::span<const Modifier*> seen = seenModifiers_;
  for (Modifier& modifier : cut.modifiers) {
    checkModifier(modifier, scope, seen);
  }
  const Modifier* sweep = seenAt(seen, places.sweep);
  auto checkSweepPart = [&](std::size_t place, std::string_view name) {
    const Modifier* given = seenAt(seen, place);
    if (sweep != nullptr && given == nullptr) {
      context_.report(DiagnosticKind::SweepIncomplete, sweep->nameSpan,
                      fmt::format("'sweep' needs '{}='; write 'sweep depth=D step=S'", name));
    }
    if (sweep == nullptr && given != nullptr) {
      context_.report(DiagnosticKind::SweepIncomplete, given->nameSpan,
                      fmt::format("'{}=' belongs to a sweep; write 'sweep depth=D step=S'", name));
    }
  };
  checkSweepPart(places.depth, "depth");
  checkSweepPart(places.step, "step");
  const Modifier* samples = seenAt(seen, places.samples);
  const Modifier* spacing = seenAt(seen, places.spacing);
  if (samples != nullptr && spacing != nullptr) {
    Diagnostic* diagnostic =
        context_.report(DiagnosticKind::ConflictingModifiers, spacing->nameSpan,
                        "'samples=' and 'spacing=' both choose the points; give only one");
    context_.diagnostics.addNote(diagnostic, samples->nameSpan, "'samples=' is given here");
  }
  checkToolSide(seenAt(seen, places.side), seenAt(seen, places.comp), seenAt(seen, places.lead));
}

// `comp=` and `lead=` say how the tool runs beside the curve, so they need
// `side=left|right` (which targets have the controller's compensation is
// the lowering's to say).
void Checker::checkToolSide(const Modifier* side, const Modifier* comp, const Modifier* lead) {
  std::string_view sideWord = choiceWord(side);
  bool beside = sideWord == "left"sv || sideWord == "right"sv;
  // A side= that is not a valid choice is reported already.
  bool sideInvalid = side != nullptr && !beside && sideWord != "center"sv;
  for (const Modifier* modifier : {comp, lead}) {
    if (modifier == nullptr || beside || sideInvalid) {
      continue;
    }
    Diagnostic* diagnostic = context_.report(
        DiagnosticKind::OffsetWithoutSide, modifier->nameSpan,
        fmt::format("'{}=' is for a tool running beside the curve; add 'side=left' or "
                    "'side=right'",
                    modifier->name));
    if (side != nullptr) {
      context_.diagnostics.addNote(diagnostic, side->span(),
                                   "with side=center the tool's centre runs on the curve");
    }
  }
}

void Checker::checkModifier(Modifier& modifier, const Scope& scope,
                            std::span<const Modifier*> seen) {
  const ModifierPlaces& places = modifierPlaces();
  const std::vector<std::string>& names = *places.names;
  std::size_t place = 0;
  while (place < names.size() && !sameName(names[place], modifier.name)) {
    ++place;
  }
  if (place == names.size()) {
    context_.report(DiagnosticKind::UnknownModifier, modifier.nameSpan,
                    fmt::format("unknown modifier '{}' after 'curve'{}", modifier.name,
                                suggestion(std::string(modifier.name), names)));
    if (modifier.value) {
      checkExpression(*modifier.value, scope);
    }
    return;
  }
  if (const Modifier* previous = seen[place]) {
    Diagnostic* diagnostic =
        context_.report(DiagnosticKind::DuplicateModifier, modifier.nameSpan,
                        fmt::format("modifier '{}' is given twice", modifier.name));
    context_.diagnostics.addNote(diagnostic, previous->nameSpan, "first given here");
    return;
  }
  seen[place] = &modifier;
  if (place == places.sweep) {
    if (modifier.value) {
      context_.report(DiagnosticKind::ModifierValue, modifier.span(),
                      "'sweep' takes no value; write 'sweep depth=D step=S'");
    }
    return;
  }
  if (!modifier.value) {
    context_.report(
        DiagnosticKind::ModifierValue, modifier.nameSpan,
        fmt::format("modifier '{}' needs a value: '{}=...'", modifier.name, modifier.name));
    return;
  }
  if (place == places.method) {
    checkChoice(modifier, methodChoices);
  } else if (place == places.entry) {
    checkChoice(modifier, entryChoices);
  } else if (place == places.side) {
    checkChoice(modifier, sideChoices);
  } else if (place == places.comp) {
    checkChoice(modifier, compChoices);
  } else if (place == places.arcs) {
    // A switch of the printed program, so a literal rather than an expression.
    if (modifier.value->kind != ExprKind::Bool) {
      context_.report(DiagnosticKind::InvalidChoice, modifier.value->span,
                      "'arcs=' takes true or false");
    }
  } else {
    expectNumberOf(*modifier.value, scope, [&] { return fmt::format("'{}='", modifier.name); });
  }
}

// `method=linear`: the value is a word from a fixed list, not a name.
void Checker::checkChoice(Modifier& modifier, std::span<const std::string_view> choices) {
  auto list = [&] {
    std::string text;
    for (std::string_view choice : choices) {
      text.append(text.empty() ? "" : ", ").append(choice);
    }
    return text;
  };
  if (modifier.value->kind != ExprKind::Name) {
    context_.report(DiagnosticKind::InvalidChoice, modifier.value->span,
                    fmt::format("'{}=' takes one of: {}", modifier.name, list()));
    return;
  }
  std::string_view word = as<NameExpr>(*modifier.value).name;
  if (std::find(choices.begin(), choices.end(), word) == choices.end()) {
    std::vector<std::string> candidates(choices.begin(), choices.end());
    context_.report(DiagnosticKind::InvalidChoice, modifier.value->span,
                    fmt::format("'{}' is not a valid {}; expected one of: {}{}", word,
                                modifier.name, list(), suggestion(std::string(word), candidates)));
  }
}

} // namespace cncc::frontend
