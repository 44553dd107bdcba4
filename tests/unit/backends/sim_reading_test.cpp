// How the virtual controller reads shop programs (`;` as end of block,
// comments in any case, Fanuc's two-letter abbreviations) and how strict
// reading keeps refusing them.
#include "cncc/backends/controller_profile.h"
#include "cncc/backends/virtual_controller.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

namespace cncc::backends::sim {
namespace {

using ::testing::HasSubstr;

const ControllerProfile& profileNamed(const char* name) {
  return *findControllerProfile(name);
}

SimulationOptions shopReading(ControllerFamily family = ControllerFamily::Fanuc) {
  SimulationOptions options;
  options.reading.strict = false;
  options.reading.family = family;
  return options;
}

// The value of #100 after running `body` (wrapped in % O1000 ... M30 %).
double commonAfter(const std::string& body, const SimulationOptions& options = shopReading(),
                   const char* profile = "fanuc") {
  SimulationResult result =
      simulateProgram("%\nO1000\n" + body + "M30\n%\n", profileNamed(profile), options);
  if (result.error) {
    ADD_FAILURE() << "line " << result.error->line() << ": " << result.error->what();
    return 0;
  }
  auto found = result.commonVariables.find(100);
  if (found == result.commonVariables.end() || !found->second) {
    ADD_FAILURE() << "#100 is vacant";
    return 0;
  }
  return *found->second;
}

std::string errorOf(const std::string& text, const SimulationOptions& options,
                    const char* profile = "fanuc") {
  SimulationResult result = simulateProgram(text, profileNamed(profile), options);
  if (!result.error) {
    ADD_FAILURE() << "no error for:\n" << text;
    return "";
  }
  return result.error->what();
}

TEST(SimReading, SemicolonEndsTheBlock) {
  EXPECT_EQ(commonAfter("#100 = 1;\n#100 = #100 + 2;\n"), 3);
  // What follows `;` on the line is the next block.
  EXPECT_EQ(commonAfter("#100 = 1; #100 = #100 * 5;\n"), 5);
  // A `;` inside a comment is part of the comment.
  EXPECT_EQ(commonAfter("#100 = 7 (A; B);\n"), 7);
  SimulationResult result =
      simulateProgram("%;\nO1000;\n#100 = 2;\nM30;\n%;\n", profileNamed("fanuc"), shopReading());
  EXPECT_FALSE(result.error) << result.error->what();
}

TEST(SimReading, StrictReadingRefusesSemicolonsAndLowerCase) {
  SimulationOptions strict;
  EXPECT_THAT(errorOf("%\nO1000\n#100 = 1;\nM30\n%\n", strict), HasSubstr("';'"));
  EXPECT_THAT(errorOf("%\nO1000 (hole)\nM30\n%\n", strict), HasSubstr("lower-case"));
  EXPECT_THAT(errorOf("%\nO1000\nWH [1 LT 2] DO1\nEN1\nM30\n%\n", strict),
              HasSubstr("'WH' abbreviates WHILE"));
}

TEST(SimReading, CommentsMayHoldLowerCaseButCodeMayNot) {
  EXPECT_EQ(commonAfter("(drill the holes) #100 = 4 (depth: 4 mm)\n"), 4);
  EXPECT_THAT(errorOf("%\nO1000\ng01 X1.\nM30\n%\n", shopReading()),
              HasSubstr("only allowed in comments"));
}

TEST(SimReading, FanucAbbreviationsOfStatements) {
  std::string loop = "#100 = 0\n"
                     "#1 = 0\n"
                     "WH [[#1 GE 5] OR [#1 EQ 5]] DO1\n"
                     "EN1\n";
  // The condition is false at once: the loop body is skipped. With GO and TH:
  EXPECT_EQ(commonAfter(loop), 0);
  EXPECT_EQ(commonAfter("#100 = 0\n"
                        "N10 #100 = #100 + 1\n"
                        "IF [#100 LT 4] GO10\n"
                        "IF [#100 EQ 4] TH #100 = #100 * 10\n"),
            40);
  EXPECT_EQ(commonAfter("#100 = 0\n#1 = 0\nWH [#1 LT 3] DO1\n#1 = #1 + 1\n#100 = #100 + #1\n"
                        "EN1\n"),
            6);
}

TEST(SimReading, FanucAbbreviationsOfFunctionsAndOperators) {
  EXPECT_DOUBLE_EQ(commonAfter("#100 = SI[30.] + CO[60.]\n"), 1.0);
  EXPECT_DOUBLE_EQ(commonAfter("#100 = SQ[16.] + AB[-2.] + FI[2.7] + FU[1.2]\n"), 4 + 2 + 2 + 2);
  EXPECT_NEAR(commonAfter("#100 = AT[1.]/[1.]\n"), 45, 1e-9);
  EXPECT_DOUBLE_EQ(commonAfter("#100 = 6 AN 3 + [5 XO 1] + [7 MO 4]\n"), 2 + 4 + 3);
  // The full words still read the same, SIN not as SI followed by N.
  EXPECT_DOUBLE_EQ(commonAfter("#100 = SIN[90.] + ROUND[1.5] + RO[2.5]\n"), 1 + 2 + 3);
}

TEST(SimReading, MitsubishiReadsNoAbbreviations) {
  SimulationOptions m80 = shopReading(ControllerFamily::Mitsubishi);
  EXPECT_EQ(commonAfter("#100 = 3; (lower case here)\n", m80, "m80"), 3);
  EXPECT_THAT(errorOf("%\nO1000\n#100 = SI[30.]\nM30\n%\n", m80, "m80"),
              HasSubstr("'SI' abbreviates SIN: only Fanuc reads it"));
  EXPECT_THAT(errorOf("%\nO1000\n#1 = 0\nWH [#1 LT 3] DO1\nEN1\nM30\n%\n", m80, "m80"),
              HasSubstr("write WHILE"));
}

TEST(SimReading, ErrorsNameTheLineOfASplitBlock) {
  SimulationResult result = simulateProgram("%\nO1000\n#100 = 1; #100 = 1/0;\nM30\n%\n",
                                            profileNamed("fanuc"), shopReading());
  ASSERT_TRUE(result.error);
  EXPECT_EQ(result.error->line(), 3);
  EXPECT_THAT(result.error->what(), HasSubstr("division by zero"));
}

} // namespace
} // namespace cncc::backends::sim
