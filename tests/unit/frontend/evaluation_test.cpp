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
