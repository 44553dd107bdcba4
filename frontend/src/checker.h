// Name resolution, scopes and types.
//
// Every expression gets a type; a mistake makes its expression's type Error,
// which is accepted everywhere, so one mistake gives one message. `fn`
// parameters have type Any: a function is checked once generically, and the
// evaluator checks the values each call actually passes.
#pragma once

#include "sema_context.h"

#include <array>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace cncc::frontend {

// Constants and functions are checked on first use.
enum class ItemState { Unchecked, InProgress, Checked };

struct ParameterSpec {
  std::string_view name; // of a builtin's, a fn's or a statement's parameter
  bool required;
};

// The parameters a call binds its arguments to: a builtin's or a
// statement's specs, or a fn's parameters, which are all required.
class ParameterList {
public:
  ParameterList(std::span<const ParameterSpec> specs) : specs_(specs) {}
  ParameterList(std::span<const Parameter> function) : function_(function) {}
  std::size_t size() const { return specs_.size() + function_.size(); }
  bool empty() const { return size() == 0; }
  std::string_view name(std::size_t i) const {
    return function_.empty() ? specs_[i].name : std::string_view(function_[i].name);
  }
  bool required(std::size_t i) const { return function_.empty() ? specs_[i].required : true; }

private:
  std::span<const ParameterSpec> specs_; // empty for a fn
  std::span<const Parameter> function_;
};

std::string joinNames(ParameterList parameters);

// Binds call arguments to parameters: positional ones in order, named ones
// by name. Reports unknown, duplicate, surplus and missing arguments.
class ArgumentBinding {
public:
  explicit ArgumentBinding(std::size_t parameters) {
    if (parameters <= fewParameters) {
      bound = std::span<const Argument*>(few_.data(), parameters);
    } else {
      many_.assign(parameters, nullptr);
      bound = many_;
    }
  }
  ArgumentBinding(const ArgumentBinding&) = delete;
  ArgumentBinding& operator=(const ArgumentBinding&) = delete;

  std::span<const Argument*> bound; // one per parameter, null when absent
  std::size_t extra = 0;            // positional arguments of a variadic function
  bool ok = true;
  bool unknownName = false; // a misspelt name: missing arguments are its echo

private:
  // Every builtin has at most this many parameters.
  static constexpr std::size_t fewParameters = 8;
  std::array<const Argument*, fewParameters> few_{};
  std::vector<const Argument*> many_;
};

// A builtin function's parameters and types, as its calls are checked
// (checker_calls.cpp).
struct BuiltinSpec;

class Checker {
public:
  explicit Checker(SemaContext& context) : context_(context), states_(ownStates_) {}
  // A checker for parts on another thread: it reads `main`'s states, all
  // Checked by then, and reports to `context`.
  Checker(SemaContext& context, const Checker& main) : context_(context), states_(main.states_) {}

  // Every module's declarations, file scopes, constants and functions: what
  // parts use, so that parts can be checked after, each on its own.
  void checkItems();
  // A part of the main module, in its file scope (checker_statements.cpp).
  void checkPart(PartItem& part, const Scope& fileScope);
  // The parts of the imported modules, which are checked but not run.
  void checkImportedParts();

private:
  // file level (checker_items.cpp)
  void declareItems(Module& module);
  static std::string functionSignature(const FnItem& function);
  static const Declaration* itemDeclaration(const Item& item);
  void buildFileScope(Module& module);
  void addImportedNames(Scope& scope, const ImportItem& import,
                        std::map<std::string, const ImportItem*>& importedFrom);
  void checkConstantsAndFunctions(Module& module);
  void checkUnnamedItem(Item& item, const Scope& scope);
  ItemState stateOf(const Declaration* declaration) const {
    auto found = states_.find(declaration);
    return found == states_.end() ? ItemState::Unchecked : found->second;
  }
  void ensureChecked(const Declaration* declaration);
  Type checkFunction(FnItem& function, const Scope& fileScope);

  // parts (checker_statements.cpp)
  void checkBlock(Block& block, const Scope& parent);
  void checkStatement(Stmt& statement, Scope& scope, Block& block);
  void checkSettings(NodeList<Argument>& settings, std::span<const ParameterSpec> allowed,
                     const Scope& scope, std::string_view owner, SourceSpan ownerSpan);
  void checkOffsetRegisters(ToolStmt& tool);
  // Whether the value may change with a part parameter: it names one, or a
  // let or loop variable computed from one.
  bool dependsOnPartParameter(const Expr& expression) const;
  void checkLet(LetStmt& let, Scope& scope, Block& block);
  void warnIfShadowing(std::string_view name, SourceSpan span, const Scope& outer);
  void checkFor(ForStmt& loop, const Scope& scope);
  void checkCut(CutStmt& cut, const Scope& scope);
  // `seen` holds, by their place in cutModifierNames(), the modifiers
  // already given.
  void checkModifier(Modifier& modifier, const Scope& scope, std::span<const Modifier*> seen);
  void checkChoice(Modifier& modifier, std::span<const std::string_view> choices);
  void checkToolSide(const Modifier* side, const Modifier* comp, const Modifier* lead);

