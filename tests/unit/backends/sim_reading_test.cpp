// How the virtual controller reads shop programs (`;` as end of block,
// comments in any case, two-letter abbreviations of macro words where the
// profile says the control reads them) and how strict reading keeps
// refusing them.
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

// A Fanuc whose machine file says it reads the abbreviations (no built-in
// profile does: no manual statement of them was found).
ControllerProfile fanucReadingAbbreviations() {
  ControllerProfile profile = profileNamed("fanuc");
  profile.macroWordAbbreviations = true;
  return profile;
}

// The value of #100 after running `body` (wrapped in % O1000 ... M30 %).
double commonAfter(const std::string& body, const SimulationOptions& options,
                   const ControllerProfile& profile) {
  SimulationResult result = simulateProgram("%\nO1000\n" + body + "M30\n%\n", profile, options);
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

double commonAfter(const std::string& body, const SimulationOptions& options = shopReading(),
                   const char* profile = "fanuc") {
  return commonAfter(body, options, profileNamed(profile));
}

// With abbreviations read: on the Fanuc above, in shop reading.
double abbreviatedCommonAfter(const std::string& body) {
  return commonAfter(body, shopReading(), fanucReadingAbbreviations());
}

std::string errorOf(const std::string& text, const SimulationOptions& options,
                    const ControllerProfile& profile) {
  SimulationResult result = simulateProgram(text, profile, options);
  if (!result.error) {
    ADD_FAILURE() << "no error for:\n" << text;
    return "";
  }
  return result.error->what();
}

std::string errorOf(const std::string& text, const SimulationOptions& options,
                    const char* profile = "fanuc") {
  return errorOf(text, options, profileNamed(profile));
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
  // Even on a profile that reads them in a shop's program.
  EXPECT_THAT(errorOf("%\nO1000\n#100 = SI[30.]\nM30\n%\n", strict, fanucReadingAbbreviations()),
              HasSubstr("never in strict reading; write SIN"));
}

TEST(SimReading, CommentsMayHoldLowerCaseButCodeMayNot) {
  EXPECT_EQ(commonAfter("(drill the holes) #100 = 4 (depth: 4 mm)\n"), 4);
  EXPECT_THAT(errorOf("%\nO1000\ng01 X1.\nM30\n%\n", shopReading()),
              HasSubstr("only allowed in comments"));
}

TEST(SimReading, AbbreviationsOfStatementsWhereTheProfileReadsThem) {
  std::string loop = "#100 = 0\n"
                     "#1 = 0\n"
                     "WH [[#1 GE 5] OR [#1 EQ 5]] DO1\n"
                     "EN1\n";
  // The condition is false at once: the loop body is skipped. With GO and TH:
  EXPECT_EQ(abbreviatedCommonAfter(loop), 0);
  EXPECT_EQ(abbreviatedCommonAfter("#100 = 0\n"
                                   "N10 #100 = #100 + 1\n"
                                   "IF [#100 LT 4] GO10\n"
                                   "IF [#100 EQ 4] TH #100 = #100 * 10\n"),
            40);
  EXPECT_EQ(
      abbreviatedCommonAfter("#100 = 0\n#1 = 0\nWH [#1 LT 3] DO1\n#1 = #1 + 1\n#100 = #100 + #1\n"
                             "EN1\n"),
      6);
}

TEST(SimReading, AbbreviationsOfFunctionsAndOperatorsWhereTheProfileReadsThem) {
  EXPECT_DOUBLE_EQ(abbreviatedCommonAfter("#100 = SI[30.] + CO[60.]\n"), 1.0);
  EXPECT_DOUBLE_EQ(abbreviatedCommonAfter("#100 = SQ[16.] + AB[-2.] + FI[2.7] + FU[1.2]\n"),
                   4 + 2 + 2 + 2);
  EXPECT_NEAR(abbreviatedCommonAfter("#100 = AT[1.]/[1.]\n"), 45, 1e-9);
  EXPECT_DOUBLE_EQ(abbreviatedCommonAfter("#100 = 6 AN 3 + [5 XO 1] + [7 MO 4]\n"), 2 + 4 + 3);
  // The full words still read the same, SIN not as SI followed by N.
  EXPECT_DOUBLE_EQ(abbreviatedCommonAfter("#100 = SIN[90.] + ROUND[1.5] + RO[2.5]\n"), 1 + 2 + 3);
}

// No manual statement of the abbreviations was found, for Fanuc or for
// Mitsubishi: the built-in profiles refuse them by name, in shop reading too.
TEST(SimReading, BuiltinProfilesReadNoAbbreviations) {
  SimulationOptions m80 = shopReading(ControllerFamily::Mitsubishi);
  EXPECT_EQ(commonAfter("#100 = 3; (lower case here)\n", m80, "m80"), 3);
  for (const char* profile : {"fanuc", "fanuc-0i-small", "m80"}) {
    EXPECT_FALSE(profileNamed(profile).macroWordAbbreviations) << profile;
    SimulationOptions shop =
        shopReading(profileNamed(profile).name == "m80" ? ControllerFamily::Mitsubishi
                                                        : ControllerFamily::Fanuc);
    EXPECT_THAT(errorOf("%\nO1000\n#100 = SI[30.]\nM30\n%\n", shop, profile),
                HasSubstr("'SI' abbreviates SIN, read only where the machine file's [profile] "
                          "sets macro_word_abbreviations = true"))
        << profile;
    EXPECT_THAT(errorOf("%\nO1000\n#1 = 0\nWH [#1 LT 3] DO1\nEN1\nM30\n%\n", shop, profile),
                HasSubstr("write WHILE"))
        << profile;
  }
  // The full words read everywhere.
  EXPECT_DOUBLE_EQ(commonAfter("#100 = SIN[90.] + ROUND[1.5]\n"), 3);
}

// A profile that reads them does so in the Mitsubishi family's reading too:
// the profile, not the family, decides.
TEST(SimReading, TheProfileDecidesNotTheFamily) {
  ControllerProfile m80 = profileNamed("m80");
  m80.macroWordAbbreviations = true;
  EXPECT_DOUBLE_EQ(commonAfter("#100 = SQ[16.]\n", shopReading(ControllerFamily::Mitsubishi), m80),
                   4);
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
