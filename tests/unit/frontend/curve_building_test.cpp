// Unit tests of building curve values: the samples of polar and param
// curves (evaluated at once when every one is a finite number, one by one
// when some is not), lists written out in a call, and the binding of a
// builtin's arguments.
#include "cncc/frontend/sema.h"

#include "checked_source.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace cncc::frontend {
namespace {

using ::testing::ElementsAre;

using test_support::check;
using test_support::part;

std::vector<std::string> namesOf(const std::string& body, const std::string& items = "") {
  return check(items + part(body))->names();
}

TEST(CurveBuildingTest, ASampleThatDividesByZeroIsReportedWithItsCall) {
  // t = 0.5 is the ninth of the 17 samples of 0 .. 1.
  auto checked = check("fn f(a) = polar(r = 1 / (t - a), t = 0 .. 1)\n" + part("  curve f(0.5)"));
  ASSERT_THAT(checked->names(), ElementsAre("division-by-zero"));
  EXPECT_EQ(checked->diagnostics.diagnostics().front().notes.size(), 1u);
  EXPECT_THAT(namesOf("  curve polar(r = 1 / (t - 0.55), t = 0 .. 1)"), ElementsAre());
}

TEST(CurveBuildingTest, NamedArgumentsOfAtan2AreTakenInTheirOrder) {
  // atan2(y = t - 0.5, x = 1) is negative for t < 0.5; atan2(1, t - 0.5)
  // never is.
  EXPECT_THAT(namesOf("  curve polar(r = sqrt(atan2(x = 1, y = t - 0.5)), t = 0 .. 1)"),
              ElementsAre("non-finite-value"));
  EXPECT_THAT(namesOf("  curve polar(r = sqrt(atan2(y = 1, x = t - 0.5)), t = 0 .. 1)"),
              ElementsAre());
}

TEST(CurveBuildingTest, WhatDoesNotDependOnTIsCheckedAtEverySampleAsWell) {
  EXPECT_THAT(namesOf("  curve polar(r = sqrt(c - 1) + t, t = 0 .. 1)", "const c = 0.5\n"),
              ElementsAre("non-finite-value"));
  EXPECT_THAT(namesOf("  curve param(x = t, y = 2 % (c - 0.5), t = 0 .. 1)", "const c = 0.5\n"),
              ElementsAre("division-by-zero"));
}

TEST(CurveBuildingTest, OnlySomeSamplesOutOfRangeAreFound) {
  // pow of a negative base: every sample but the last; the remainder by t:
  // only the first.
  EXPECT_THAT(namesOf("  curve polar(r = (t - 1) ^ 0.5 + 2, t = 0 .. 1)"),
              ElementsAre("non-finite-value"));
  EXPECT_THAT(namesOf("  curve polar(r = 1 + 1 % t, t = 0 .. 1)"), ElementsAre("division-by-zero"));
  EXPECT_THAT(namesOf("  curve polar(r = 1 + 1 % t, t = 0.1 .. 1)"), ElementsAre());
}

TEST(CurveBuildingTest, SamplesThroughFunctionsUseTheirOwnParameters) {
  // Inside lobe, `t` is its parameter k*t, never negative here; the
  // parameter of the second fn shadows nothing outside it.
  std::string functions = "fn lobe(t) = sqrt(t)\nfn shifted(a, b) = sqrt(b - a)\n";
  EXPECT_THAT(namesOf("  curve polar(r = 1 + lobe(2*t), t = 0 .. 1)", functions), ElementsAre());
  EXPECT_THAT(namesOf("  curve polar(r = 1 + shifted(b = t, a = 0.5), t = 0 .. 1)", functions),
              ElementsAre("non-finite-value"));
  EXPECT_THAT(namesOf("  curve polar(r = 1 + shifted(t, 1), t = 0 .. 1)", functions),
              ElementsAre());
}

std::string chainOf(const std::string& term, int count) {
  std::string chain = term;
  for (int i = 1; i < count; ++i) {
    chain += " + " + term;
  }
  return chain;
}

TEST(CurveBuildingTest, DeepExpressionsAreSampledAsWell) {
  // 300 operators deep: beyond what is sampled at once.
  std::string deep = chainOf("t", 300);
  EXPECT_THAT(namesOf("  curve polar(r = " + deep + " + sqrt(t - 0.5), t = 0 .. 1)"),
              ElementsAre("non-finite-value"));
  EXPECT_THAT(namesOf("  curve polar(r = 1 + " + deep + ", t = 0 .. 1)"), ElementsAre());
  // Through nested fns.
  std::string functions = "fn f1(x) = " + chainOf("x", 60) + "\nfn f2(x) = f1(x) + " +
                          chainOf("x", 60) + "\nfn f3(x) = f2(x) + " + chainOf("x", 60) +
                          "\nfn f4(x) = f3(x) + sqrt(x - 0.25)\n";
  EXPECT_THAT(namesOf("  curve polar(r = f4(t), t = 0 .. 1)", functions),
              ElementsAre("non-finite-value"));
  EXPECT_THAT(namesOf("  curve polar(r = 1 + f3(t), t = 0 .. 1)", functions), ElementsAre());
}

TEST(CurveBuildingTest, AnExpressionThatIsNoNumberIsReported) {
  EXPECT_THAT(namesOf("  curve param(x = t, y = (t, 1), t = 0 .. 1)"),
              ElementsAre("type-mismatch"));
}

TEST(CurveBuildingTest, AListWrittenOutIsCheckedElementByElement) {
  // The elements are a fn's parameter, so only their values tell their
  // type. One element of another type: the list is mixed, nothing more.
  EXPECT_THAT(namesOf("  curve f(1)", "fn f(a) = nurbs(order=2, points=[(0, 0), a, (1, 1)])\n"),
              ElementsAre("mixed-list"));
  // Numbers where points belong: one message, at the first of them.
  auto numbers = check("fn f(a) = nurbs(order=2, points=[a, a, a])\n" + part("  curve f(1)"));
  ASSERT_THAT(numbers->names(), ElementsAre("type-mismatch"));
  const Diagnostic& mismatch = numbers->diagnostics.diagnostics().front();
  EXPECT_EQ(mismatch.message, "'points' must hold points");
  EXPECT_EQ(mismatch.span.begin, 33u); // the first `a`
  // An element that cannot be evaluated: its own message only.
  EXPECT_THAT(namesOf("  curve f(2)", "fn f(a) = nurbs(order=2, points=[(0, 0), (1, 1), (2, 0)], "
                                      "weights=[1, a, 1/(a - 2)])\n"),
              ElementsAre("division-by-zero"));
  // Both weights that are not positive; knots that decrease.
  EXPECT_THAT(namesOf("  curve nurbs(order=2, points=[(0, 0), (1, 1), (2, 0)], "
                      "weights=[1, 0, -2])"),
              ElementsAre("weight-not-positive", "weight-not-positive"));
  EXPECT_THAT(namesOf("  curve bspline(order=2, points=[(0, 0), (1, 1), (2, 0)], "
                      "knots=[0, 0, 0.7, 0.5, 1])"),
              ElementsAre("knots-not-monotonic"));
}

TEST(CurveBuildingTest, AListGivenByNameIsCheckedAsWell) {
  EXPECT_THAT(namesOf("  let W = [1, 1, 0]\n"
                      "  curve nurbs(order=2, points=[(0, 0), (1, 1), (2, 0)], weights=W)"),
              ElementsAre("weight-not-positive"));
  EXPECT_THAT(
      namesOf("  curve f([1, 2])\n  curve f([(0, 0)])", "fn f(a) = nurbs(order=2, points=a)\n"),
      ElementsAre("type-mismatch", "order-vs-points"));
}

// The curve of the part's only cut, a polar or param call whose `t` the
// checker declared.
const CallExpr& onlyAnalyticCall(const test_support::Checked& checked) {
  std::vector<const CallExpr*> curves;
  for (const StmtPtr& statement : checked.program.parts.at(0)->body.statements) {
    if (statement->kind == StmtKind::Cut) {
      curves.push_back(&as<CallExpr>(*as<CutStmt>(*statement).curve));
    }
  }
  EXPECT_EQ(curves.size(), 1u);
  EXPECT_NE(curves.at(0)->curveParameter, nullptr);
  return *curves.at(0);
}

TEST(CurveBuildingTest, BuiltinArgumentsAreBoundByNameAndPosition) {
  auto checked = check(part("  curve param(1 + t, t = 0 .. 1, y = 2)"));
  ASSERT_THAT(checked->names(), ElementsAre());
  const CallExpr& call = onlyAnalyticCall(*checked);
  EXPECT_EQ(builtinArgument(call, "x"), call.arguments[0].value.get());
  EXPECT_EQ(builtinArgument(call, "t"), call.arguments[1].value.get());
  EXPECT_EQ(builtinArgument(call, "y"), call.arguments[2].value.get());
  EXPECT_EQ(builtinArgument(call, "z"), nullptr);
  EXPECT_EQ(builtinArgument(call, "r"), nullptr);
}

TEST(CurveBuildingTest, EveryBuiltinHasFewEnoughParametersToBind) {
  // Arguments are bound into a small fixed array.
  for (const BuiltinInfo& builtin : builtinFunctions()) {
    EXPECT_LE(builtin.parameters.size(), 8u) << builtin.name;
  }
}

} // namespace
} // namespace cncc::frontend
