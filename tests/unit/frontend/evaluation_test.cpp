// Unit tests of what makes the front end fast without changing what it
// finds: curves sampled once per call and values, the fast path for
// numbers, and tokens that view the source.
#include "cncc/frontend/lexer.h"
#include "cncc/frontend/sema.h"

#include "checked_source.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace cncc::frontend {
namespace {

using ::testing::ElementsAre;

using test_support::check;
using test_support::Checked;
using test_support::part;

TEST(EvaluationTest, ACurveCalledAgainWithOtherValuesIsSampledAgain) {
  // The first three iterations make the same curve; the fourth one's
  // radius is undefined past t = 0.5.
  auto checked = check("fn pocket(s) = polar(r = sqrt(s - t), t = 0 .. 1)\n" +
                       part("  for i in 0 .. 3 {\n"
                            "    curve pocket(if i < 3 then 2 else 0.5)\n  }"));
  EXPECT_THAT(checked->names(), ElementsAre("non-finite-value"));
}

TEST(EvaluationTest, NegativeZeroIsNotTheSameValueAsZero) {
  // atan2(0, -1) is pi but atan2(-0, -1) is -pi: only the second curve
  // divides by zero.
  auto checked = check("fn f(s) = polar(r = 1 / (atan2(s, -1) + pi), t = 0 .. 1)\n" +
                       part("  curve f(0)\n  curve f(0)\n  curve f(-0)"));
  EXPECT_THAT(checked->names(), ElementsAre("division-by-zero"));
}

TEST(EvaluationTest, TheSameCurveReportsItsProblemOnce) {
  auto checked = check("fn pocket(s) = polar(r = sqrt(s - t), t = 0 .. 1)\n" +
                       part("  for i in 0 .. 3 {\n    curve pocket(0.5)\n  }"));
  EXPECT_THAT(checked->names(), ElementsAre("non-finite-value"));
}

TEST(EvaluationTest, NumbersThroughFunctionsMatchTheOrdinaryArithmetic) {
  auto checked =
      check("fn f(a, b) = a*a - b/3 + 2^a\nconst c = f(b = 2, a = 1.5) + atan2(x = 1, y = 2)\n" +
            part("  curve line((0, 0), (c, 1))"));
  ASSERT_THAT(checked->names(), ElementsAre());
  const Declaration* constant = checked->find("c");
  ASSERT_NE(constant, nullptr);
  ASSERT_TRUE(constant->value.has_value());
  EXPECT_EQ(constant->value->number,
            1.5 * 1.5 + -1 * (2.0 / 3) + std::pow(2.0, 1.5) + std::atan2(2, 1));
}

TEST(EvaluationTest, TheLogarithmIsTheOneTheIrComputes) {
  // std::log, as the IR's interpreter and the JIT call it; ln(0) (-inf)
  // and ln(-1) (NaN) are no numbers for a part.
  auto checked = check("const z = ln(0)\nconst n = ln(-1)\nconst e = ln(2.5)\n" +
                       part("  curve line((0, 0), (e, 1))"));
  EXPECT_THAT(checked->names(), ElementsAre("non-finite-value", "non-finite-value"));
  const Declaration* positive = checked->find("e");
  ASSERT_TRUE(positive && positive->value);
  EXPECT_EQ(positive->value->number, std::log(2.5));
}

TEST(EvaluationTest, ACurveConstructorBindsNamedArgumentsInAnyOrder) {
  // Named arguments out of order, alone and after a positional one.
  auto checked = check("const a = arc(to = 1, center = (3, 4), radius = 2, from = 0.5)\n"
                       "const b = translate(line((0, 0), (1, 0)), dy = 3, dx = 2)\n" +
                       part("  curve a\n  curve b"));
  ASSERT_THAT(checked->names(), ElementsAre());
  const Declaration* arc = checked->find("a");
  ASSERT_TRUE(arc != nullptr && arc->value && arc->value->curve);
  EXPECT_EQ(arc->value->curve->center[0], 3);
  EXPECT_EQ(arc->value->curve->center[1], 4);
  EXPECT_EQ(arc->value->curve->arcRadius, 2);
  EXPECT_EQ(arc->value->curve->startAngle, 0.5);
  EXPECT_EQ(arc->value->curve->endAngle, 1);
  const Declaration* moved = checked->find("b");
  ASSERT_TRUE(moved != nullptr && moved->value && moved->value->curve);
  EXPECT_EQ(moved->value->curve->kind, CurveKind::Translate);
  EXPECT_EQ(moved->value->curve->dx, 2);
  EXPECT_EQ(moved->value->curve->dy, 3);
  ASSERT_EQ(moved->value->curve->pieces.size(), 1u);
  EXPECT_EQ(moved->value->curve->pieces.front()->kind, CurveKind::Line);
}

TEST(EvaluationTest, ABlockWithMoreLetsThanItsFrameHoldsFindsEachOne) {
  // The later lets live past the frame's own room; `f` is 0 only when each
  // let before it has its value.
  auto checked = check(part("  let a = 1\n  let b = a + 1\n  let c = b + 1\n  let d = c + 1\n"
                            "  let e = d + 1\n  let f = e - 5\n"
                            "  curve line((0, 0), (1 / f, a + e))"));
  EXPECT_THAT(checked->names(), ElementsAre("division-by-zero"));
  const Declaration* e = checked->find("e");
  ASSERT_NE(e, nullptr);
  ASSERT_TRUE(e->value.has_value());
  EXPECT_EQ(e->value->number, 5);
}

TEST(EvaluationTest, AFunctionWithManyParametersBindsEachOne) {
  // Six parameters: more than a frame holds in itself, and named ones in
  // another order than declared.
  auto checked = check("fn f(a, b, c, d, e, g) = line((a, b), (c + d, e / g))\n" +
                       part("  curve f(1, 2, 3, g = 0, e = 4, d = 5)"));
  EXPECT_THAT(checked->names(), ElementsAre("division-by-zero"));
}

TEST(EvaluationTest, NumbersOffTheFastPathAreNumbersAndAPointIsNot) {
  // A coordinate given by `if` and a point added up are evaluated the
  // ordinary way; only the point given as a radius is a mismatch.
  auto checked = check("fn f(k) = line((0, 0), (if k > 1 then 1 else 2, 1))\n" +
                       part("  let r = (1, 2) + (3, 4)\n  curve line((0, 0), r)\n"
                            "  curve f(2)\n  curve arc(center=(0, 0), radius=r, from=0, to=1)"));
  EXPECT_THAT(checked->names(), ElementsAre("type-mismatch"));
}

TEST(EvaluationTest, AFastPathProblemIsReportedByTheOrdinaryPath) {
  // Every number but one: the division by zero inside the fn still gets
  // its message and the note for the call.
  auto checked = check("fn f(a) = 1 / (a - 2)\n" + part("  curve line((0, 0), (f(2), 1))"));
  ASSERT_THAT(checked->names(), ElementsAre("division-by-zero"));
  EXPECT_EQ(checked->diagnostics.diagnostics().front().notes.size(), 1u);
}

TEST(EvaluationTest, EscapedStringsStayValidWhenTheFileIsLexedAgain) {
  SourceManager sources;
  FileId file = sources.addFile("test.cdl", R"(import "a\"b" "plain")");
  DiagnosticEngine diagnostics;
  std::vector<Token> first = lex(sources, file, diagnostics);
  std::vector<Token> second = lex(sources, file, diagnostics);
  ASSERT_EQ(first.size(), 4u);
  EXPECT_EQ(first[1].text, "a\"b");
  EXPECT_EQ(first[2].text, "plain");
  EXPECT_EQ(second[1].text, "a\"b");
  EXPECT_EQ(first[1].text.data(), second[1].text.data()); // one copy, kept by the file
}

} // namespace
} // namespace cncc::frontend
