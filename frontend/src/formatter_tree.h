// The formatter's walk over the syntax tree (private to the front end): one
// function per construct, each building the document of its canonical
// layout in source order (so the SourceCursor can place the comments).
// Items and statements are in formatter.cpp, expressions in
// formatter_expressions.cpp; the layout rules are listed in formatter.h.
#pragma once

#include "cncc/frontend/ast.h"
#include "cncc/frontend/formatter.h"
#include "formatter_layout.h"
#include "formatter_source.h"

#include <functional>
#include <string>
#include <vector>

namespace cncc::frontend::format {

class TreeFormatter {
public:
  TreeFormatter(SourceCursor& source, const FormatOptions& options)
      : source_(source), indent_(options.indentWidth) {}

  Doc module(const Module& module);

private:
  // items (formatter.cpp)
  Doc item(const Item& item);
  Doc importItem(const ImportItem& import);
  Doc constItem(const ConstItem& constant);
  Doc fnItem(const FnItem& function);
  Doc partItem(const PartItem& part);
  Doc parameters(const NodeList<Parameter>& parameters, std::uint32_t after);
  Doc parameter(const Parameter& parameter);
  Doc assignment(std::vector<Doc> head, const Expr& value);

  // statements (formatter.cpp)
  Doc block(const Block& block);
  Doc statement(const Stmt& statement);
  Doc unitsStatement(const UnitsStmt& units);
  Doc toolStatement(const ToolStmt& tool);
  Doc valueStatement(const ValueStmt& setting);
  Doc safeStatement(const SafeStmt& safe);
  Doc originStatement(const OriginStmt& origin);
  Doc coolantStatement(const CoolantStmt& coolant);
  Doc letStatement(const LetStmt& let);
  Doc cutStatement(const CutStmt& cut);
  Doc forStatement(const ForStmt& loop);
  Doc ifStatement(const IfStmt& choice);
  Doc settings(const NodeList<Argument>& settings, const std::vector<std::string>& known);
  Doc modifiers(const NodeList<Modifier>& modifiers);
  Doc setting(SourceSpan nameSpan, const Expr* value);

  // expressions (formatter_expressions.cpp)
  Doc expression(const Expr& expression);
  Doc operand(const Expr& expression, bool parenthesised);
  Doc operatorChain(const Expr& root);
  Doc unary(const UnaryExpr& unary);
  Doc call(const CallExpr& call);
  Doc argument(const Argument& argument, bool spacedEquals);
  Doc point(const PointExpr& point);
  Doc list(const ListExpr& list);
  Doc index(const IndexExpr& index);
  Doc member(const MemberExpr& member);
  Doc ifElse(const IfElseExpr& choice);

  // `open element, element, ... close`: on one line if it fits, else one
  // element per line or, with `fill`, as many per line as fit.
  // `element(i)` prints element i and returns where it ends in the source.
  using ElementPrinter = std::function<std::uint32_t(std::size_t, std::vector<Doc>&)>;
  Doc bracketed(const Token& open, std::size_t count, const ElementPrinter& element, bool fill);

  SourceCursor& source_;
  int indent_;
};

// How tightly an expression binds, for parentheses and spacing: 0 for a
// range, 1 `||` .. 5 `* / %`, 6 unary, 7 `^`, 8 what needs no parentheses
// anywhere (names, literals, calls, points, lists, postfix), -1 `if`.
int precedence(const Expr& expression);
// Whether `child`, an operand of `parent`, needs parentheses to parse back
// as the same tree. `right` says which operand of a binary operator.
bool needsParentheses(const Expr& parent, const Expr& child, bool right);
// Whether `root` prints with a spaced operator outside parentheses (so the
// named arguments of a call holding it are written `name = value`).
bool hasSpacedOperator(const Expr& root);

} // namespace cncc::frontend::format
