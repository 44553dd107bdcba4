// The checker's part bodies: parameters, statements, settings and cut
// modifiers.
#include "checker.h"

#include <algorithm>
#include <fmt/format.h>

namespace cncc::frontend {

using namespace std::string_view_literals;

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
  std::vector<const Declaration*> lets;
  for (StmtPtr& statement : block.statements) {
    checkStatement(*statement, scope, block, lets);
  }
  for (const Declaration* let : lets) {
    // A let whose value had an error is already reported.
    if (!context_.usedDeclarations.contains(let) && !let->name.starts_with("_") &&
        let->type.kind != TypeKind::Error) {
      context_.report(DiagnosticKind::UnusedLet, let->span,
                      fmt::format("'{}' is never used", let->name));
    }
  }
}

void Checker::checkStatement(Stmt& statement, Scope& scope, Block& block,
                             std::vector<const Declaration*>& lets) {
  switch (statement.kind) {
  case StmtKind::Units:
  case StmtKind::Error:
    return;
  case StmtKind::Tool: {
    auto& tool = as<ToolStmt>(statement);
    expectNumber(*tool.number, scope, "tool number");
    checkSettings(tool.settings, {{"diameter", true}, {"spindle", false}, {"feed", false}}, scope,
                  "tool", tool.span);
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
    checkSettings(safe.settings, {{"z", true}}, scope, "safe", safe.span);
    return;
  }
  case StmtKind::Let:
    checkLet(as<LetStmt>(statement), scope, block, lets);
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

void Checker::checkSettings(std::vector<Argument>& settings,
                            const std::vector<ParameterSpec>& allowed, const Scope& scope,
                            std::string_view owner, SourceSpan ownerSpan) {
  std::map<std::string, const Argument*> seen;
  for (Argument& setting : settings) {
    bool known = false;
    for (const ParameterSpec& spec : allowed) {
      known |= spec.name == setting.name;
    }
    expectNumberOf(*setting.value, scope,
                   [&] { return fmt::format("'{}' of '{}'", setting.name, owner); });
    if (!known) {
      context_.report(DiagnosticKind::UnknownArgument, setting.nameSpan,
                      fmt::format("'{}' has no setting '{}'; expected {}", owner, setting.name,
                                  joinNames(allowed)));
    } else if (auto previous = seen.find(setting.name); previous != seen.end()) {
      Diagnostic* diagnostic = context_.report(DiagnosticKind::DuplicateArgument, setting.nameSpan,
                                               fmt::format("'{}' is given twice", setting.name));
      context_.diagnostics.addNote(diagnostic, previous->second->nameSpan, "first given here");
    } else {
      seen[setting.name] = &setting;
    }
  }
  for (const ParameterSpec& spec : allowed) {
    if (spec.required && !seen.contains(spec.name)) {
      context_.report(DiagnosticKind::MissingArgument, ownerSpan,
                      fmt::format("'{}' needs '{}='", owner, spec.name));
    }
  }
}

void Checker::checkLet(LetStmt& let, Scope& scope, Block& block,
                       std::vector<const Declaration*>& lets) {
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
  scope.add(let.name, &declaration);
  lets.push_back(&declaration);
  context_.program.scopeExtents.push_back(
      {SourceSpan{let.span.file, let.span.end, block.span.end}, &declaration});
}

void Checker::warnIfShadowing(const std::string& name, SourceSpan span, const Scope& outer) {
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
    bodyScope.add(loop.variable, &declaration);
    context_.program.scopeExtents.push_back({loop.body.span, &declaration});
  }
  checkBlock(loop.body, bodyScope);
}

void Checker::checkCut(CutStmt& cut, const Scope& scope) {
  Type type = checkExpression(*cut.curve, scope);
  expectType(*cut.curve, type, TypeKind::Curve, "'curve' statement");
  std::map<std::string, const Modifier*> seen;
  for (Modifier& modifier : cut.modifiers) {
    checkModifier(modifier, scope, seen);
  }
  bool sweep = seen.contains("sweep");
  for (const char* needed : {"depth", "step"}) {
    if (sweep && !seen.contains(needed)) {
      context_.report(DiagnosticKind::SweepIncomplete, seen.at("sweep")->nameSpan,
                      fmt::format("'sweep' needs '{}='; write 'sweep depth=D step=S'", needed));
    }
    if (!sweep && seen.contains(needed)) {
      context_.report(
          DiagnosticKind::SweepIncomplete, seen.at(needed)->nameSpan,
          fmt::format("'{}=' belongs to a sweep; write 'sweep depth=D step=S'", needed));
    }
  }
  if (seen.contains("samples") && seen.contains("spacing")) {
    Diagnostic* diagnostic =
        context_.report(DiagnosticKind::ConflictingModifiers, seen.at("spacing")->nameSpan,
                        "'samples=' and 'spacing=' both choose the points; give only one");
    context_.diagnostics.addNote(diagnostic, seen.at("samples")->nameSpan,
                                 "'samples=' is given here");
  }
}

void Checker::checkModifier(Modifier& modifier, const Scope& scope,
                            std::map<std::string, const Modifier*>& seen) {
  const std::vector<std::string>& names = cutModifierNames();
  if (std::find(names.begin(), names.end(), modifier.name) == names.end()) {
    context_.report(DiagnosticKind::UnknownModifier, modifier.nameSpan,
                    fmt::format("unknown modifier '{}' after 'curve'{}", modifier.name,
                                suggestion(modifier.name, names)));
    if (modifier.value) {
      checkExpression(*modifier.value, scope);
    }
    return;
  }
  if (auto previous = seen.find(modifier.name); previous != seen.end()) {
    Diagnostic* diagnostic =
        context_.report(DiagnosticKind::DuplicateModifier, modifier.nameSpan,
                        fmt::format("modifier '{}' is given twice", modifier.name));
    context_.diagnostics.addNote(diagnostic, previous->second->nameSpan, "first given here");
    return;
  }
  seen[modifier.name] = &modifier;
  if (modifier.name == "sweep"sv) {
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
  if (modifier.name == "method"sv) {
    checkChoice(modifier, {"linear", "aspline", "bspline", "cspline", "nurbs"});
  } else if (modifier.name == "entry"sv) {
    checkChoice(modifier, {"plunge", "ramp"});
  } else if (modifier.name == "arcs"sv) {
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
void Checker::checkChoice(Modifier& modifier, const std::vector<std::string>& choices) {
  std::string list;
  for (const std::string& choice : choices) {
    list += (list.empty() ? "" : ", ") + choice;
  }
  if (modifier.value->kind != ExprKind::Name) {
    context_.report(DiagnosticKind::InvalidChoice, modifier.value->span,
                    fmt::format("'{}=' takes one of: {}", modifier.name, list));
    return;
  }
  const std::string& word = as<NameExpr>(*modifier.value).name;
  if (std::find(choices.begin(), choices.end(), word) == choices.end()) {
    context_.report(DiagnosticKind::InvalidChoice, modifier.value->span,
                    fmt::format("'{}' is not a valid {}; expected one of: {}{}", word,
                                modifier.name, list, suggestion(word, choices)));
  }
}

} // namespace cncc::frontend
