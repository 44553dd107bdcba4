// Name resolution, scopes and types.
//
// Every expression gets a type; a mistake makes its expression's type Error,
// which is accepted everywhere, so one mistake gives one message. `fn`
// parameters have type Any: a function is checked once generically, and the
// evaluator checks the values each call actually passes.
#include "sema_context.h"

#include <algorithm>
#include <fmt/format.h>

namespace cncc::frontend {

namespace {

enum class ItemState { Unchecked, InProgress, Checked };

// Binds call arguments to parameters: positional ones in order, named ones
// by name. Reports unknown, duplicate, surplus and missing arguments.
struct ArgumentBinding {
  std::vector<const Argument*> bound; // one per parameter, null when absent
  std::vector<const Argument*> extra; // for variadic functions
  bool ok = true;
  bool unknownName = false; // a misspelt name: missing arguments are its echo
};

struct ParameterSpec {
  std::string name;
  bool required;
};

std::string joinNames(const std::vector<ParameterSpec>& parameters) {
  std::string text;
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    text += fmt::format("{}'{}'", i == 0 ? "" : ", ", parameters[i].name);
  }
  return text;
}

class Checker {
public:
  explicit Checker(SemaContext& context) : context_(context) {}

  void run() {
    for (Module& module : context_.program.modules) {
      declareItems(module);
    }
    for (Module& module : context_.program.modules) {
      buildFileScope(module);
    }
    for (Module& module : context_.program.modules) {
      checkItems(module);
    }
  }

private:
  // ------------------------------------------------------------ file level
  void declareItems(Module& module) {
    for (ItemPtr& item : module.items) {
      if (item->kind == ItemKind::Const) {
        auto& constant = as<ConstItem>(*item);
        if (!constant.name.empty()) {
          Declaration& declaration = context_.declare(DeclarationKind::Constant, constant.name,
                                                      constant.nameSpan, Type::error());
          constant.declaration = &declaration;
          context_.itemOf[&declaration] = &constant;
        }
      } else if (item->kind == ItemKind::Fn) {
        auto& function = as<FnItem>(*item);
        if (!function.name.empty()) {
          Declaration& declaration = context_.declare(DeclarationKind::Function, function.name,
                                                      function.nameSpan, Type::error());
          declaration.function = &function;
          declaration.signature = functionSignature(function);
          function.declaration = &declaration;
          context_.itemOf[&declaration] = &function;
        }
      } else if (item->kind == ItemKind::Part && &module == &context_.program.modules.front()) {
        auto& part = as<PartItem>(*item);
        context_.program.parts.push_back(&part);
      }
    }
  }

  static std::string functionSignature(const FnItem& function) {
    std::string text = function.name + "(";
    for (std::size_t i = 0; i < function.parameters.size(); ++i) {
      text += (i == 0 ? "" : ", ") + function.parameters[i].name;
    }
    return text + ")";
  }

  static const Declaration* itemDeclaration(const Item& item) {
    if (item.kind == ItemKind::Const) {
      return as<ConstItem>(item).declaration;
    }
    if (item.kind == ItemKind::Fn) {
      return as<FnItem>(item).declaration;
    }
    return nullptr;
  }

  void buildFileScope(Module& module) {
    Scope& scope = context_.fileScopes.emplace(&module, Scope(&context_.builtinScope)).first->second;
    // Imported names first, so the file's own definitions take precedence.
    std::map<std::string, const ImportItem*> importedFrom;
    for (ItemPtr& item : module.items) {
      if (item->kind == ItemKind::Import && as<ImportItem>(*item).resolvedFile.valid()) {
        addImportedNames(scope, as<ImportItem>(*item), importedFrom);
      }
    }
    std::map<std::string, const Item*> seen;
    for (ItemPtr& item : module.items) {
      const Declaration* declaration = itemDeclaration(*item);
      std::string name = item->kind == ItemKind::Part ? as<PartItem>(*item).name
                         : declaration != nullptr    ? declaration->name
                                                     : "";
      if (name.empty()) {
        continue;
      }
      SourceSpan nameSpan = item->kind == ItemKind::Part ? as<PartItem>(*item).nameSpan
                                                         : declaration->span;
      if (auto previous = seen.find(name); previous != seen.end()) {
        Diagnostic* diagnostic = context_.report(
            DiagnosticKind::Redefinition, nameSpan, fmt::format("'{}' is already defined", name));
        context_.diagnostics.addNote(diagnostic, previous->second->span,
                                     "the first definition is here");
        continue;
      }
      seen[name] = item.get();
      if (declaration == nullptr) {
        continue; // parts are not values
      }
      if (const Declaration* builtin = context_.builtinScope.findLocal(name)) {
        context_.report(DiagnosticKind::Redefinition, nameSpan,
                        fmt::format("'{}' is a builtin {} and cannot be redefined", name,
                                    builtin->name == "pi" ? "constant" : "function"));
        continue;
      }
      scope.add(name, declaration);
      context_.itemScope[declaration] = &scope;
    }
  }

