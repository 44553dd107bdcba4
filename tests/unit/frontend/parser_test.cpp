// The parser: precedence and associativity, every expression, statement and
// item form, cut modifiers, and recovery (one typo, one message; the rest of
// the tree kept; no crash on absurd nesting).
#include "cncc/frontend/parser.h"

#include "cncc/frontend/ast_printer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fmt/format.h>
#include <memory>
#include <string>
#include <vector>

namespace cncc::frontend {
namespace {

// An expression as a compact S-expression: `(+ 1 (* 2 3))`.
std::string sexpr(const Expr& expression);

template <typename Arguments> std::string argumentsText(const Arguments& arguments) {
  std::string text;
  for (const Argument& argument : arguments) {
    text += " ";
    text += argument.name.empty() ? "" : std::string(argument.name) + "=";
    text += sexpr(*argument.value);
  }
  return text;
}

std::string listText(const NodeList<ExprPtr>& expressions) {
  std::string text;
  for (const ExprPtr& expression : expressions) {
    text += " " + sexpr(*expression);
  }
  return text;
}

std::string sexpr(const Expr& expression) {
  switch (expression.kind) {
  case ExprKind::Number:
    return fmt::format("{}", as<NumberExpr>(expression).value);
  case ExprKind::Bool:
    return as<BoolExpr>(expression).value ? "true" : "false";
  case ExprKind::String:
    return "\"" + std::string(as<StringExpr>(expression).value) + "\"";
  case ExprKind::Name:
    return std::string(as<NameExpr>(expression).name);
  case ExprKind::Unary: {
    const auto& unary = as<UnaryExpr>(expression);
    return fmt::format("({} {})", unary.op == UnaryOperator::Negate ? "-" : "!",
                       sexpr(*unary.operand));
  }
  case ExprKind::Binary: {
    const auto& binary = as<BinaryExpr>(expression);
    return fmt::format("({} {} {})", operatorSpelling(binary.op), sexpr(*binary.left),
                       sexpr(*binary.right));
  }
  case ExprKind::Call: {
    const auto& call = as<CallExpr>(expression);
    return "(" + std::string(call.callee) + argumentsText(call.arguments) + ")";
  }
  case ExprKind::Point:
    return "(point" + listText(as<PointExpr>(expression).components) + ")";
  case ExprKind::List: {
    std::string text = listText(as<ListExpr>(expression).elements);
    return "[" + (text.empty() ? "" : text.substr(1)) + "]";
  }
  case ExprKind::Range: {
    const auto& range = as<RangeExpr>(expression);
    return fmt::format("(.. {} {})", sexpr(*range.low), sexpr(*range.high));
  }
  case ExprKind::Index: {
    const auto& index = as<IndexExpr>(expression);
    return fmt::format("(index {} {})", sexpr(*index.base), sexpr(*index.index));
  }
  case ExprKind::Member: {
    const auto& member = as<MemberExpr>(expression);
    return fmt::format("(. {} {})", sexpr(*member.base), member.member);
  }
  case ExprKind::IfElse: {
    const auto& ifElse = as<IfElseExpr>(expression);
    return fmt::format("(if {} {} {})", sexpr(*ifElse.condition), sexpr(*ifElse.thenValue),
                       sexpr(*ifElse.elseValue));
  }
  case ExprKind::Error:
    return "<error>";
  }
  return "?";
}

class ParserTest : public ::testing::Test {
protected:
  const Module& parseText(std::string text) {
    FileId file = sources_.addFile("test.cdl", std::move(text));
    modules_.push_back(std::make_unique<Module>(parseFile(sources_, file, diagnostics_)));
    return *modules_.back();
  }

  // `text` parsed as the value of a constant, as an S-expression.
  std::string expression(const std::string& text) {
    const Module& module = parseText("const x = " + text);
    if (module.items.empty() || module.items[0]->kind != ItemKind::Const) {
      return "<no const>";
    }
    return sexpr(*as<ConstItem>(*module.items[0]).value);
  }

  // The statements of the one part in `body`'s `part p() { body }`.
  const NodeList<StmtPtr>& statements(const std::string& body) {
    const Module& module = parseText("part p() {\n" + body + "\n}\n");
    EXPECT_EQ(module.items.size(), 1u);
    EXPECT_EQ(module.items[0]->kind, ItemKind::Part);
    return as<PartItem>(*module.items[0]).body.statements;
  }

  std::vector<std::string> diagnosticNames() const {
    std::vector<std::string> names;
    for (const Diagnostic& diagnostic : diagnostics_.diagnostics()) {
      names.emplace_back(diagnosticName(diagnostic.kind));
    }
    return names;
  }

  bool clean() const { return diagnostics_.diagnostics().empty(); }

  std::string textOf(SourceSpan span) const { return std::string(sources_.text(span)); }