  // expressions (checker_expressions.cpp)
  void expectNumber(Expr& expression, const Scope& scope, std::string_view context) {
    Type type = checkExpression(expression, scope);
    expectType(expression, type, TypeKind::Num, context);
  }
  // Reports when `actual` is not `expected`; returns whether it fits.
  bool expectType(const Expr& expression, Type actual, TypeKind expected, std::string_view what,
                  TypeKind element = TypeKind::Any) {
    return typeFits(actual, expected, element) ||
           reportMismatch(expression, actual, expected, what, element);
  }
  static bool typeFits(Type actual, TypeKind expected, TypeKind element) {
    if (actual.isLenient()) {
      return true;
    }
    if (actual.kind != expected) {
      return false;
    }
    return expected != TypeKind::List || element == TypeKind::Any || actual.element == element ||
           actual.element == TypeKind::Any || actual.element == TypeKind::Error;
  }
  bool reportMismatch(const Expr& expression, Type actual, TypeKind expected, std::string_view what,
                      TypeKind element);
  // As expectType and expectNumber, with `describe()` naming what is checked:
  // called only for a message, as most checks pass.
  template <typename Describe>
  bool expectTypeOf(const Expr& expression, Type actual, TypeKind expected, Describe describe,
                    TypeKind element = TypeKind::Any) {
    return typeFits(actual, expected, element) ||
           reportMismatch(expression, actual, expected, describe(), element);
  }
  template <typename Describe>
  void expectNumberOf(Expr& expression, const Scope& scope, Describe describe) {
    Type type = checkExpression(expression, scope);
    expectTypeOf(expression, type, TypeKind::Num, describe);
  }
  // Numbers, the most common expressions, are typed without a call.
  Type checkExpression(Expr& expression, const Scope& scope) {
    Type type = expression.kind == ExprKind::Number ? Type::num() : computeType(expression, scope);
    expression.type = type;
    return type;
  }
  Type computeType(Expr& expression, const Scope& scope);
  Type checkRange(RangeExpr& range, const Scope& scope);
  Type checkName(NameExpr& name, const Scope& scope);
  Type checkUnary(UnaryExpr& unary, const Scope& scope);
  Type checkBinary(BinaryExpr& binary, const Scope& scope);
  Type checkIfElse(IfElseExpr& choice, const Scope& scope);
  Type checkPoint(PointExpr& point, const Scope& scope);
  Type checkList(ListExpr& list, const Scope& scope);
  Type checkIndex(IndexExpr& index, const Scope& scope);
  Type checkMember(MemberExpr& member, const Scope& scope);

  // calls (checker_calls.cpp)
  Type checkCall(CallExpr& call, const Scope& scope);
  void checkArgumentsAlone(CallExpr& call, const Scope& scope);
  void bindArguments(const CallExpr& call, ParameterList parameters, bool variadic,
                     ArgumentBinding& binding);
  void bindNamedArgument(const CallExpr& call, const Argument& argument, ParameterList parameters,
                         ArgumentBinding& binding);
  void reportMissing(const CallExpr& call, ParameterList parameters, ArgumentBinding& binding);
  Type checkFunctionCall(CallExpr& call, const Declaration& declaration, const Scope& scope);
  // The spec of a builtin function's declaration; null for `pi`.
  const BuiltinSpec* builtinSpecOf(const Declaration& declaration);
  Type checkBuiltinCall(CallExpr& call, const BuiltinSpec& spec, const Scope& scope);
  void checkOrderOrDegree(const CallExpr& call, ArgumentBinding& binding);
  bool checkBuiltinArgument(const BuiltinSpec& spec, std::size_t parameter, Expr& value,
                            const Scope& scope);
  bool checkAnalyticCurve(CallExpr& call, const BuiltinSpec& spec, const ArgumentBinding& binding,
                          const Scope& scope);

  static std::optional<Type> binaryResultType(BinaryOperator op, Type left, Type right);

  SemaContext& context_;
  std::unordered_map<const Declaration*, ItemState> ownStates_;
  std::unordered_map<const Declaration*, ItemState>& states_;

  // Each builtin declaration's spec, looked up by name on its first call.
  std::unordered_map<const Declaration*, const BuiltinSpec*> builtinSpecs_;
  // checkCut's modifiers seen, by their place in cutModifierNames() (cuts do
  // not nest, so one buffer serves them all).
  std::vector<const Modifier*> seenModifiers_;
  // The lets of the blocks being checked, innermost last: checkBlock looks
  // at its own for unused ones, then drops them.
  std::vector<const Declaration*> lets_;
  // The lets and loop variables whose values come from a part parameter.
  std::unordered_set<const Declaration*> parameterDependent_;
};

} // namespace cncc::frontend
