// Name resolution, scopes and types.
//
// Every expression gets a type; a mistake makes its expression's type Error,
// which is accepted everywhere, so one mistake gives one message. `fn`
// parameters have type Any: a function is checked once generically, and the
// evaluator checks the values each call actually passes.
#pragma once

#include "sema_context.h"

#include <map>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

namespace cncc::frontend {

// Constants and functions are checked on first use.
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

std::string joinNames(const std::vector<ParameterSpec>& parameters);

class Checker {
public:
  explicit Checker(SemaContext& context) : context_(context), states_(ownStates_) {}
  void run();

private:
  // file level (checker_items.cpp)
  void declareItems(Module& module);
  static std::string functionSignature(const FnItem& function);
  static const Declaration* itemDeclaration(const Item& item);
  void buildFileScope(Module& module);
  void addImportedNames(Scope& scope, const ImportItem& import,
                        std::map<std::string, const ImportItem*>& importedFrom);
  void checkConstantsAndFunctions(Module& module);
  void checkParts(Module& module, std::span<PartItem* const> parts);
  void checkPartsOnTwoThreads(const Scope& scope, std::span<PartItem* const> first,
                              std::span<PartItem* const> second);
  void checkUnnamedItem(Item& item, const Scope& scope);
  // A checker for parts on another thread: it reads this one's states, all
  // Checked by then, and reports to `context`.
  Checker(SemaContext& context, const Checker& main) : context_(context), states_(main.states_) {}
  ItemState stateOf(const Declaration* declaration) const {
    auto found = states_.find(declaration);
    return found == states_.end() ? ItemState::Unchecked : found->second;
  }
  void ensureChecked(const Declaration* declaration);
  Type checkFunction(FnItem& function, const Scope& fileScope);

  // parts (checker_statements.cpp)
  void checkPart(PartItem& part, const Scope& fileScope);
  void checkBlock(Block& block, const Scope& parent);
  void checkStatement(Stmt& statement, Scope& scope, Block& block,
                      std::vector<const Declaration*>& lets);
  void checkSettings(std::vector<Argument>& settings, const std::vector<ParameterSpec>& allowed,
                     const Scope& scope, std::string_view owner, SourceSpan ownerSpan);
  void checkLet(LetStmt& let, Scope& scope, Block& block, std::vector<const Declaration*>& lets);
  void warnIfShadowing(const std::string& name, SourceSpan span, const Scope& outer);
  void checkFor(ForStmt& loop, const Scope& scope);
  void checkCut(CutStmt& cut, const Scope& scope);
  void checkModifier(Modifier& modifier, const Scope& scope,
                     std::map<std::string, const Modifier*>& seen);
  void checkChoice(Modifier& modifier, const std::vector<std::string>& choices);

  // expressions (checker_expressions.cpp)
  void expectNumber(Expr& expression, const Scope& scope, std::string_view context);
  bool expectType(const Expr& expression, Type actual, TypeKind expected, std::string_view what,
                  TypeKind element = TypeKind::Any);
  static bool typeFits(Type actual, TypeKind expected, TypeKind element);
  // As expectType and expectNumber, with `describe()` naming what is checked:
  // called only for a message, as most checks pass.
  template <typename Describe>
  bool expectTypeOf(const Expr& expression, Type actual, TypeKind expected, Describe describe,
                    TypeKind element = TypeKind::Any) {
    return typeFits(actual, expected, element) ||
           expectType(expression, actual, expected, describe(), element);
  }
  template <typename Describe>
  void expectNumberOf(Expr& expression, const Scope& scope, Describe describe) {
    Type type = checkExpression(expression, scope);
    expectTypeOf(expression, type, TypeKind::Num, describe);
  }
  Type checkExpression(Expr& expression, const Scope& scope);
  Type computeType(Expr& expression, const Scope& scope);
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
  ArgumentBinding bindArguments(const CallExpr& call, const std::vector<ParameterSpec>& parameters,
                                bool variadic);
  void bindNamedArgument(const CallExpr& call, const Argument& argument,
                         const std::vector<ParameterSpec>& parameters, ArgumentBinding& binding);
  void reportMissing(const CallExpr& call, const std::vector<ParameterSpec>& parameters,
                     ArgumentBinding& binding);
  Type checkFunctionCall(CallExpr& call, const Declaration& declaration, const Scope& scope);
  Type checkBuiltinCall(CallExpr& call, const Scope& scope);
  void checkOrderOrDegree(const CallExpr& call, ArgumentBinding& binding);
  static Type builtinResultType(const std::string& name);
  bool checkBuiltinArgument(const std::string& function, const std::string& parameter, Expr& value,
                            const Scope& scope);
  bool checkAnalyticCurve(CallExpr& call, const std::vector<ParameterSpec>& parameters,
                          const ArgumentBinding& binding, const Scope& scope);

  static std::optional<Type> binaryResultType(BinaryOperator op, Type left, Type right);

  SemaContext& context_;
  std::unordered_map<const Declaration*, ItemState> ownStates_;
  std::unordered_map<const Declaration*, ItemState>& states_;
  // Each fn's parameters as bindArguments takes them, built on its first call.
  std::unordered_map<const FnItem*, std::vector<ParameterSpec>> functionParameters_;
};

} // namespace cncc::frontend