  void addImportedNames(Scope& scope, const ImportItem& import,
                        std::map<std::string, const ImportItem*>& importedFrom) {
    for (const Module& imported : context_.program.modules) {
      if (imported.file != import.resolvedFile) {
        continue;
      }
      for (const ItemPtr& item : imported.items) {
        const Declaration* declaration = itemDeclaration(*item);
        if (declaration == nullptr) {
          continue;
        }
        if (auto previous = importedFrom.find(declaration->name);
            previous != importedFrom.end() && previous->second != &import) {
          Diagnostic* diagnostic = context_.report(
              DiagnosticKind::Redefinition, import.pathSpan,
              fmt::format("'{}' is defined by both \"{}\" and \"{}\"", declaration->name,
                          previous->second->path, import.path));
          context_.diagnostics.addNote(diagnostic, previous->second->pathSpan,
                                       "the first import is here");
          continue;
        }
        importedFrom[declaration->name] = &import;
        scope.add(declaration->name, declaration);
      }
    }
  }

  void checkItems(Module& module) {
    const Scope& scope = context_.fileScopes.at(&module);
    for (ItemPtr& item : module.items) {
      if (const Declaration* declaration = itemDeclaration(*item)) {
        ensureChecked(declaration);
      } else if (item->kind == ItemKind::Fn || item->kind == ItemKind::Const) {
        checkUnnamedItem(*item, scope);
      } else if (item->kind == ItemKind::Part) {
        checkPart(as<PartItem>(*item), scope);
      }
    }
  }

  // An item whose name did not parse: still check its body for the editor.
  void checkUnnamedItem(Item& item, const Scope& scope) {
    if (item.kind == ItemKind::Const) {
      checkExpression(*as<ConstItem>(item).value, scope);
    }
  }

  // Constants and functions are checked on first use, so they may be used
  // before the line that defines them; a cycle is an error.
  void ensureChecked(const Declaration* declaration) {
    ItemState& state = states_[declaration];
    if (state != ItemState::Unchecked) {
      return;
    }
    state = ItemState::InProgress;
    const Item* item = context_.itemOf.at(declaration);
    auto scopeEntry = context_.itemScope.find(declaration);
    Scope detached(&context_.builtinScope);
    const Scope& scope = scopeEntry != context_.itemScope.end() ? *scopeEntry->second : detached;
    Declaration& mutableDeclaration = context_.mutableDeclaration(declaration);
    if (item->kind == ItemKind::Const) {
      auto& constant = const_cast<ConstItem&>(as<ConstItem>(*item));
      mutableDeclaration.type = checkExpression(*constant.value, scope);
    } else {
      auto& function = const_cast<FnItem&>(as<FnItem>(*item));
      mutableDeclaration.type = checkFunction(function, scope);
    }
    state = ItemState::Checked;
  }

  Type checkFunction(FnItem& function, const Scope& fileScope) {
    Scope scope(&fileScope);
    for (Parameter& parameter : function.parameters) {
      if (scope.findLocal(parameter.name) != nullptr) {
        context_.report(DiagnosticKind::Redefinition, parameter.nameSpan,
                        fmt::format("parameter '{}' is declared twice", parameter.name));
        continue;
      }
      if (parameter.defaultValue) {
        context_.report(DiagnosticKind::TypeMismatch, parameter.defaultValue->span,
                        "function parameters have no defaults; only part parameters do");
      }
      Declaration& declaration = context_.declare(DeclarationKind::FunctionParameter,
                                                  parameter.name, parameter.nameSpan, Type::any());
      parameter.declaration = &declaration;
      scope.add(parameter.name, &declaration);
      context_.program.scopeExtents.push_back({function.body->span, &declaration});
    }
    return checkExpression(*function.body, scope);
  }

