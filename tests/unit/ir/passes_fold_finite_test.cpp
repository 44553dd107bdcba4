// fold-finite: each identity it uses, the folding of constants, and what
// it leaves alone (parameters, non-finite results, comparisons, effects).
#include "cncc/ir/interpreter.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/printer.h"
#include "cncc/ir/verifier.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

namespace cncc::ir {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

Function parsed(std::string_view text) {
  ParseError error;
  std::optional<Function> function = parseFunction(text, error);
  EXPECT_TRUE(function) << error.line << ": " << error.message;
  return function ? *function : Function{};
}

// The function after fold-finite then dce (so only what is used is left),
// printed; whether fold-finite changed it goes to `changed`.
std::string foldedText(std::string_view text, bool* changed = nullptr) {
  Function function = parsed(text);
  bool folded = foldAssumingFinite(function);
  if (changed != nullptr) {
    *changed = folded;
  }
  EXPECT_THAT(verifyFunction(function), ::testing::IsEmpty());
  eliminateDeadCode(function);
  return printFunction(function);
}

// `move.feed` of one operation of the parameter x and the constant `c`.
std::string withParameter(std::string_view operation, std::string_view constant) {
  return "func @f(x = 2) {\n"
         "  %x = param x\n"
         "  %c = const " +
         std::string(constant) +
         "\n"
         "  %r = " +
         std::string(operation) +
         "\n"
         "  move.feed %r, %r, %r, %x\n"
         "}\n";
}

constexpr std::string_view justX = "func @f(x = 2) {\n"
                                   "  %0 = param x\n"
                                   "  move.feed %0, %0, %0, %0\n"
                                   "}\n";

TEST(PassesFoldFiniteTest, AddingOrSubtractingZeroAndMultiplyingOrDividingByOneIsTheOperand) {
  for (std::string_view operation :
       {"add %x, %c", "add %c, %x", "sub %x, %c", "mul %x, %c", "mul %c, %x", "div %x, %c"}) {
    std::string constant = operation.starts_with("add") || operation.starts_with("sub") ? "0" : "1";
    bool changed = false;
    EXPECT_EQ(foldedText(withParameter(operation, constant), &changed), justX) << operation;
    EXPECT_TRUE(changed) << operation;
  }
}

// 0 - x is -x here (fold keeps it: 0 - 0 is +0, -0 is -0).
TEST(PassesFoldFiniteTest, ZeroMinusAValueIsItsNegation) {
  std::string folded = foldedText(withParameter("sub %c, %x", "0"));
  EXPECT_THAT(folded, HasSubstr("neg %0"));
  EXPECT_THAT(folded, Not(HasSubstr("sub")));
}

// `fold` keeps x + 0 (x may be -0) and x * 0 (x may be infinite); on a
// controller's finite numbers without a sign of zero they are x and 0.
TEST(PassesFoldFiniteTest, WhatFoldKeepsForSignedZerosAndInfinitiesFoldsHere) {
  std::string sum = withParameter("add %x, %c", "0");
  Function kept = parsed(sum);
  foldConstants(kept);
  EXPECT_THAT(printFunction(kept), HasSubstr("add"));
  EXPECT_THAT(foldedText(sum), Not(HasSubstr("add")));

  for (std::string_view operation : {"mul %x, %c", "mul %c, %x"}) {
    EXPECT_EQ(foldedText(withParameter(operation, "0")), "func @f(x = 2) {\n"
                                                         "  %0 = param x\n"
                                                         "  %1 = const 0\n"
                                                         "  move.feed %1, %1, %1, %0\n"
                                                         "}\n")
        << operation;
  }
}

TEST(PassesFoldFiniteTest, OperationsThatAreNotIdentitiesStay) {
  for (auto [operation, constant] :
       {std::pair{"sub %c, %x", "1"}, std::pair{"div %c, %x", "1"}, std::pair{"div %x, %c", "0"},
        std::pair{"add %x, %c", "1"}, std::pair{"mul %x, %c", "2"}, std::pair{"pow %x, %c", "1"},
        std::pair{"min %x, %c", "0"}}) {
    bool changed = true;
    std::string text = withParameter(operation, constant);
    EXPECT_EQ(foldedText(text, &changed), printFunction(parsed(text))) << operation;
    EXPECT_FALSE(changed) << operation;
  }
}

// A parameter is not a constant, whatever its default: nothing folds
// through `param`, so the program keeps it editable.
TEST(PassesFoldFiniteTest, NothingFoldsThroughAParameter) {
  std::string text = "func @f(zero = 0, one = 1) {\n"
                     "  %0 = param zero\n"
                     "  %1 = param one\n"
                     "  %2 = const 5\n"
                     "  %3 = add %2, %0\n"
                     "  %4 = mul %2, %1\n"
                     "  %5 = div %2, %1\n"
                     "  %6 = sin %0\n"
                     "  move.feed %3, %4, %5, %6\n"
                     "}\n";
  bool changed = true;
  EXPECT_EQ(foldedText(text, &changed), text);
  EXPECT_FALSE(changed);
}

TEST(PassesFoldFiniteTest, ConstantsFoldByTheInterpretersArithmetic) {
  EXPECT_EQ(foldedText("func @f() {\n"
                       "  %two = const 2\n"
                       "  %three = const 3\n"
                       "  %sum = add %two, %three\n"
                       "  %power = pow %two, %three\n"
                       "  %negated = neg %sum\n"
                       "  %root = sqrt %power\n"
                       "  move.feed %sum, %power, %negated, %root\n"
                       "}\n"),
            "func @f() {\n"
            "  %0 = const 5\n"
            "  %1 = const 8\n"
            "  %2 = const -5\n"
            "  %3 = const 2.8284271247461903\n"
            "  move.feed %0, %1, %2, %3\n"
            "}\n");
}

// sin(2 pi) is -2.4e-16: below any printed digit, 0; and a constant within
// 1e-12 of 0 or 1 is taken as it.
TEST(PassesFoldFiniteTest, NumbersWithinATrillionthOfZeroOrOneAreThem) {
  EXPECT_EQ(foldedText("func @f(x = 2) {\n"
                       "  %x = param x\n"
                       "  %turn = const 6.283185307179586\n"
                       "  %sine = sin %turn\n"
                       "  %almostOne = const 0.9999999999999999\n"
                       "  %tiny = const 1e-13\n"
                       "  %a = mul %x, %almostOne\n"
                       "  %b = add %tiny, %x\n"
                       "  %c = mul %x, %tiny\n"
                       "  move.feed %sine, %a, %b, %c\n"
                       "}\n"),
            "func @f(x = 2) {\n"
            "  %0 = param x\n"
            "  %1 = const 0\n"
            "  %2 = const 0\n"
            "  move.feed %1, %0, %0, %2\n"
            "}\n");
}

// 1/0, sqrt(-1) and ln(0) are not folded: the controller alarms there, as
// the host would fail. Nor are comparisons (bools), select or the not of
// a const.bool.
TEST(PassesFoldFiniteTest, NonFiniteResultsAndBoolsStayOperations) {
  std::string text = "func @f() {\n"
                     "  %0 = const 1\n"
                     "  %1 = const 0\n"
                     "  %2 = const -1\n"
                     "  %3 = div %0, %1\n"
                     "  %4 = sqrt %2\n"
                     "  %5 = ln %1\n"
                     "  %6 = lt %1, %0\n"
                     "  %7 = const.bool true\n"
                     "  %8 = not %7\n"
                     "  %9 = and %6, %8\n"
                     "  %10 = select %9, %0, %1\n"
                     "  move.feed %3, %4, %5, %10\n"
                     "}\n";
  bool changed = true;
  EXPECT_EQ(foldedText(text, &changed), text);
  EXPECT_FALSE(changed);
}

// Inside loops and ifs too, loop bounds included; the induction variable
// is not a constant, effects stay where they are.
TEST(PassesFoldFiniteTest, FoldsInsideLoopsAndIfsAndKeepsEffects) {
  Function function = parsed("func @f(n = 3) {\n"
                             "  %n = param n\n"
                             "  %zero = const 0\n"
                             "  %one = const 1\n"
                             "  %high = mul %n, %one\n"
                             "  %i = loop %zero, %high {\n"
                             "    %x = add %i, %zero\n"
                             "    %y = add %i, %one\n"
                             "    %positive = gt %i, %zero\n"
                             "    if %positive {\n"
                             "      %z = mul %zero, %y\n"
                             "      move.feed %x, %y, %z, %one\n"
                             "    }\n"
                             "  }\n"
                             "}\n");
  std::vector<MachineEvent> before = interpret(function).events;
  EXPECT_TRUE(foldAssumingFinite(function));
  EXPECT_THAT(verifyFunction(function), ::testing::IsEmpty());
  eliminateDeadCode(function);
  EXPECT_EQ(printFunction(function), "func @f(n = 3) {\n"
                                     "  %0 = param n\n"
                                     "  %1 = const 0\n"
                                     "  %2 = const 1\n"
                                     "  %3 = loop %1, %0 {\n"
                                     "    %4 = add %3, %2\n"
                                     "    %5 = gt %3, %1\n"
                                     "    if %5 {\n"
                                     "      %6 = const 0\n"
                                     "      move.feed %3, %4, %6, %2\n"
                                     "    }\n"
                                     "  }\n"
                                     "}\n");
  std::vector<MachineEvent> after = interpret(function).events;
  ASSERT_EQ(after.size(), before.size());
  ASSERT_EQ(after.size(), 3u);
  for (std::size_t i = 0; i < after.size(); ++i) {
    EXPECT_EQ(after[i].x, before[i].x);
    EXPECT_EQ(after[i].y, before[i].y);
    EXPECT_EQ(after[i].z, before[i].z);
  }
}

TEST(PassesFoldFiniteTest, IsInTheRegistryAsATargetsPassThatIsNotExact) {
  const Pass* pass = findPass("fold-finite");
  ASSERT_NE(pass, nullptr);
  EXPECT_FALSE(pass->exact);
  EXPECT_EQ(pass->run, &foldAssumingFinite);
  for (std::string_view name : defaultPipeline()) {
    EXPECT_NE(name, "fold-finite") << "the optimiser keeps every bit";
  }
}

} // namespace
} // namespace cncc::ir
