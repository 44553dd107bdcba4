// expand-whole-powers: a ^ n with a whole constant n as multiplications,
// the same value for a negative base (where EXP[LN[a]*n] alarms); a half
// power as the product times a square root, the same value from a = 0 on;
// and what it leaves alone.
#include "cncc/ir/interpreter.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/printer.h"
#include "cncc/ir/verifier.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <initializer_list>
#include <string>

namespace cncc::ir {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

// x ^ `exponent` for the parameter x, fed to as its X.
Function powerOfX(std::string_view exponent) {
  std::string text = "func @f(x = 2) {\n"
                     "  %x = param x\n"
                     "  %n = const " +
                     std::string(exponent) +
                     "\n"
                     "  %r = pow %x, %n\n"
                     "  %f = const 100\n"
                     "  move.feed %r, %x, %x, %f\n"
                     "}\n";
  ParseError error;
  std::optional<Function> function = parseFunction(text, error);
  EXPECT_TRUE(function) << error.line << ": " << error.message;
  return function ? *function : Function{};
}

double firstX(const Function& function, double x) {
  InterpreterOptions options;
  options.parameters = {{"x", x}};
  return interpret(function, options).events.front().x;
}

// The expanded function's x ^ exponent at each x, as pow gives it (0 ^ n
// for n < 0, a division by zero, left out).
void expectPowerAtEach(const Function& function, std::string_view exponent,
                       std::initializer_list<double> bases) {
  double n = std::stod(std::string(exponent));
  for (double x : bases) {
    if (n < 0 && x == 0) {
      continue;
    }
    double expected = std::pow(x, n);
    EXPECT_NEAR(firstX(function, x), expected, 1e-12 * std::max(1.0, std::abs(expected)))
        << "x = " << x << ", n = " << exponent;
  }
}

TEST(PassesWholePowersTest, AWholePowerIsItsProductForEveryBase) {
  for (std::string_view exponent : {"0", "1", "2", "3", "5", "8", "-2", "64"}) {
    Function function = powerOfX(exponent);
    ASSERT_TRUE(expandWholePowers(function)) << exponent;
    EXPECT_TRUE(verifyFunction(function).empty()) << exponent;
    std::string text = printFunction(function);
    EXPECT_THAT(text, Not(HasSubstr("pow"))) << exponent;
    expectPowerAtEach(function, exponent, {-3.0, -0.5, 0.0, 1.5, 2.0});
  }
}

TEST(PassesWholePowersTest, ACubeTakesTwoMultiplications) {
  Function function = powerOfX("3");
  expandWholePowers(function);
  eliminateDeadCode(function);
  std::string text = printFunction(function);
  std::size_t multiplications = 0;
  for (std::size_t at = text.find("mul"); at != std::string::npos; at = text.find("mul", at + 1)) {
    ++multiplications;
  }
  EXPECT_EQ(multiplications, 2u) << text;
}

// t ^ 1.5 from t = 0: pow gives 0 there, where a controller's
// EXP[LN[0]*1.5] stops the program.
TEST(PassesWholePowersTest, AHalfPowerIsAProductAndASquareRootFromZeroOn) {
  for (std::string_view exponent : {"0.5", "1.5", "2.5", "-1.5", "63.5"}) {
    Function function = powerOfX(exponent);
    ASSERT_TRUE(expandWholePowers(function)) << exponent;
    EXPECT_TRUE(verifyFunction(function).empty()) << exponent;
    std::string text = printFunction(function);
    EXPECT_THAT(text, Not(HasSubstr("pow"))) << exponent;
    EXPECT_THAT(text, HasSubstr("sqrt")) << exponent;
    expectPowerAtEach(function, exponent, {0.0, 0.25, 1.5, 2.0});
  }
}

TEST(PassesWholePowersTest, OtherFractionalLargeAndComputedExponentsStay) {
  for (std::string_view exponent : {"2.25", "0.1", "65", "-65", "64.5"}) {
    Function function = powerOfX(exponent);
    EXPECT_FALSE(expandWholePowers(function)) << exponent;
    EXPECT_THAT(printFunction(function), HasSubstr("pow")) << exponent;
  }
  ParseError error;
  std::optional<Function> computed = parseFunction("func @f(x = 2) {\n"
                                                   "  %x = param x\n"
                                                   "  %r = pow %x, %x\n"
                                                   "  move.feed %r, %x, %x, %x\n"
                                                   "}\n",
                                                   error);
  ASSERT_TRUE(computed) << error.message;
  EXPECT_FALSE(expandWholePowers(*computed));
}

} // namespace
} // namespace cncc::ir