  SourceManager sources_;
  DiagnosticEngine diagnostics_{0};
  std::vector<std::unique_ptr<Module>> modules_;
};

using Names = std::vector<std::string>;

std::vector<StmtKind> kindsOf(const NodeList<StmtPtr>& statements) {
  std::vector<StmtKind> kinds;
  for (const StmtPtr& statement : statements) {
    kinds.push_back(statement->kind);
  }
  return kinds;
}

// ---------------------------------------------------------------- precedence

TEST_F(ParserTest, ArithmeticPrecedenceAndLeftAssociativity) {
  EXPECT_EQ(expression("1 + 2 * 3"), "(+ 1 (* 2 3))");
  EXPECT_EQ(expression("1 * 2 + 3"), "(+ (* 1 2) 3)");
  EXPECT_EQ(expression("1 - 2 - 3"), "(- (- 1 2) 3)");
  EXPECT_EQ(expression("8 / 4 / 2"), "(/ (/ 8 4) 2)");
  EXPECT_EQ(expression("a % b * c"), "(* (% a b) c)");
  EXPECT_EQ(expression("(1 + 2) * 3"), "(* (+ 1 2) 3)");
  EXPECT_TRUE(clean());
}

TEST_F(ParserTest, NestedListsKeepTheirOwnChildren) {
  EXPECT_EQ(expression("f(a, [1, (2, 3), g(4, [5, (6, 7, 8)]), []], 10, k = (9))"),
            "(f a [1 (point 2 3) (g 4 [5 (point 6 7 8)]) []] 10 k=9)");
  EXPECT_EQ(expression("[[[1], [2, 3]], ((4), 5)]"), "[[[1] [2 3]] (point 4 5)]");
  EXPECT_TRUE(clean());
}

TEST_F(ParserTest, AListLargerThanAnArenaBlockIsKept) {
  std::string elements = "0";
  for (int i = 1; i < 20000; ++i) {
    elements += fmt::format(", {}", i);
  }
  const Module& module = parseText("const x = [" + elements + "]\nconst y = [1, 2]\n");
  ASSERT_EQ(module.items.size(), 2u);
  const auto& list = as<ListExpr>(*as<ConstItem>(*module.items[0]).value);
  ASSERT_EQ(list.elements.size(), 20000u);
  EXPECT_EQ(as<NumberExpr>(*list.elements.back()).value, 19999);
  EXPECT_EQ(as<NumberExpr>(*list.elements[12345]).value, 12345);
  EXPECT_EQ(sexpr(*as<ConstItem>(*module.items[1]).value), "[1 2]");
  EXPECT_TRUE(clean());
}

TEST_F(ParserTest, PowerIsRightAssociativeAndBindsTighterThanUnaryMinus) {
  EXPECT_EQ(expression("-2^2"), "(- (^ 2 2))");
  EXPECT_EQ(expression("2^-1"), "(^ 2 (- 1))");
  EXPECT_EQ(expression("2^3^2"), "(^ 2 (^ 3 2))");
  EXPECT_EQ(expression("2*3^2"), "(* 2 (^ 3 2))");
  EXPECT_EQ(expression("-a*b"), "(* (- a) b)");
  EXPECT_EQ(expression("--a"), "(- (- a))");
  EXPECT_TRUE(clean());
}

TEST_F(ParserTest, LogicAndComparisons) {
  EXPECT_EQ(expression("a || b && c"), "(|| a (&& b c))");
  EXPECT_EQ(expression("a && b || c"), "(|| (&& a b) c)");
  EXPECT_EQ(expression("!a && b"), "(&& (! a) b)");
  EXPECT_EQ(expression("a + 1 < b * 2"), "(< (+ a 1) (* b 2))");
  EXPECT_EQ(expression("a < b && c >= d"), "(&& (< a b) (>= c d))");
  EXPECT_EQ(expression("a == b != c"), "(!= (== a b) c)");
  EXPECT_EQ(expression("a <= b"), "(<= a b)");
  EXPECT_EQ(expression("a > b"), "(> a b)");
  EXPECT_TRUE(clean());
}

TEST_F(ParserTest, RangesTakeWholeOperands) {
  EXPECT_EQ(expression("0 .. 2*pi"), "(.. 0 (* 2 pi))");
  EXPECT_EQ(expression("1..5"), "(.. 1 5)");
  EXPECT_EQ(expression("a + 1 .. b - 1"), "(.. (+ a 1) (- b 1))");
  EXPECT_TRUE(clean());
}

TEST_F(ParserTest, IfExpressions) {
  EXPECT_EQ(expression("if a < b then 1 else 2"), "(if (< a b) 1 2)");
  EXPECT_EQ(expression("if a then 1 else if b then 2 else 3"), "(if a 1 (if b 2 3))");
  EXPECT_EQ(expression("1 + (if a then 2 else 3)"), "(+ 1 (if a 2 3))");
  EXPECT_TRUE(clean());
}

TEST_F(ParserTest, AnIfExpressionNeedsBothValues) {
  EXPECT_EQ(expression("if a then 1"), "(if a 1 <error>)");
  EXPECT_EQ(diagnosticNames(), Names{"expected-token"});
}

// ---------------------------------------------------------------- primaries

TEST_F(ParserTest, LiteralsAndNames) {
  EXPECT_EQ(expression("12"), "12");
  EXPECT_EQ(expression("2.5mm"), "2.5");
  EXPECT_EQ(expression("true"), "true");
  EXPECT_EQ(expression("false"), "false");
  EXPECT_EQ(expression("\"text\""), "\"text\"");
  EXPECT_EQ(expression("depth"), "depth");
  EXPECT_TRUE(clean());
}

TEST_F(ParserTest, PointsAndParentheses) {
  EXPECT_EQ(expression("(1, 2)"), "(point 1 2)");
  EXPECT_EQ(expression("(1, 2, 3)"), "(point 1 2 3)");
  EXPECT_EQ(expression("(x)"), "x");
  EXPECT_EQ(expression("((1))"), "1");
  EXPECT_EQ(expression("(-1, a + b)"), "(point (- 1) (+ a b))");
  EXPECT_EQ(expression("2 * (1, 2)"), "(* 2 (point 1 2))");
  EXPECT_TRUE(clean());
}

TEST_F(ParserTest, APointHasTwoOrThreeComponents) {
  EXPECT_EQ(expression("(1, 2, 3, 4)"), "(point 1 2 3 4)");
  EXPECT_EQ(diagnosticNames(), Names{"point-components"});
}

TEST_F(ParserTest, Lists) {
  EXPECT_EQ(expression("[]"), "[]");
  EXPECT_EQ(expression("[1, 2, 3]"), "[1 2 3]");
  EXPECT_EQ(expression("[(0, 0), (10, 0)]"), "[(point 0 0) (point 10 0)]");
  EXPECT_EQ(expression("[1, 2,]"), "[1 2]");
  EXPECT_EQ(expression("[[1], []]"), "[[1] []]");
  EXPECT_TRUE(clean());
}

TEST_F(ParserTest, IndexingAndMembers) {
  EXPECT_EQ(expression("L[0]"), "(index L 0)");
  EXPECT_EQ(expression("L[i + 1].x"), "(. (index L (+ i 1)) x)");
  EXPECT_EQ(expression("p.x + p.y"), "(+ (. p x) (. p y))");
  EXPECT_EQ(expression("-p.z"), "(- (. p z))");
  EXPECT_EQ(expression("M[1][2]"), "(index (index M 1) 2)");
  EXPECT_TRUE(clean());
}

TEST_F(ParserTest, CallsWithPositionalAndNamedArguments) {
  EXPECT_EQ(expression("f()"), "(f)");
  EXPECT_EQ(expression("sin(t)"), "(sin t)");
  EXPECT_EQ(expression("atan2(y, x)"), "(atan2 y x)");
  EXPECT_EQ(expression("nurbs(order=4, points=P)"), "(nurbs order=4 points=P)");
  EXPECT_EQ(expression("line((0, 0), to=(1, 1))"), "(line (point 0 0) to=(point 1 1))");
  EXPECT_EQ(expression("polar(r = 1 + t, t = 0 .. 2*pi)"), "(polar r=(+ 1 t) t=(.. 0 (* 2 pi)))");
  EXPECT_EQ(expression("f(g(1), [2])"), "(f (g 1) [2])");
  EXPECT_TRUE(clean());
}

TEST_F(ParserTest, APositionalArgumentCannotFollowANamedOne) {
  expression("line(from=(0, 0), (1, 1))");
  EXPECT_EQ(diagnosticNames(), Names{"positional-after-named"});
}

TEST_F(ParserTest, CallSpansCoverTheirArguments) {
  const Module& module = parseText("const x = nurbs(order=4, points=P) + 1");
  const auto& sum = as<BinaryExpr>(*as<ConstItem>(*module.items[0]).value);
  EXPECT_EQ(textOf(sum.left->span), "nurbs(order=4, points=P)");
  EXPECT_EQ(textOf(as<CallExpr>(*sum.left).calleeSpan), "nurbs");
  EXPECT_EQ(textOf(sum.operatorSpan), "+");
  EXPECT_EQ(textOf(sum.span), "nurbs(order=4, points=P) + 1");
}

// ---------------------------------------------------------------- items

TEST_F(ParserTest, EveryItemKind) {
  const Module& module = parseText("import \"std/curves\"\n"
                                   "const clearance = 5\n"
                                   "fn lobes(k, t) = 1 + 0.2*cos(k*t)\n"
                                   "part cam(depth = 3, step = 0.5) { }\n"
                                   "part plain { }\n");
  EXPECT_TRUE(clean());
  ASSERT_EQ(module.items.size(), 5u);

  const auto& import = as<ImportItem>(*module.items[0]);
  EXPECT_EQ(import.kind, ItemKind::Import);
  EXPECT_EQ(import.path, "std/curves");

  const auto& constant = as<ConstItem>(*module.items[1]);
  EXPECT_EQ(constant.kind, ItemKind::Const);
  EXPECT_EQ(constant.name, "clearance");
  EXPECT_EQ(sexpr(*constant.value), "5");

  const auto& function = as<FnItem>(*module.items[2]);
  EXPECT_EQ(function.kind, ItemKind::Fn);
  EXPECT_EQ(function.name, "lobes");
  ASSERT_EQ(function.parameters.size(), 2u);
  EXPECT_EQ(function.parameters[1].name, "t");
  EXPECT_EQ(function.parameters[1].defaultValue, nullptr);
  EXPECT_EQ(sexpr(*function.body), "(+ 1 (* 0.2 (cos (* k t))))");

  const auto& part = as<PartItem>(*module.items[3]);
  EXPECT_EQ(part.kind, ItemKind::Part);
  EXPECT_EQ(part.name, "cam");
  ASSERT_EQ(part.parameters.size(), 2u);
  EXPECT_EQ(part.parameters[0].name, "depth");
  EXPECT_EQ(sexpr(*part.parameters[1].defaultValue), "0.5");
  EXPECT_EQ(textOf(part.nameSpan), "cam");

  EXPECT_TRUE(as<PartItem>(*module.items[4]).parameters.empty());
}

// ---------------------------------------------------------------- statements

TEST_F(ParserTest, EveryStatementKind) {
  const auto& body = statements("units mm\n"
                                "tool 1 diameter=10 spindle=3000 feed=300\n"
                                "feed 250\n"
                                "spindle 8000\n"
                                "safe z=5\n"
                                "let r = 20\n"
                                "curve line((0, 0), (r, 0))\n"
                                "for i in 1 .. 3 { curve line((0, i), (10, i)) }\n"
                                "if r > 10 { feed 100 } else { feed 200 }");
  EXPECT_TRUE(clean());
  EXPECT_EQ(kindsOf(body), (std::vector<StmtKind>{StmtKind::Units, StmtKind::Tool, StmtKind::Feed,
                                                  StmtKind::Spindle, StmtKind::Safe, StmtKind::Let,
                                                  StmtKind::Cut, StmtKind::For, StmtKind::If}));
  ASSERT_EQ(body.size(), 9u);

  EXPECT_EQ(as<UnitsStmt>(*body[0]).unit, "mm");

  const auto& tool = as<ToolStmt>(*body[1]);
  EXPECT_EQ(sexpr(*tool.number), "1");
  EXPECT_EQ(argumentsText(tool.settings), " diameter=10 spindle=3000 feed=300");

  EXPECT_EQ(sexpr(*as<ValueStmt>(*body[2]).value), "250");
  EXPECT_EQ(sexpr(*as<ValueStmt>(*body[3]).value), "8000");
  EXPECT_EQ(argumentsText(as<SafeStmt>(*body[4]).settings), " z=5");

  const auto& let = as<LetStmt>(*body[5]);
  EXPECT_EQ(let.name, "r");
  EXPECT_EQ(sexpr(*let.value), "20");

  const auto& cut = as<CutStmt>(*body[6]);
  EXPECT_EQ(sexpr(*cut.curve), "(line (point 0 0) (point r 0))");
  EXPECT_TRUE(cut.modifiers.empty());

  const auto& loop = as<ForStmt>(*body[7]);
  EXPECT_EQ(loop.variable, "i");
  EXPECT_EQ(sexpr(*loop.range), "(.. 1 3)");
  EXPECT_EQ(kindsOf(loop.body.statements), std::vector<StmtKind>{StmtKind::Cut});

  const auto& branch = as<IfStmt>(*body[8]);
  EXPECT_EQ(sexpr(*branch.condition), "(> r 10)");
  EXPECT_TRUE(branch.hasElse);
  EXPECT_EQ(kindsOf(branch.thenBlock.statements), std::vector<StmtKind>{StmtKind::Feed});
  EXPECT_EQ(kindsOf(branch.elseBlock.statements), std::vector<StmtKind>{StmtKind::Feed});
}

TEST_F(ParserTest, UnitsInch) {
  const auto& body = statements("units inch");
  ASSERT_EQ(body.size(), 1u);
  EXPECT_EQ(as<UnitsStmt>(*body[0]).unit, "inch");
  EXPECT_TRUE(clean());
}

TEST_F(ParserTest, ElseIfBecomesAnElseBlockHoldingAnIf) {
  const auto& body = statements("if a { feed 1 } else if b { feed 2 } else { feed 3 }");
  EXPECT_TRUE(clean());
  ASSERT_EQ(body.size(), 1u);
  const auto& outer = as<IfStmt>(*body[0]);
  ASSERT_EQ(outer.elseBlock.statements.size(), 1u);
  const auto& inner = as<IfStmt>(*outer.elseBlock.statements[0]);
  EXPECT_EQ(inner.kind, StmtKind::If);
  EXPECT_EQ(sexpr(*inner.condition), "b");
  EXPECT_TRUE(inner.hasElse);
}

TEST_F(ParserTest, IfWithoutElse) {
  const auto& body = statements("if a { feed 1 }\nfeed 2");
  EXPECT_TRUE(clean());
  ASSERT_EQ(body.size(), 2u);
  EXPECT_FALSE(as<IfStmt>(*body[0]).hasElse);
}

TEST_F(ParserTest, ContextualWordsAreNamesWhereANameFits) {
  const auto& body = statements("let depth = 3\nlet feed2 = depth\ncurve c sweep depth=depth");
  EXPECT_TRUE(clean());
  ASSERT_EQ(body.size(), 3u);
  EXPECT_EQ(as<LetStmt>(*body[0]).name, "depth");
  EXPECT_EQ(sexpr(*as<LetStmt>(*body[1]).value), "depth");
}

TEST_F(ParserTest, SemicolonsSeparateStatementsOnOneLine) {
  const auto& body = statements("feed 100; spindle 2000");
  EXPECT_TRUE(clean());
  std::vector<StmtKind> kinds = kindsOf(body);
  EXPECT_EQ(std::count(kinds.begin(), kinds.end(), StmtKind::Feed), 1);
  EXPECT_EQ(std::count(kinds.begin(), kinds.end(), StmtKind::Spindle), 1);
}

// ---------------------------------------------------------------- modifiers

std::string modifiersText(const CutStmt& cut) {
  std::string text;
  for (const Modifier& modifier : cut.modifiers) {
    text += " " + std::string(modifier.name) + (modifier.value ? "=" + sexpr(*modifier.value) : "");
  }
  return text;
}

TEST_F(ParserTest, CutModifiersIncludingABareSweep) {
  const auto& body = statements(
      "curve nurbs(order=4, points=P) sweep depth=depth step=1 tolerance=0.01 method=nurbs");
  EXPECT_TRUE(clean());
  ASSERT_EQ(body.size(), 1u);
  const auto& cut = as<CutStmt>(*body[0]);
  EXPECT_EQ(modifiersText(cut), " sweep depth=depth step=1 tolerance=0.01 method=nurbs");
  EXPECT_EQ(cut.modifiers[0].value, nullptr);
  EXPECT_EQ(textOf(cut.modifiers[1].span()), "depth=depth");
}

TEST_F(ParserTest, AModifierListMayContinueOnTheNextLine) {
  const auto& body = statements("curve c sweep depth=3 step=1\n"
                                "  tolerance=0.01 entry=ramp\n"
                                "curve d");
  EXPECT_TRUE(clean());
  ASSERT_EQ(body.size(), 2u);
  EXPECT_EQ(modifiersText(as<CutStmt>(*body[0])),
            " sweep depth=3 step=1 tolerance=0.01 entry=ramp");
  EXPECT_EQ(sexpr(*as<CutStmt>(*body[1]).curve), "d");
}

TEST_F(ParserTest, ANewLineEndsTheModifiersUnlessAModifierContinuesThem) {
  const auto& body = statements("curve c sweep\n"
                                "feed 100\n"
                                "curve d\n"
                                "let x = 1");
  EXPECT_TRUE(clean());
  EXPECT_EQ(kindsOf(body),
            (std::vector<StmtKind>{StmtKind::Cut, StmtKind::Feed, StmtKind::Cut, StmtKind::Let}));
  EXPECT_EQ(modifiersText(as<CutStmt>(*body[0])), " sweep");
  EXPECT_EQ(modifiersText(as<CutStmt>(*body[2])), "");
}

TEST_F(ParserTest, ASettingStatementWordEndsTheModifiersOnTheSameLine) {
  const auto& body = statements("curve c sweep feed 100");
  EXPECT_EQ(kindsOf(body), (std::vector<StmtKind>{StmtKind::Cut, StmtKind::Feed}));
}

// ---------------------------------------------------------------- recovery

TEST_F(ParserTest, ABrokenLetGivesOneMessageAndTheNextStatementIsKept) {
  const auto& body = statements("let a = (1 +\n"
                                "curve line((0, 0), (1, 1))");
  EXPECT_EQ(diagnosticNames(), Names{"expected-expression"});
  ASSERT_EQ(body.size(), 2u);
  EXPECT_EQ(body[0]->kind, StmtKind::Let);
  ASSERT_EQ(body[1]->kind, StmtKind::Cut);
  EXPECT_EQ(sexpr(*as<CutStmt>(*body[1]).curve), "(line (point 0 0) (point 1 1))");
}

TEST_F(ParserTest, ATypoInAStatementGivesOneMessage) {
  const auto& body = statements("tool 1 diameter=6 feed=200\n"
                                "curv line((0, 0), (1, 1)) sweep depth=3\n"
                                "safe z=5\n"
                                "curve line((0, 0), (2, 2))");
  EXPECT_EQ(diagnosticNames(), Names{"expected-statement"});
  EXPECT_EQ(kindsOf(body), (std::vector<StmtKind>{StmtKind::Tool, StmtKind::Error, StmtKind::Safe,
                                                  StmtKind::Cut}));
}

TEST_F(ParserTest, AnAssignmentWithoutLetIsOneMessageWithAHint) {
  const auto& body = statements("x = 3\ncurve c");
  ASSERT_EQ(diagnosticNames(), Names{"expected-statement"});
  EXPECT_NE(diagnostics_.diagnostics().front().message.find("let x = ..."), std::string::npos);
  EXPECT_EQ(body.back()->kind, StmtKind::Cut);
}

TEST_F(ParserTest, AnUnclosedPointGivesOneMessageWithANote) {
  const auto& body = statements("let a = (1, 2\n"
                                "curve line((0, 0), a)");
  EXPECT_EQ(diagnosticNames(), Names{"expected-token"});
  ASSERT_EQ(diagnostics_.diagnostics().front().notes.size(), 1u);
  EXPECT_EQ(body.back()->kind, StmtKind::Cut);
}

TEST_F(ParserTest, AMissingClosingBraceBeforeTheNextPart) {
  const Module& module = parseText("part a() {\n"
                                   "  curve line((0, 0), (1, 1))\n"
                                   "part b() {\n"
                                   "  curve line((0, 0), (2, 2))\n"
                                   "}\n");
  EXPECT_EQ(diagnosticNames(), Names{"expected-token"});
  ASSERT_EQ(module.items.size(), 2u);
  EXPECT_EQ(as<PartItem>(*module.items[0]).body.statements.size(), 1u);
  EXPECT_EQ(as<PartItem>(*module.items[1]).name, "b");
  EXPECT_EQ(as<PartItem>(*module.items[1]).body.statements.size(), 1u);
}

TEST_F(ParserTest, AMissingClosingBraceAtTheEndOfTheFile) {
  const Module& module = parseText("part a() {\n  curve c\n");
  EXPECT_EQ(diagnosticNames(), Names{"expected-token"});
  ASSERT_EQ(module.items.size(), 1u);
  EXPECT_EQ(as<PartItem>(*module.items[0]).body.statements.size(), 1u);
}

TEST_F(ParserTest, AStrayItemGivesOneMessageAndTheNextItemIsKept) {
  const Module& module = parseText("prat p() { curve c }\n"
                                   "part q() { curve d }\n");
  EXPECT_EQ(diagnosticNames(), Names{"expected-item"});
  ASSERT_FALSE(module.items.empty());
  EXPECT_EQ(module.items.front()->kind, ItemKind::Error);
  EXPECT_EQ(module.items.back()->kind, ItemKind::Part);
  EXPECT_EQ(as<PartItem>(*module.items.back()).name, "q");
}

TEST_F(ParserTest, AStatementOutsideAPartSaysWhereItBelongs) {
  parseText("curve c\npart p() { }\n");
  ASSERT_EQ(diagnosticNames(), Names{"expected-item"});
  EXPECT_NE(diagnostics_.diagnostics().front().message.find("inside a 'part"), std::string::npos);
}

TEST_F(ParserTest, AKeywordIsNotAName) {
  parseText("part p() { let for = 3 }");
  EXPECT_EQ(diagnosticNames(), Names{"expected-identifier"});
}

TEST_F(ParserTest, UnknownUnits) {
  const auto& body = statements("units cm\ncurve c");
  EXPECT_EQ(diagnosticNames(), Names{"unknown-units"});
  EXPECT_EQ(body.back()->kind, StmtKind::Cut);
}

// ---------------------------------------------------------------- machine set-up

TEST_F(ParserTest, OriginTakesG54ToG59) {
  const auto& body = statements("origin G54\norigin G59\ncurve c");
  EXPECT_TRUE(clean());
  ASSERT_EQ(kindsOf(body),
            (std::vector<StmtKind>{StmtKind::Origin, StmtKind::Origin, StmtKind::Cut}));
  const auto& first = as<OriginStmt>(*body[0]);
  EXPECT_EQ(first.group, 54);
  EXPECT_EQ(first.extended, 0);
  EXPECT_EQ(textOf(first.offsetSpan), "G54");
  EXPECT_FALSE(first.extendedSpan.valid());
  EXPECT_EQ(textOf(first.span), "origin G54");
  EXPECT_EQ(as<OriginStmt>(*body[1]).group, 59);
}

TEST_F(ParserTest, OriginTakesTheExtendedOffsetsOfG54Point1) {
  const auto& body = statements("origin G54.1 P1\norigin G54.1 P300\norigin G54.1 P07");
  EXPECT_TRUE(clean());
  ASSERT_EQ(body.size(), 3u);
  const auto& first = as<OriginStmt>(*body[0]);
  EXPECT_EQ(first.group, 54);
  EXPECT_EQ(first.extended, 1);
  EXPECT_EQ(textOf(first.offsetSpan), "G54.1");
  EXPECT_EQ(textOf(first.extendedSpan), "P1");
  EXPECT_EQ(textOf(first.span), "origin G54.1 P1");
  EXPECT_EQ(as<OriginStmt>(*body[1]).extended, 300);
  EXPECT_EQ(as<OriginStmt>(*body[2]).extended, 7);
}

TEST_F(ParserTest, OriginStatementsInLoopsAndBranches) {
  const auto& body = statements("for i in 1 .. 2 { origin G55 }\n"
                                "if true { coolant mist } else { origin G54.1 P2 }");
  EXPECT_TRUE(clean());
  ASSERT_EQ(body.size(), 2u);
  const auto& loop = as<ForStmt>(*body[0]);
  ASSERT_EQ(loop.body.statements.size(), 1u);
  EXPECT_EQ(as<OriginStmt>(*loop.body.statements[0]).group, 55);
  const auto& branch = as<IfStmt>(*body[1]);
  EXPECT_EQ(as<CoolantStmt>(*branch.thenBlock.statements[0]).mode, CoolantMode::Mist);
  EXPECT_EQ(as<OriginStmt>(*branch.elseBlock.statements[0]).extended, 2);
}

// Each bad origin: one message of `name`, at `at`, and the next statement kept.
struct BadOrigin {
  const char* statement;
  const char* name;
  const char* at;
};

TEST_F(ParserTest, ABadOriginGivesOneMessageAtTheWrongWord) {
  for (const BadOrigin& bad : {
           BadOrigin{"origin G60", "invalid-choice", "G60"},
           BadOrigin{"origin G53", "invalid-choice", "G53"},
           BadOrigin{"origin g54", "invalid-choice", "g54"},
           BadOrigin{"origin G55.1 P1", "invalid-choice", "G55.1"},
           BadOrigin{"origin G54.2 P1", "invalid-choice", "G54.2"},
           BadOrigin{"origin G54.10 P1", "invalid-choice", "G54.10"},
           BadOrigin{"origin G54. P1", "invalid-choice", "G54."},
           BadOrigin{"origin G54.1 P0", "register-out-of-range", "P0"},
           BadOrigin{"origin G54.1 P301", "register-out-of-range", "P301"},
           BadOrigin{"origin G54.1 P99999", "expected-token", "P99999"},
           BadOrigin{"origin G54.1 P", "expected-token", "P"},
           BadOrigin{"origin G54.1 3", "expected-token", "3"},
           BadOrigin{"origin G54.1", "expected-token", "G54.1"},
           BadOrigin{"origin", "expected-identifier", "origin"},
           BadOrigin{"origin 54", "expected-identifier", "54"},
           BadOrigin{"origin G54.1P3", "unknown-unit-suffix", "P3"},
       }) {
    diagnostics_.clear();
    const auto& body = statements(std::string(bad.statement) + "\ncurve c");
    ASSERT_EQ(diagnosticNames(), Names{bad.name}) << bad.statement;
    EXPECT_EQ(textOf(diagnostics_.diagnostics().front().span), bad.at) << bad.statement;
    EXPECT_EQ(kindsOf(body), (std::vector<StmtKind>{StmtKind::Error, StmtKind::Cut}))
        << bad.statement;
  }
}

TEST_F(ParserTest, TheMessagesOfABadOriginSayWhatIsAllowed) {
  statements("origin G60");
  ASSERT_EQ(diagnostics_.diagnostics().size(), 1u);
  EXPECT_EQ(diagnostics_.diagnostics().front().message,
            "'G60' is not a work offset; 'origin' takes G54 .. G59, or G54.1 P1 .. P300");
  diagnostics_.clear();
  statements("origin G54.1 P301");
  ASSERT_EQ(diagnostics_.diagnostics().size(), 1u);
  EXPECT_EQ(diagnostics_.diagnostics().front().message,
            "there is no extended work offset P301; G54.1 takes P1 .. P300");
}

TEST_F(ParserTest, CoolantModes) {
  const auto& body = statements("coolant flood\ncoolant mist\ncoolant through\ncoolant off");
  EXPECT_TRUE(clean());
  ASSERT_EQ(body.size(), 4u);
  std::vector<CoolantMode> modes;
  for (const StmtPtr& statement : body) {
    ASSERT_EQ(statement->kind, StmtKind::Coolant);
    modes.push_back(as<CoolantStmt>(*statement).mode);
  }
  EXPECT_EQ(modes, (std::vector<CoolantMode>{CoolantMode::Flood, CoolantMode::Mist,
                                             CoolantMode::Through, CoolantMode::Off}));
  EXPECT_EQ(textOf(as<CoolantStmt>(*body[2]).modeSpan), "through");
  EXPECT_EQ(textOf(body[2]->span), "coolant through");
}

TEST_F(ParserTest, ABadCoolantGivesOneMessage) {
  const auto& unknown = statements("coolant on\ncurve c");
  ASSERT_EQ(diagnosticNames(), Names{"invalid-choice"});
  EXPECT_EQ(textOf(diagnostics_.diagnostics().front().span), "on");
  EXPECT_NE(diagnostics_.diagnostics().front().message.find("flood, mist, through or off"),
            std::string::npos);
  EXPECT_EQ(kindsOf(unknown), (std::vector<StmtKind>{StmtKind::Error, StmtKind::Cut}));

  diagnostics_.clear();
  const auto& alone = statements("coolant\ncurve c");
  ASSERT_EQ(diagnosticNames(), Names{"expected-identifier"});
  // At the word itself, not at the next line's `curve`.
  EXPECT_EQ(textOf(diagnostics_.diagnostics().front().span), "coolant");
  EXPECT_EQ(kindsOf(alone), (std::vector<StmtKind>{StmtKind::Error, StmtKind::Cut}));
}

TEST_F(ParserTest, SetUpWordsAreNamesWhereANameFits) {
  const auto& body = statements("let origin = (0, 0)\nlet coolant = 1\ncurve line(origin, "
                                "(coolant, 0))");
  EXPECT_TRUE(clean());
  EXPECT_EQ(kindsOf(body), (std::vector<StmtKind>{StmtKind::Let, StmtKind::Let, StmtKind::Cut}));
}

TEST_F(ParserTest, ToolLengthAndRadiusMayContinueOnTheNextLine) {
  const auto& body = statements("tool 2 diameter=6\n  length=12\n  radius=22\ncurve c");
  EXPECT_TRUE(clean());
  ASSERT_EQ(kindsOf(body), (std::vector<StmtKind>{StmtKind::Tool, StmtKind::Cut}));
  EXPECT_EQ(argumentsText(as<ToolStmt>(*body[0]).settings), " diameter=6 length=12 radius=22");
}

TEST_F(ParserTest, ALexerErrorIsNotReportedAgainByTheParser) {
  const auto& body = statements("let a = 3 @ 4\ncurve c");
  EXPECT_EQ(diagnosticNames(), Names{"unexpected-character"});
  EXPECT_EQ(body.back()->kind, StmtKind::Cut);
}

TEST_F(ParserTest, ErrorsLeaveErrorNodes) {
  EXPECT_EQ(expression("1 + )"), "(+ 1 <error>)");
  EXPECT_EQ(diagnosticNames(), Names{"expected-expression"});
}

// ---------------------------------------------------------------- nesting

TEST_F(ParserTest, DeeplyNestedParenthesesAreAnErrorNotACrash) {
  std::string text = "const x = " + std::string(100000, '(') + "1" + std::string(100000, ')');
  parseText(text);
  EXPECT_EQ(diagnosticNames(), Names{"nesting-too-deep"});
}

TEST_F(ParserTest, DeeplyNestedUnaryOperatorsAreAnErrorNotACrash) {
  parseText("const x = " + std::string(100000, '-') + "1");
  parseText("const y = " + std::string(100000, '!') + "true");
  EXPECT_EQ(diagnosticNames(), (Names{"nesting-too-deep", "nesting-too-deep"}));
}

TEST_F(ParserTest, LongPowerChainsAreAnErrorNotACrash) {
  std::string powers = "const z = 2";
  for (int i = 0; i < 50000; ++i) {
    powers += "^2";
  }
  parseText(powers);
  EXPECT_EQ(diagnosticNames(), Names{"nesting-too-deep"});
}

TEST_F(ParserTest, LongOperatorChainsAreAnErrorNotACrash) {
  std::string sum = "const s = 1";
  for (int i = 0; i < 3 * maximumChainLength; ++i) {
    sum += " + 1";
  }
  parseText(sum);
  EXPECT_EQ(diagnosticNames(), Names{"nesting-too-deep"});
}

TEST_F(ParserTest, DeeplyNestedListsAndBlocksAreAnErrorNotACrash) {
  parseText("const x = " + std::string(100000, '[') + std::string(100000, ']'));
  std::string blocks = "part p() {\n";
  for (int i = 0; i < 20000; ++i) {
    blocks += "if true {\n";
  }
  for (int i = 0; i < 20000; ++i) {
    blocks += "}\n";
  }
  parseText(blocks + "}\n");
  std::vector<std::string> names = diagnosticNames();
  ASSERT_FALSE(names.empty());
  for (const std::string& name : names) {
    EXPECT_EQ(name, "nesting-too-deep");
  }
}

TEST_F(ParserTest, ModerateNestingIsFine) {
  int depth = maximumNestingDepth / 4;
  parseText("const x = " + std::string(depth, '(') + "1" + std::string(depth, ')'));
  EXPECT_TRUE(clean());
}

// ---------------------------------------------------------------- the dump

TEST_F(ParserTest, TheTreeDumpOfAnUncheckedTreeShowsNoTypes) {
  const Module& module = parseText("part p(d = 2) {\n  curve line((0, 0), (d, 0)) sweep\n}\n");
  EXPECT_EQ(dumpAst(module, sources_), "Module test.cdl\n"
                                       "  Part 1:1 p\n"
                                       "    Parameter 1:8 d\n"
                                       "      Number 1:12 2\n"
                                       "    Body 1:15\n"
                                       "      Cut 2:3\n"
                                       "        Call 2:9 line\n"
                                       "          Point 2:14\n"
                                       "            Number 2:15 0\n"
                                       "            Number 2:18 0\n"
                                       "          Point 2:22\n"
                                       "            Name 2:23 d\n"
                                       "            Number 2:26 0\n"
                                       "        Modifier 2:30 sweep\n");
}

} // namespace
} // namespace cncc::frontend
