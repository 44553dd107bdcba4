#include "cncc/backends/controller_profile.h"
#include "cncc/backends/virtual_controller.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

namespace cncc::backends::sim {
namespace {

using ::testing::HasSubstr;

const ControllerProfile& fanuc() {
  return *findControllerProfile("fanuc");
}

// Runs `body` wrapped in `%`, `O1000` and `M30`: the body's first line is
// line 3 of the program.
SimulationResult runBody(const std::string& body, const ControllerProfile& profile = fanuc(),
                         const SimulationOptions& options = {}) {
  return simulateProgram("%\nO1000\n" + body + "M30\n%\n", profile, options);
}

// The value of common variable `variable` after running `body`; fails the
// test when the program has an error or left it vacant.
double commonAfter(const std::string& body, int variable) {
  SimulationResult result = runBody(body);
  if (result.error) {
    ADD_FAILURE() << "line " << result.error->line() << ": " << result.error->what();
    return 0;
  }
  auto found = result.commonVariables.find(variable);
  if (found == result.commonVariables.end() || !found->second) {
    ADD_FAILURE() << "#" << variable << " is vacant";
    return 0;
  }
  return *found->second;
}

bool isVacantAfter(const std::string& body, int variable) {
  SimulationResult result = runBody(body);
  EXPECT_FALSE(result.error) << (result.error ? result.error->what() : "");
  auto found = result.commonVariables.find(variable);
  return found == result.commonVariables.end() || !found->second;
}

// The error running `text` gives; fails the test when there is none.
SimulationError errorOf(const std::string& text, const ControllerProfile& profile = fanuc(),
                        const SimulationOptions& options = {}) {
  SimulationResult result = simulateProgram(text, profile, options);
  if (!result.error) {
    ADD_FAILURE() << "no error for:\n" << text;
    return SimulationError(-1, "", "no error");
  }
  return *result.error;
}

TEST(SimExpression, FunctionsTakeAndGiveDegrees) {
  EXPECT_NEAR(commonAfter("#100 = SIN[30.]\n", 100), 0.5, 1e-12);
  EXPECT_NEAR(commonAfter("#100 = COS[60.]\n", 100), 0.5, 1e-12);
  EXPECT_NEAR(commonAfter("#100 = TAN[45.]\n", 100), 1.0, 1e-12);
  EXPECT_NEAR(commonAfter("#100 = ASIN[1.]\n", 100), 90.0, 1e-12);
  EXPECT_NEAR(commonAfter("#100 = ACOS[0.5]\n", 100), 60.0, 1e-12);
  EXPECT_NEAR(commonAfter("#100 = SQRT[2.]*SQRT[2.]\n", 100), 2.0, 1e-12);
  EXPECT_NEAR(commonAfter("#100 = LN[EXP[2.]]\n", 100), 2.0, 1e-12);
  EXPECT_EQ(commonAfter("#100 = ABS[-3.5]\n", 100), 3.5);
}

TEST(SimExpression, TwoArgumentArcTangentCoversAllQuadrantsFrom0To360) {
  EXPECT_NEAR(commonAfter("#100 = ATAN[1.]/[1.]\n", 100), 45.0, 1e-12);
  EXPECT_NEAR(commonAfter("#100 = ATAN[1.]/[-1.]\n", 100), 135.0, 1e-12);
  EXPECT_NEAR(commonAfter("#100 = ATAN[-1.]/[-1.]\n", 100), 225.0, 1e-12);
  EXPECT_NEAR(commonAfter("#100 = ATAN[-1.]/[1.]\n", 100), 315.0, 1e-12);
  EXPECT_NEAR(commonAfter("#100 = ATAN[0]/[-2.]\n", 100), 180.0, 1e-12);
  EXPECT_NEAR(commonAfter("#100 = ATAN[2.]/[0]\n", 100), 90.0, 1e-12);
}

TEST(SimExpression, RoundingFunctionsOfNegativeNumbers) {
  EXPECT_EQ(commonAfter("#100 = FIX[-1.5]\n", 100), -1);
  EXPECT_EQ(commonAfter("#100 = FIX[1.7]\n", 100), 1);
  EXPECT_EQ(commonAfter("#100 = FUP[-1.2]\n", 100), -2);
  EXPECT_EQ(commonAfter("#100 = FUP[1.2]\n", 100), 2);
  EXPECT_EQ(commonAfter("#100 = ROUND[-1.5]\n", 100), -2);
  EXPECT_EQ(commonAfter("#100 = ROUND[-1.4]\n", 100), -1);
  EXPECT_EQ(commonAfter("#100 = ROUND[2.5]\n", 100), 3);
}

TEST(SimExpression, PrecedenceAndIntegerOperators) {
  EXPECT_EQ(commonAfter("#100 = 2 + 3 * 4\n", 100), 14);
  EXPECT_EQ(commonAfter("#100 = [2 + 3] * 4\n", 100), 20);
  EXPECT_EQ(commonAfter("#100 = 10 - 4 - 3\n", 100), 3);
  EXPECT_EQ(commonAfter("#100 = 12 / 4 / 3\n", 100), 1);
  EXPECT_EQ(commonAfter("#100 = -2 * -3\n", 100), 6);
  EXPECT_EQ(commonAfter("#100 = 7 MOD 3\n", 100), 1);
  EXPECT_EQ(commonAfter("#100 = 5 AND 3\n", 100), 1);
  EXPECT_EQ(commonAfter("#100 = 5 OR 3\n", 100), 7);
  EXPECT_EQ(commonAfter("#100 = 5 XOR 3\n", 100), 6);
  EXPECT_EQ(commonAfter("#100=2+3*4\n", 100), 14); // spaces are optional
}

TEST(SimExpression, IndirectVariables) {
  EXPECT_EQ(commonAfter("#101 = 7.\n#1 = 101\n#100 = #[#1]\n", 100), 7);
  EXPECT_EQ(commonAfter("#1 = 50\n#[#1 * 2 + 2] = 4.\n", 102), 4);
}

TEST(SimVacant, AssignmentKeepsVacantAndArithmeticMakesZero) {
  EXPECT_TRUE(isVacantAfter("#100 = #1\n", 100));
  EXPECT_TRUE(isVacantAfter("#100 = #0\n", 100));
  EXPECT_EQ(commonAfter("#100 = #1 + #1\n", 100), 0);
  EXPECT_EQ(commonAfter("#100 = #1 * 5\n", 100), 0);
  EXPECT_EQ(commonAfter("#100 = -#1\n", 100), 0);
  EXPECT_EQ(commonAfter("#100 = SIN[#1]\n", 100), 0);
}

TEST(SimVacant, OnlyEqualAndNotEqualTellVacantFromZero) {
  // #1 is vacant, #2 is 0.
  auto truth = [](const std::string& condition) {
    return commonAfter("#2 = 0\n#100 = 0\nIF [" + condition + "] THEN #100 = 1\n", 100);
  };
  EXPECT_EQ(truth("#1 EQ #0"), 1);
  EXPECT_EQ(truth("#1 EQ 0"), 0);
  EXPECT_EQ(truth("#1 NE 0"), 1);
  EXPECT_EQ(truth("#2 EQ #0"), 0);
  EXPECT_EQ(truth("#2 EQ 0"), 1);
  EXPECT_EQ(truth("#1 GE 0"), 1);
  EXPECT_EQ(truth("#1 GT 0"), 0);
  EXPECT_EQ(truth("#1 LE #2"), 1);
  EXPECT_EQ(truth("[#1 EQ #0] AND [#2 EQ 0]"), 1);
  EXPECT_EQ(truth("[#1 EQ 0] OR [#2 NE 0]"), 0);
}

TEST(SimVacant, AnAddressWithAVacantValueIsDropped) {
  SimulationResult result = runBody("G90 G00 X5. Y6. Z7.\n#10 = 2.\nG00 X#10 Y#11 Z#0\n");
  ASSERT_FALSE(result.error) << result.error->what();
  ASSERT_EQ(result.path.events.size(), 2u);
  const ExecutedEvent& second = result.path.events[1];
  EXPECT_EQ(second.end.x, 2);
  EXPECT_EQ(second.end.y, 6);
  EXPECT_EQ(second.end.z, 7);
}

TEST(SimExpression, ErrorsNameTheLine) {
  SimulationError division = errorOf("%\nO1\n#1 = 2.\n#100 = #1 / [#1 - 2]\nM30\n%\n");
  EXPECT_EQ(division.line(), 4);
  EXPECT_EQ(division.lineText(), "#100 = #1 / [#1 - 2]");
  EXPECT_THAT(division.what(), HasSubstr("division by zero"));
  EXPECT_EQ(errorOf("%\nO1\n#100 = SQRT[-1.]\nM30\n%\n").line(), 3);
  EXPECT_EQ(errorOf("%\nO1\n#100 = 1 MOD 0\nM30\n%\n").line(), 3);
  EXPECT_EQ(errorOf("%\nO1\n#100 = ACOS[2.]\nM30\n%\n").line(), 3);
  EXPECT_EQ(errorOf("%\nO1\n#100 = 1.5 AND 1\nM30\n%\n").line(), 3);
  EXPECT_EQ(errorOf("%\nO1\n#100 = EXP[1000.]\nM30\n%\n").line(), 3);
}

TEST(SimExpression, ConstructsThatDifferBetweenControllersAreRefused) {
  EXPECT_THAT(errorOf("%\nO1\n#100 = [1 EQ 1]\nM30\n%\n").what(), HasSubstr("comparison"));
  EXPECT_THAT(errorOf("%\nO1\n#100 = ATAN[1.]\nM30\n%\n").what(), HasSubstr("ATAN[a]/[b]"));
  EXPECT_THAT(errorOf("%\nO1\n#100 = POW[2.,3.]\nM30\n%\n").what(), HasSubstr("POW"));
  EXPECT_THAT(errorOf("%\nO1\nIF [#1] GOTO 5\nM30\n%\n").what(), HasSubstr("comparison"));
  EXPECT_THAT(errorOf("%\nO1\n#100 = 123456789\nM30\n%\n").what(), HasSubstr("9 digits"));
}

TEST(SimExpression, PowerWhereTheProfileHasIt) {
  ControllerProfile profile = fanuc();
  profile.hasPowerFunction = true;
  SimulationResult result = runBody("#100 = POW[2.,10.]\n#101 = ATAN[1.,-1.]\n", profile);
  ASSERT_FALSE(result.error) << result.error->what();
  EXPECT_EQ(*result.commonVariables[100], 1024);
  EXPECT_NEAR(*result.commonVariables[101], 135, 1e-12);
}

} // namespace
} // namespace cncc::backends::sim
