#include "cncc/frontend/compiled_number.h"

#include "checked_source.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

namespace cncc::frontend {
namespace {

using test_support::check;
using ::testing::ElementsAre;

// The curve of `const c = ...` in `text`.
struct CheckedCurve {
  std::unique_ptr<test_support::Checked> checked;
  const CurveValue* curve = nullptr;
};

CheckedCurve curveOf(const std::string& text) {
  CheckedCurve result{check(text)};
  EXPECT_THAT(result.checked->names(), ElementsAre());
  const Declaration* declaration = result.checked->find("c");
  if (declaration != nullptr && declaration->value && declaration->value->curve) {
    result.curve = declaration->value->curve.get();
  }
  return result;
}

bool sameBits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// Compiled, `expression` gives the evaluator's value to the bit at every t
// of the curve's range sampled (and where it gives up, so does the
// evaluator's fast path: the evaluator then reports).
void expectSameAsEvaluator(const test_support::Checked& checked, const CurveValue& curve,
                           const Expr& expression) {
  std::optional<CompiledNumber> compiled =
      CompiledNumber::compile(expression, curve.environment, curve.parameter);
  ASSERT_TRUE(compiled.has_value());
  DiagnosticEngine diagnostics{0};
  ExpressionEvaluator evaluator(checked.program, diagnostics);
  Environment environment = curve.environment;
  int steps = 997;
  for (int i = 0; i <= steps; ++i) {
    double t = curve.low + (curve.high - curve.low) * i / steps;
    environment[curve.parameter] = Value::ofNumber(t);
    Value expected = evaluator.evaluate(expression, environment);
    double number = 0;
    ASSERT_TRUE(compiled->evaluate(t, number)) << "t = " << t;
    ASSERT_EQ(expected.type.kind, TypeKind::Num);
    EXPECT_TRUE(sameBits(number, expected.number))
        << "t = " << t << ": " << number << " against " << expected.number;
  }
}

TEST(CompiledNumberTest, GivesTheEvaluatorsValuesToTheBit) {
  auto polar = curveOf("const c = polar(r = 18 + 4*cos(2*t)*cos(6*t), t = 0 .. 2*pi)\n");
  ASSERT_NE(polar.curve, nullptr);
  expectSameAsEvaluator(*polar.checked, *polar.curve, *polar.curve->radius);

  // Constants, fn calls (inlined, an argument used twice), named arguments
  // in the other order, %, ^, unary minus and every operator.
  auto param = curveOf("const a = 1.5\n"
                       "const b = a * 2\n"
                       "fn lobe(k, x) = cos(k*x) * x - k / 3\n"
                       "const c = param(x = a + b*t - lobe(3, t) % 0.7, "
                       "y = -t^1.5 + atan2(x = t + 1, y = 2) - lobe(x = t, k = 2*pi), "
                       "z = sqrt(t + 1) * exp(-t) / (1 + t), t = 0 .. 4)\n");
  ASSERT_NE(param.curve, nullptr);
  for (const Expr* expression : {param.curve->x, param.curve->y, param.curve->z}) {
    ASSERT_NE(expression, nullptr);
    expectSameAsEvaluator(*param.checked, *param.curve, *expression);
  }
}

TEST(CompiledNumberTest, ComputesWhatDoesNotDependOnTheVariableOnce) {
  auto polar = curveOf("const c = polar(r = 2 * (3 + 4) * sin(pi / 6) + t, t = 0 .. 1)\n");
  ASSERT_NE(polar.curve, nullptr);
  std::optional<CompiledNumber> compiled = CompiledNumber::compile(
      *polar.curve->radius, polar.curve->environment, polar.curve->parameter);
  ASSERT_TRUE(compiled.has_value());
  // The variable and the one addition.
  EXPECT_EQ(compiled->operationCount(), 2u);
  double number = 0;
  ASSERT_TRUE(compiled->evaluate(0.5, number));
  EXPECT_EQ(number, 2 * (3 + 4) * std::sin(M_PI / 6) + 0.5);
}

TEST(CompiledNumberTest, GivesUpWhereTheFastPathDoes) {
  // A division by zero at t = 1 and a square root of a negative number
  // past t = 2 (outside the range, which checking samples): the ordinary
  // evaluation reports them.
  auto polar = curveOf("const c = polar(r = 1 / (t - 1) + sqrt(2 - t), t = 0 .. 0.9)\n");
  ASSERT_NE(polar.curve, nullptr);
  std::optional<CompiledNumber> compiled = CompiledNumber::compile(
      *polar.curve->radius, polar.curve->environment, polar.curve->parameter);
  ASSERT_TRUE(compiled.has_value());
  double number = 0;
  EXPECT_TRUE(compiled->evaluate(0.5, number));
  EXPECT_EQ(number, 1 / (0.5 - 1) + std::sqrt(2 - 0.5));
  DiagnosticEngine diagnostics{0};
  ExpressionEvaluator evaluator(polar.checked->program, diagnostics);
  for (double t : {1.0, 2.5}) {
    EXPECT_FALSE(compiled->evaluate(t, number)) << "t = " << t;
    Environment environment = polar.curve->environment;
    environment[polar.curve->parameter] = Value::ofNumber(t);
    EXPECT_NE(evaluator.evaluate(*polar.curve->radius, environment).type.kind, TypeKind::Num);
  }
}

TEST(CompiledNumberTest, LeavesToTheEvaluatorWhatTheFastPathDoesNotTake) {
  // A conditional.
  auto conditional = curveOf("const c = polar(r = if t < 1 then 1 else t, t = 0 .. 2)\n");
  ASSERT_NE(conditional.curve, nullptr);
  EXPECT_FALSE(CompiledNumber::compile(*conditional.curve->radius, conditional.curve->environment,
                                       conditional.curve->parameter));
}

} // namespace
} // namespace cncc::frontend