  // ------------------------------------------------------------ parts
  void checkPart(PartItem& part, const Scope& fileScope) {
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
        expectType(*parameter.defaultValue, type, TypeKind::Num,
                   fmt::format("default of part parameter '{}'", parameter.name));
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

  void checkBlock(Block& block, const Scope& parent) {
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

  void checkStatement(Stmt& statement, Scope& scope, Block& block,
                      std::vector<const Declaration*>& lets) {
    switch (statement.kind) {
    case StmtKind::Units:
    case StmtKind::Error:
      return;
    case StmtKind::Tool: {
      auto& tool = as<ToolStmt>(statement);
      expectNumber(*tool.number, scope, "tool number");
      checkSettings(tool.settings, {{"diameter", true}, {"spindle", false}, {"feed", false}},
                    scope, "tool", tool.span);
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

  void checkSettings(std::vector<Argument>& settings, const std::vector<ParameterSpec>& allowed,
                     const Scope& scope, std::string_view owner, SourceSpan ownerSpan) {
    std::map<std::string, const Argument*> seen;
    for (Argument& setting : settings) {
      bool known = false;
      for (const ParameterSpec& spec : allowed) {
        known |= spec.name == setting.name;
      }
      expectNumber(*setting.value, scope, fmt::format("'{}' of '{}'", setting.name, owner));
      if (!known) {
        context_.report(DiagnosticKind::UnknownArgument, setting.nameSpan,
                        fmt::format("'{}' has no setting '{}'; expected {}", owner, setting.name,
                                    joinNames(allowed)));
      } else if (auto previous = seen.find(setting.name); previous != seen.end()) {
        Diagnostic* diagnostic =
            context_.report(DiagnosticKind::DuplicateArgument, setting.nameSpan,
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

  void checkLet(LetStmt& let, Scope& scope, Block& block, std::vector<const Declaration*>& lets) {
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
    Declaration& declaration =
        context_.declare(DeclarationKind::Let, let.name, let.nameSpan, type);
    let.declaration = &declaration;
    scope.add(let.name, &declaration);
    lets.push_back(&declaration);
    context_.program.scopeExtents.push_back(
        {SourceSpan{let.span.file, let.span.end, block.span.end}, &declaration});
  }

  void warnIfShadowing(const std::string& name, SourceSpan span, const Scope& outer) {
    const Declaration* shadowed = outer.find(name);
    if (shadowed == nullptr) {
      return;
    }
    Diagnostic* diagnostic = context_.report(
        DiagnosticKind::ShadowedName, span,
        fmt::format("'{}' hides the {} of the same name", name,
                    declarationKindName(shadowed->kind)));
    if (shadowed->span.valid()) {
      context_.diagnostics.addNote(diagnostic, shadowed->span, "which is defined here");
    }
  }

  void checkFor(ForStmt& loop, const Scope& scope) {
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

  void checkCut(CutStmt& cut, const Scope& scope) {
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
        context_.report(DiagnosticKind::SweepIncomplete, seen.at(needed)->nameSpan,
                        fmt::format("'{}=' belongs to a sweep; write 'sweep depth=D step=S'",
                                    needed));
      }
    }
    if (seen.contains("samples") && seen.contains("spacing")) {
      Diagnostic* diagnostic = context_.report(
          DiagnosticKind::ConflictingModifiers, seen.at("spacing")->nameSpan,
          "'samples=' and 'spacing=' both choose the points; give only one");
      context_.diagnostics.addNote(diagnostic, seen.at("samples")->nameSpan,
                                   "'samples=' is given here");
    }
  }

  void checkModifier(Modifier& modifier, const Scope& scope,
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
    if (modifier.name == "sweep") {
      if (modifier.value) {
        context_.report(DiagnosticKind::ModifierValue, modifier.span(),
                        "'sweep' takes no value; write 'sweep depth=D step=S'");
      }
      return;
    }
    if (!modifier.value) {
      context_.report(DiagnosticKind::ModifierValue, modifier.nameSpan,
                      fmt::format("modifier '{}' needs a value: '{}=...'", modifier.name,
                                  modifier.name));
      return;
    }
    if (modifier.name == "method") {
      checkChoice(modifier, {"linear", "aspline", "bspline", "cspline", "nurbs"});
    } else if (modifier.name == "entry") {
      checkChoice(modifier, {"plunge", "ramp"});
    } else {
      expectNumber(*modifier.value, scope, fmt::format("'{}='", modifier.name));
    }
  }

  // `method=linear`: the value is a word from a fixed list, not a name.
  void checkChoice(Modifier& modifier, const std::vector<std::string>& choices) {
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
                      fmt::format("'{}' is not a valid {}; expected one of: {}{}", word, modifier.name,
                                  list, suggestion(word, choices)));
    }
  }

  // ------------------------------------------------------------ expressions
  void expectNumber(Expr& expression, const Scope& scope, std::string_view context) {
    Type type = checkExpression(expression, scope);
    expectType(expression, type, TypeKind::Num, context);
  }

  // Reports when `actual` is not `expected`; returns whether it fits.
  bool expectType(const Expr& expression, Type actual, TypeKind expected,
                  std::string_view what, TypeKind element = TypeKind::Any) {
    if (actual.isLenient()) {
      return true;
    }
    bool fits = actual.kind == expected;
    if (fits && expected == TypeKind::List && element != TypeKind::Any) {
      fits = actual.element == element || actual.element == TypeKind::Any ||
             actual.element == TypeKind::Error;
    }
    if (fits) {
      return true;
    }
    Type wanted = expected == TypeKind::List ? Type::listOf(element) : Type{expected};
    context_.report(DiagnosticKind::TypeMismatch, expression.span,
                    fmt::format("{} must be a {}, but this is a {}", what, typeName(wanted),
                                typeName(actual)));
    return false;
  }

  Type checkExpression(Expr& expression, const Scope& scope) {
    expression.type = computeType(expression, scope);
    return expression.type;
  }

  Type computeType(Expr& expression, const Scope& scope) {
    switch (expression.kind) {
    case ExprKind::Number:
      return Type::num();
    case ExprKind::Bool:
      return Type::boolean();
    case ExprKind::String:
      return Type::string();
    case ExprKind::Error:
      return Type::error();
    case ExprKind::Name:
      return checkName(as<NameExpr>(expression), scope);
    case ExprKind::Unary:
      return checkUnary(as<UnaryExpr>(expression), scope);
    case ExprKind::Binary:
      return checkBinary(as<BinaryExpr>(expression), scope);
    case ExprKind::Call:
      return checkCall(as<CallExpr>(expression), scope);
    case ExprKind::Point:
      return checkPoint(as<PointExpr>(expression), scope);
    case ExprKind::List:
      return checkList(as<ListExpr>(expression), scope);
    case ExprKind::Range: {
      auto& range = as<RangeExpr>(expression);
      bool ok = expectType(*range.low, checkExpression(*range.low, scope), TypeKind::Num,
                           "start of a range");
      ok &= expectType(*range.high, checkExpression(*range.high, scope), TypeKind::Num,
                       "end of a range");
      return ok ? Type::range() : Type::error();
    }
    case ExprKind::Index:
      return checkIndex(as<IndexExpr>(expression), scope);
    case ExprKind::Member:
      return checkMember(as<MemberExpr>(expression), scope);
    case ExprKind::IfElse:
      return checkIfElse(as<IfElseExpr>(expression), scope);
    }
    return Type::error();
  }

  Type checkName(NameExpr& name, const Scope& scope) {
    const Declaration* declaration = scope.find(name.name);
    if (declaration == nullptr) {
      std::string hint = name.name == "t"
                             ? "; 't' is the curve parameter only inside polar(...) and param(...)"
                             : suggestion(name.name, scope.visibleNames());
      context_.report(DiagnosticKind::UndefinedName, name.span,
                      fmt::format("'{}' is not defined{}", name.name, hint));
      return Type::error();
    }
    name.declaration = declaration;
    context_.reference(name.span, declaration, false);
    if (declaration->kind == DeclarationKind::Function ||
        (declaration->kind == DeclarationKind::Builtin && declaration->name != "pi")) {
      context_.report(DiagnosticKind::TypeMismatch, name.span,
                      fmt::format("'{}' is a function; call it as {}(...)", name.name, name.name));
      return Type::error();
    }
    if (declaration->kind == DeclarationKind::Constant) {
      if (states_[declaration] == ItemState::InProgress) {
        context_.report(DiagnosticKind::CircularConstant, name.span,
                        fmt::format("constant '{}' depends on itself", name.name));
        return Type::error();
      }
      ensureChecked(declaration);
    }
    return declaration->type;
  }

  Type checkUnary(UnaryExpr& unary, const Scope& scope) {
    Type operand = checkExpression(*unary.operand, scope);
    if (operand.isLenient()) {
      return operand;
    }
    if (unary.op == UnaryOperator::Not) {
      return expectType(*unary.operand, operand, TypeKind::Bool, "operand of '!'") ? operand
                                                                                  : Type::error();
    }
    if (operand.kind == TypeKind::Num || operand.kind == TypeKind::Point) {
      return operand;
    }
    context_.report(DiagnosticKind::TypeMismatch, unary.span,
                    fmt::format("cannot negate a {}", typeName(operand)));
    return Type::error();
  }

  Type checkBinary(BinaryExpr& binary, const Scope& scope) {
    Type left = checkExpression(*binary.left, scope);
    Type right = checkExpression(*binary.right, scope);
    if (left.kind == TypeKind::Error || right.kind == TypeKind::Error) {
      return Type::error();
    }
    std::optional<Type> result = binaryResultType(binary.op, left, right);
    if (result) {
      return *result;
    }
    context_.report(DiagnosticKind::TypeMismatch, binary.operatorSpan,
                    fmt::format("'{}' cannot combine a {} and a {}", operatorSpelling(binary.op),
                                typeName(left), typeName(right)));
    return Type::error();
  }

  Type checkIfElse(IfElseExpr& choice, const Scope& scope) {
    Type condition = checkExpression(*choice.condition, scope);
    bool conditionOk =
        expectType(*choice.condition, condition, TypeKind::Bool, "condition of 'if'");
    Type thenType = checkExpression(*choice.thenValue, scope);
    Type elseType = checkExpression(*choice.elseValue, scope);
    if (!conditionOk || condition.kind == TypeKind::Error) {
      return Type::error();
    }
    if (thenType.isLenient()) {
      return elseType.kind == TypeKind::Error ? thenType : elseType;
    }
    if (elseType.isLenient() || thenType.kind == elseType.kind) {
      return thenType;
    }
    context_.report(DiagnosticKind::TypeMismatch, choice.elseValue->span,
                    fmt::format("both values of 'if' must have one type: this is a {}, the "
                                "'then' value is a {}",
                                typeName(elseType), typeName(thenType)));
    return Type::error();
  }

  Type checkPoint(PointExpr& point, const Scope& scope) {
    bool ok = true;
    for (ExprPtr& component : point.components) {
      ok &= expectType(*component, checkExpression(*component, scope), TypeKind::Num,
                       "a point's coordinate");
    }
    return ok && point.components.size() <= 3 ? Type::point() : Type::error();
  }

  Type checkList(ListExpr& list, const Scope& scope) {
    const Expr* first = nullptr;
    TypeKind element = TypeKind::Any;
    bool ok = true;
    for (ExprPtr& item : list.elements) {
      Type type = checkExpression(*item, scope);
      if (type.isLenient()) {
        ok &= type.kind != TypeKind::Error;
        continue;
      }
      if (first == nullptr) {
        first = item.get();
        element = type.kind;
      } else if (type.kind != element) {
        Diagnostic* diagnostic = context_.report(
            DiagnosticKind::MixedList, item->span,
            fmt::format("a list holds one type: this element is a {}, the first is a {}",
                        typeName(type), typeKindName(element)));
        context_.diagnostics.addNote(diagnostic, first->span, "the first element is here");
        ok = false;
      }
    }
    return ok ? Type::listOf(element) : Type::error();
  }

  Type checkIndex(IndexExpr& index, const Scope& scope) {
    Type base = checkExpression(*index.base, scope);
    Type position = checkExpression(*index.index, scope);
    bool ok = expectType(*index.index, position, TypeKind::Num, "an index");
    if (base.isLenient()) {
      return base;
    }
    if (base.kind != TypeKind::List) {
      std::string hint = base.kind == TypeKind::Point ? "; use .x, .y or .z for a coordinate" : "";
      context_.report(DiagnosticKind::TypeMismatch, index.base->span,
                      fmt::format("only a list can be indexed; this is a {}{}", typeName(base),
                                  hint));
      return Type::error();
    }
    return ok ? Type{base.element} : Type::error();
  }

  Type checkMember(MemberExpr& member, const Scope& scope) {
    Type base = checkExpression(*member.base, scope);
    if (member.member.empty() || base.kind == TypeKind::Error) {
      return Type::error();
    }
    if (base.kind != TypeKind::Point && base.kind != TypeKind::Any) {
      context_.report(DiagnosticKind::TypeMismatch, member.base->span,
                      fmt::format("only a point has .{}; this is a {}", member.member,
                                  typeName(base)));
      return Type::error();
    }
    if (member.member != "x" && member.member != "y" && member.member != "z") {
      context_.report(DiagnosticKind::UnknownMember, member.memberSpan,
                      fmt::format("a point has no member '{}'; it has x, y and z{}", member.member,
                                  suggestion(member.member, {"x", "y", "z"})));
      return Type::error();
    }
    return Type::num();
  }

  // ------------------------------------------------------------ calls
  Type checkCall(CallExpr& call, const Scope& scope) {
    const Declaration* declaration = scope.find(call.callee);
    if (declaration == nullptr) {
      std::vector<std::string> callable;
      for (const std::string& name : scope.visibleNames()) {
        const Declaration* candidate = scope.find(name);
        if (candidate->kind == DeclarationKind::Function ||
            candidate->kind == DeclarationKind::Builtin) {
          callable.push_back(name);
        }
      }
      context_.report(DiagnosticKind::UnknownFunction, call.calleeSpan,
                      fmt::format("there is no function '{}'{}", call.callee,
                                  suggestion(call.callee, callable)));
      checkArgumentsAlone(call, scope);
      return Type::error();
    }
    context_.reference(call.calleeSpan, declaration, false);
    call.declaration = declaration;
    if (declaration->kind == DeclarationKind::Function) {
      return checkFunctionCall(call, *declaration, scope);
    }
    if (declaration->kind == DeclarationKind::Builtin && declaration->name != "pi") {
      return checkBuiltinCall(call, scope);
    }
    context_.report(DiagnosticKind::NotCallable, call.calleeSpan,
                    fmt::format("'{}' is a {} ({}), not a function", call.callee,
                                declarationKindName(declaration->kind),
                                typeName(declaration->type)));
    checkArgumentsAlone(call, scope);
    return Type::error();
  }

  void checkArgumentsAlone(CallExpr& call, const Scope& scope) {
    for (Argument& argument : call.arguments) {
      checkExpression(*argument.value, scope);
    }
  }

  ArgumentBinding bindArguments(const CallExpr& call, const std::vector<ParameterSpec>& parameters,
                                bool variadic) {
    ArgumentBinding binding;
    binding.bound.assign(parameters.size(), nullptr);
    std::size_t nextPositional = 0;
    for (const Argument& argument : call.arguments) {
      if (argument.name.empty()) {
        if (variadic) {
          binding.extra.push_back(&argument);
          continue;
        }
        while (nextPositional < parameters.size() && binding.bound[nextPositional] != nullptr) {
          ++nextPositional;
        }
        if (nextPositional >= parameters.size()) {
          context_.report(DiagnosticKind::TooManyArguments, argument.value->span,
                          fmt::format("'{}' takes {} argument{}; this one is too many",
                                      call.callee, parameters.size(),
                                      parameters.size() == 1 ? "" : "s"));
          binding.ok = false;
          continue;
        }
        binding.bound[nextPositional++] = &argument;
        continue;
      }
      bindNamedArgument(call, argument, parameters, binding);
    }
    return binding;
  }

  void bindNamedArgument(const CallExpr& call, const Argument& argument,
                         const std::vector<ParameterSpec>& parameters, ArgumentBinding& binding) {
    for (std::size_t i = 0; i < parameters.size(); ++i) {
      if (parameters[i].name != argument.name) {
        continue;
      }
      if (binding.bound[i] != nullptr) {
        Diagnostic* diagnostic =
            context_.report(DiagnosticKind::DuplicateArgument, argument.nameSpan,
                            fmt::format("argument '{}' of '{}' is given twice", argument.name,
                                        call.callee));
        context_.diagnostics.addNote(diagnostic, binding.bound[i]->span(), "first given here");
        binding.ok = false;
        return;
      }
      binding.bound[i] = &argument;
      return;
    }
    std::vector<std::string> names;
    for (const ParameterSpec& parameter : parameters) {
      names.push_back(parameter.name);
    }
    std::string expected = parameters.empty()
                               ? fmt::format("'{}' takes no named arguments", call.callee)
                               : fmt::format("'{}' takes {}", call.callee, joinNames(parameters));
    context_.report(DiagnosticKind::UnknownArgument, argument.nameSpan,
                    fmt::format("unknown argument '{}'; {}{}", argument.name, expected,
                                suggestion(argument.name, names)));
    binding.ok = false;
    binding.unknownName = true;
  }

  void reportMissing(const CallExpr& call, const std::vector<ParameterSpec>& parameters,
                     ArgumentBinding& binding) {
    for (std::size_t i = 0; i < parameters.size(); ++i) {
      if (binding.unknownName) {
        binding.ok = false;
        return;
      }
      if (parameters[i].required && binding.bound[i] == nullptr) {
        context_.report(DiagnosticKind::MissingArgument, call.calleeSpan,
                        fmt::format("'{}' needs the argument '{}'", call.callee,
                                    parameters[i].name));
        binding.ok = false;
      }
    }
  }

  Type checkFunctionCall(CallExpr& call, const Declaration& declaration, const Scope& scope) {
    const FnItem& function = *declaration.function;
    std::vector<ParameterSpec> parameters;
    for (const Parameter& parameter : function.parameters) {
      parameters.push_back({parameter.name, true});
    }
    ArgumentBinding binding = bindArguments(call, parameters, false);
    reportMissing(call, parameters, binding);
    checkArgumentsAlone(call, scope);
    if (states_[&declaration] == ItemState::InProgress) {
      Diagnostic* diagnostic = context_.report(
          DiagnosticKind::RecursiveFunction, call.calleeSpan,
          fmt::format("'{}' calls itself; functions are inlined and cannot be recursive",
                      call.callee));
      context_.diagnostics.addNote(diagnostic, declaration.span, "the function is defined here");
      context_.invalidFunctions.insert(&declaration);
      return Type::error();
    }
    ensureChecked(&declaration);
    return binding.ok ? declaration.type : Type::error();
  }

  Type checkBuiltinCall(CallExpr& call, const Scope& scope) {
    const BuiltinInfo* info = nullptr;
    for (const BuiltinInfo& builtin : builtinFunctions()) {
      if (builtin.name == call.callee) {
        info = &builtin;
      }
    }
    std::vector<ParameterSpec> parameters;
    for (const BuiltinParameter& parameter : info->parameters) {
      parameters.push_back({parameter.name, parameter.required});
    }
    ArgumentBinding binding = bindArguments(call, parameters, info->variadic);
    reportMissing(call, parameters, binding);
    if (info->name == "nurbs" || info->name == "bspline") {
      checkOrderOrDegree(call, binding);
    }
    if (info->name == "polar" || info->name == "param") {
      return checkAnalyticCurve(call, parameters, binding, scope) ? Type::curve() : Type::error();
    }
    bool ok = binding.ok;
    for (std::size_t i = 0; i < parameters.size(); ++i) {
      if (binding.bound[i] != nullptr) {
        ok &= checkBuiltinArgument(info->name, parameters[i].name, *binding.bound[i]->value,
                                   scope);
      }
    }
    for (const Argument* argument : binding.extra) {
      ok &= expectType(*argument->value, checkExpression(*argument->value, scope),
                       TypeKind::Curve, fmt::format("each argument of '{}'", info->name));
    }
    if (info->variadic && binding.extra.empty()) {
      context_.report(DiagnosticKind::MissingArgument, call.calleeSpan,
                      fmt::format("'{}' needs at least one curve", info->name));
      ok = false;
    }
    if (!ok) {
      return Type::error();
    }
    return builtinResultType(info->name);
  }

  void checkOrderOrDegree(const CallExpr& call, ArgumentBinding& binding) {
    const Argument* order = binding.bound[0];
    const Argument* degree = binding.bound[1];
    if (order != nullptr && degree != nullptr) {
      Diagnostic* diagnostic = context_.report(
          DiagnosticKind::OrderAndDegree, degree->span(),
          fmt::format("'{}' takes 'order' or 'degree', not both (order = degree + 1)",
                      call.callee));
      context_.diagnostics.addNote(diagnostic, order->span(), "'order' is given here");
      binding.ok = false;
    } else if (order == nullptr && degree == nullptr) {
      context_.report(DiagnosticKind::MissingArgument, call.calleeSpan,
                      fmt::format("'{}' needs 'order=' or 'degree='", call.callee));
      binding.ok = false;
    }
  }

  static Type builtinResultType(const std::string& name) {
    static const std::set<std::string> curveBuiltins = {
        "nurbs", "bspline", "bezier", "polar", "param", "line",
        "arc",   "path",    "translate", "rotate", "scale"};
    return curveBuiltins.contains(name) ? Type::curve() : Type::num();
  }

  bool checkBuiltinArgument(const std::string& function, const std::string& parameter,
                            Expr& value, const Scope& scope) {
    Type type = checkExpression(value, scope);
    std::string what = fmt::format("argument '{}' of '{}'", parameter, function);
    if (parameter == "points") {
      return expectType(value, type, TypeKind::List, what, TypeKind::Point);
    }
    if (parameter == "weights" || parameter == "knots") {
      return expectType(value, type, TypeKind::List, what, TypeKind::Num);
    }
    if (parameter == "list") {
      return expectType(value, type, TypeKind::List, what);
    }
    if (parameter == "curve") {
      return expectType(value, type, TypeKind::Curve, what);
    }
    if ((function == "line" && (parameter == "from" || parameter == "to")) ||
        parameter == "center") {
      return expectType(value, type, TypeKind::Point, what);
    }
    return expectType(value, type, TypeKind::Num, what);
  }

  // polar(r = ..., t = a .. b) and param(x = ..., y = ..., z = ..., t = a .. b):
  // the expressions see the curve parameter `t`; the range does not.
  bool checkAnalyticCurve(CallExpr& call, const std::vector<ParameterSpec>& parameters,
                          const ArgumentBinding& binding, const Scope& scope) {
    bool ok = binding.ok;
    const Argument* range = binding.bound.back();
    SourceSpan parameterSpan = range != nullptr && !range->name.empty() ? range->nameSpan
                                                                        : call.calleeSpan;
    if (range != nullptr) {
      ok &= expectType(*range->value, checkExpression(*range->value, scope), TypeKind::Range,
                       fmt::format("argument 't' of '{}' (write 't = a .. b')", call.callee));
    }
    Declaration& parameter =
        context_.declare(DeclarationKind::CurveParameter, "t", parameterSpan, Type::num());
    parameter.description = fmt::format("the parameter of this {} curve", call.callee);
    context_.usedDeclarations.insert(&parameter);
    Scope curveScope(&scope);
    curveScope.add("t", &parameter);
    for (std::size_t i = 0; i + 1 < parameters.size(); ++i) {
      if (const Argument* argument = binding.bound[i]) {
        context_.program.scopeExtents.push_back({argument->value->span, &parameter});
        ok &= expectType(*argument->value, checkExpression(*argument->value, curveScope),
                         TypeKind::Num,
                         fmt::format("argument '{}' of '{}'", parameters[i].name, call.callee));
      }
    }
    context_.program.curveParameters[&call] = &parameter;
    return ok;
  }

  static std::optional<Type> binaryResultType(BinaryOperator op, Type left, Type right);

  SemaContext& context_;
  std::map<const Declaration*, ItemState> states_;
};

std::optional<Type> Checker::binaryResultType(BinaryOperator op, Type left, Type right) {
  bool anyLeft = left.kind == TypeKind::Any;
  bool anyRight = right.kind == TypeKind::Any;
  auto is = [](Type type, TypeKind kind) { return type.kind == kind || type.kind == TypeKind::Any; };
  switch (op) {
  case BinaryOperator::Add:
  case BinaryOperator::Subtract:
    if (anyLeft && anyRight) {
      return Type::any();
    }
    if (anyLeft || anyRight || left.kind == right.kind) {
      Type known = anyLeft ? right : left;
      if (known.kind == TypeKind::Num || known.kind == TypeKind::Point) {
        return known;
      }
    }
    return std::nullopt;
  case BinaryOperator::Multiply:
    if (is(left, TypeKind::Num) && is(right, TypeKind::Num)) {
      return anyLeft || anyRight ? Type::any() : Type::num();
    }
    if ((is(left, TypeKind::Num) && is(right, TypeKind::Point)) ||
        (is(left, TypeKind::Point) && is(right, TypeKind::Num))) {
      return Type::point();
    }
    return std::nullopt;
  case BinaryOperator::Divide:
    if (is(left, TypeKind::Num) && is(right, TypeKind::Num)) {
      return anyLeft ? Type::any() : Type::num();
    }
    if (is(left, TypeKind::Point) && is(right, TypeKind::Num)) {
      return Type::point();
    }
    return std::nullopt;
  case BinaryOperator::Remainder:
  case BinaryOperator::Power:
    if (is(left, TypeKind::Num) && is(right, TypeKind::Num)) {
      return Type::num();
    }
    return std::nullopt;
  case BinaryOperator::Less:
  case BinaryOperator::LessEqual:
  case BinaryOperator::Greater:
  case BinaryOperator::GreaterEqual:
    if (is(left, TypeKind::Num) && is(right, TypeKind::Num)) {
      return Type::boolean();
    }
    return std::nullopt;
  case BinaryOperator::Equal:
  case BinaryOperator::NotEqual:
    if (anyLeft || anyRight ||
        (left.kind == right.kind && (left.kind == TypeKind::Num || left.kind == TypeKind::Bool))) {
      return Type::boolean();
    }
    return std::nullopt;
  case BinaryOperator::And:
  case BinaryOperator::Or:
    if (is(left, TypeKind::Bool) && is(right, TypeKind::Bool)) {
      return Type::boolean();
    }
    return std::nullopt;
  }
  return std::nullopt;
}

} // namespace

void checkNamesAndTypes(SemaContext& context) { Checker(context).run(); }

} // namespace cncc::frontend
