// The M80/Fanuc macro printer: program layout, inline expressions and
// brackets, degrees, loops, parameters, and the limits of the profile.
#include "cncc/backends/controller_profile.h"
#include "cncc/backends/macro_program.h"
#include "cncc/ir/builder.h"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

namespace cncc::backends {
namespace {

using ir::Opcode;
using ir::ValueId;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Not;

const ControllerProfile& profileNamed(std::string_view name) {
  const ControllerProfile* profile = findControllerProfile(name);
  EXPECT_NE(profile, nullptr);
  return *profile;
}

// A circle of radius r around the origin in `steps` chords, at depth -d.
ir::Function circle() {
  ir::FunctionBuilder builder("circle");
  ValueId radius = builder.parameter(builder.addParameter("r", 5));
  ValueId depth = builder.parameter(builder.addParameter("d", 1));
  builder.tool(2, builder.constant(6));
  builder.spindle(builder.constant(2000));
  ValueId zero = builder.constant(0);
  ValueId z = builder.unary(Opcode::Neg, depth);
  builder.rapid(radius, zero, builder.constant(5));
  ValueId index = builder.beginLoop(builder.constant(1), builder.constant(36));
  // Two angles, each used once, so that both stay inline.
  ValueId angleX = builder.binary(Opcode::Mul, index, builder.constant(0.17453292519943295));
  ValueId angleY = builder.binary(Opcode::Mul, index, builder.constant(0.17453292519943295));
  ValueId x = builder.binary(Opcode::Mul, radius, builder.unary(Opcode::Cos, angleX));
  ValueId y = builder.binary(Opcode::Mul, radius, builder.unary(Opcode::Sin, angleY));
  builder.feed(x, y, z, builder.constant(250));
  builder.endLoop();
  builder.rapid(radius, zero, builder.constant(5));
  return builder.finish();
}

std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream stream(text);
  for (std::string line; std::getline(stream, line);) {
    lines.push_back(line);
  }
  return lines;
}

int deepestBrackets(const std::string& line) {
  int depth = 0, deepest = 0;
  for (char c : line) {
    depth += c == '[' ? 1 : c == ']' ? -1 : 0;
    deepest = std::max(deepest, depth);
  }
  return deepest;
}

TEST(MacroProgram, PrintsAMainProgramWithEditableParameters) {
  MacroProgramOptions options;
  options.programNumber = 1234;
  options.sourceName = "circle.cdl";
  options.partName = "circle";
  MacroProgram program = writeMacroProgram(circle(), profileNamed("fanuc"), options);
  ASSERT_THAT(program.errors, IsEmpty());
  std::vector<std::string> lines = linesOf(program.text);
  ASSERT_GE(lines.size(), 10u);
  EXPECT_EQ(lines[0], "%");
  EXPECT_EQ(lines[1], "O1234");
  EXPECT_EQ(lines.back(), "%");
  EXPECT_EQ(lines[lines.size() - 2], "M30");
  EXPECT_THAT(program.text, HasSubstr("(#1 R, DEFAULT 5.)"));
  EXPECT_THAT(program.text, HasSubstr("(#2 D, DEFAULT 1.)"));
  EXPECT_THAT(program.text, HasSubstr("\nG21 G17 G90 G40 G49 G80\n#1=5.\n#2=1.\n"));
  EXPECT_THAT(program.text, HasSubstr("T2 M6"));
  EXPECT_THAT(program.text, HasSubstr("S2000 M3"));
  // The loop: index in a variable, DO1/END1, the angle converted to
  // degrees with the constant folded (0.1745.. rad * 57.29.. = 10 degrees).
  EXPECT_THAT(program.text, HasSubstr("=1.\nWHILE [#"));
  EXPECT_THAT(program.text, HasSubstr(" LE 36.] DO1"));
  EXPECT_THAT(program.text, HasSubstr("END1"));
  // -d is read in the loop: computed once before it.
  EXPECT_THAT(program.text, HasSubstr("#3=-#2\n"));
  EXPECT_THAT(program.text, HasSubstr("X[#1*COS[#4*10.]] Y[#1*SIN[#4*10.]] Z#3 F250."));
  for (const std::string& line : lines) {
    EXPECT_EQ(line.find('('), line.rfind('(')) << "one comment a line: " << line;
    EXPECT_LE(deepestBrackets(line), 5) << line;
  }
  EXPECT_EQ(program.statistics.variables, 4);
  EXPECT_EQ(program.statistics.blocks, static_cast<int>(lines.size()) - 2);
  EXPECT_LT(program.statistics.bytesWithoutComments, program.statistics.bytes);
}

TEST(MacroProgram, PrintsACallableMacroWithArgumentLetters) {
  MacroProgramOptions options;
  options.callable = true;
  MacroProgram program = writeMacroProgram(circle(), profileNamed("m80"), options);
  ASSERT_THAT(program.errors, IsEmpty());
  EXPECT_THAT(program.text, HasSubstr("(CALL G65 P1000 A5. B1.)"));
  EXPECT_THAT(program.text, HasSubstr("IF [#1 EQ #0] THEN #1=5."));
  EXPECT_THAT(program.text, HasSubstr("\nM99\n%\n"));
  EXPECT_THAT(program.text, Not(HasSubstr("M30")));
}

TEST(MacroProgram, PutsParametersInCommonVariablesOnRequest) {
  MacroProgramOptions options;
  options.parametersInCommon = true;
  MacroProgram program = writeMacroProgram(circle(), profileNamed("fanuc"), options);
  ASSERT_THAT(program.errors, IsEmpty());
  EXPECT_THAT(program.text, HasSubstr("(#500 R, DEFAULT 5.)"));
  EXPECT_THAT(program.text, HasSubstr("IF [#501 EQ #0] THEN #501=1."));
  EXPECT_THAT(program.text, HasSubstr("#1=-#501\n"));
}

TEST(MacroProgram, FormatsNumbersWithinTheProfilesDigits) {
  ir::FunctionBuilder builder("numbers");
  ValueId a = builder.parameter(builder.addParameter("a", 0.5));
  ValueId zero = builder.constant(0);
  // 123.456789 has 9 digits; 8 are kept. -0.25 keeps no leading zero, and
  // after the operator it is bracketed (TARGETS.md's portable form).
  ValueId x = builder.binary(Opcode::Add, a, builder.constant(123.456789));
  ValueId y = builder.binary(Opcode::Mul, a, builder.constant(-0.25));
  builder.rapid(x, y, builder.constant(12.34567));
  MacroProgram program = writeMacroProgram(builder.finish(), profileNamed("fanuc"), {});
  ASSERT_THAT(program.errors, IsEmpty());
  EXPECT_THAT(program.text, HasSubstr("#1=.5\n"));
  EXPECT_THAT(program.text, HasSubstr("G0 Z12.346\n"));    // a literal coordinate: 3 decimals
  EXPECT_THAT(program.text, HasSubstr("X[#1+123.45679]")); // a constant: 8 digits
  EXPECT_THAT(program.text, HasSubstr("Y[#1*[-.25]]"));
  (void)zero;
}

TEST(MacroProgram, RefusesNumbersBeyondTheDigits) {
  ir::FunctionBuilder builder("huge");
  ValueId a = builder.parameter(builder.addParameter("a", 1));
  ValueId x = builder.binary(Opcode::Mul, a, builder.constant(1e12));
  builder.rapid(x, a, a);
  MacroProgram program = writeMacroProgram(builder.finish(), profileNamed("fanuc"), {});
  ASSERT_THAT(program.errors, Not(IsEmpty()));
  EXPECT_THAT(program.errors[0], HasSubstr("8 digits"));
  EXPECT_TRUE(program.text.empty());
}

TEST(MacroProgram, RefusesLoopsNestedDeeperThanTheProfileAllows) {
  ir::FunctionBuilder builder("deep loops");
  ValueId zero = builder.constant(0);
  ValueId one = builder.constant(1);
  for (int i = 0; i < 4; ++i) {
    builder.beginLoop(zero, one);
  }
  builder.feed(zero, zero, zero, builder.constant(100));
  for (int i = 0; i < 4; ++i) {
    builder.endLoop();
  }
  MacroProgram program = writeMacroProgram(builder.finish(), profileNamed("m80"), {});
  ASSERT_THAT(program.errors, ElementsAre(HasSubstr("nests 4 loops, the controller allows 3")));
}

TEST(MacroProgram, RefusesAProgramNeedingMoreVariablesThanTheProfileHas) {
  ir::FunctionBuilder builder("big table");
  std::uint32_t table = builder.addTable(std::vector<double>(60, 0.25));
  ValueId zero = builder.constant(0);
  ValueId index = builder.beginLoop(zero, builder.constant(59));
  builder.feed(builder.tableLoad(table, index), zero, zero, builder.constant(100));
  builder.endLoop();
  ir::Function function = builder.finish();
  EXPECT_THAT(writeMacroProgram(function, profileNamed("fanuc"), {}).errors, IsEmpty());
  MacroProgram small = writeMacroProgram(function, profileNamed("fanuc-0i-small"), {});
  ASSERT_THAT(small.errors, ElementsAre(HasSubstr("needs 60 consecutive variables")));
}

TEST(MacroProgram, ReadsTablesIndirectly) {
  ir::FunctionBuilder builder("table");
  std::uint32_t table = builder.addTable({0.1, 0.2, 0.3});
  ValueId zero = builder.constant(0);
  ValueId index = builder.beginLoop(zero, builder.constant(2));
  ValueId t = builder.tableLoad(table, index);
  builder.feed(builder.binary(Opcode::Mul, t, builder.constant(10)), zero, zero,
               builder.constant(100));
  builder.endLoop();
  MacroProgram program = writeMacroProgram(builder.finish(), profileNamed("fanuc"), {});
  ASSERT_THAT(program.errors, IsEmpty());
  // The table sits in #1-#3 (the first free variables), the index after it.
  EXPECT_THAT(program.text, HasSubstr("#1=.1\n#2=.2\n#3=.3\n"));
  EXPECT_THAT(program.text, HasSubstr("X[#[1+#4]*10.]"));
}

TEST(MacroProgram, KeepsEveryBlockWithinTheBracketLimit) {
  ir::FunctionBuilder builder("nested");
  ValueId a = builder.parameter(builder.addParameter("a", 2));
  ValueId value = a;
  for (int i = 0; i < 9; ++i) { // [[[[a+1]*a+1]*a+1]*a ...: one bracket level a step
    value = builder.binary(Opcode::Add, builder.binary(Opcode::Mul, value, a), builder.constant(1));
    value = builder.unary(Opcode::Sqrt, value);
  }
  ValueId zero = builder.constant(0);
  builder.rapid(value, zero, zero);
  MacroProgram program = writeMacroProgram(builder.finish(), profileNamed("fanuc"), {});
  ASSERT_THAT(program.errors, IsEmpty());
  for (const std::string& line : linesOf(program.text)) {
    EXPECT_LE(deepestBrackets(line), 5) << line;
  }
  EXPECT_GT(program.statistics.variables, 1); // some steps had to be stored
}

// Thirteen products of parameters in common variables (`#500*#501+..`): as
// `#nn` reads the sum fits a block, as the `#5nn` printed it does not, and
// the allocator splits it by the variables' own numbers.
TEST(MacroProgram, KeepsEveryBlockWithinTheLengthLimitWithFourDigitVariables) {
  ir::FunctionBuilder builder("products");
  std::vector<ValueId> parameters;
  for (int i = 0; i < 14; ++i) {
    parameters.push_back(builder.parameter(builder.addParameter(fmt::format("p{}", i), 1)));
  }
  ValueId sum = builder.binary(Opcode::Mul, parameters[0], parameters[1]);
  for (std::size_t i = 1; i + 1 < parameters.size(); ++i) {
    sum = builder.binary(Opcode::Add, sum,
                         builder.binary(Opcode::Mul, parameters[i], parameters[i + 1]));
  }
  ValueId zero = builder.constant(0);
  builder.feed(sum, zero, zero, builder.constant(100));
  MacroProgramOptions options;
  options.parametersInCommon = true;
  const ControllerProfile& fanuc = profileNamed("fanuc");
  MacroProgram program = writeMacroProgram(builder.finish(), fanuc, options);
  ASSERT_THAT(program.errors, IsEmpty());
  EXPECT_THAT(program.text, HasSubstr("#500*#501"));
  for (const std::string& line : linesOf(program.text)) {
    EXPECT_LE(static_cast<int>(line.size()), fanuc.maximumBlockLength) << line;
  }
  EXPECT_GT(program.statistics.variables, 14); // part of the sum in a variable
}

TEST(MacroProgram, WritesMinAndAtan2AsStatements) {
  ir::FunctionBuilder builder("statements");
  ValueId a = builder.parameter(builder.addParameter("a", 2));
  ValueId b = builder.parameter(builder.addParameter("b", 3));
  ValueId smaller = builder.binary(Opcode::Min, a, b);
  ValueId angle = builder.binary(Opcode::Atan2, a, b);
  builder.rapid(smaller, angle, builder.constant(0));
  MacroProgram program = writeMacroProgram(builder.finish(), profileNamed("fanuc"), {});
  ASSERT_THAT(program.errors, IsEmpty());
  EXPECT_THAT(program.text, HasSubstr("#3=#1\nIF [#2 LT #3] THEN #3=#2\n"));
  EXPECT_THAT(program.text,
              HasSubstr("#4=ATAN[#1]/[#2]\nIF [#4 GT 180.] THEN #4=#4-360.\n#4=#4*.01745329\n"));
}

TEST(MacroProgram, MeasuresBlocksAndBytes) {
  MacroProgramStatistics statistics = measureMacroProgram("%\nO1\n(NOTE)\nG0 X1. (A)\nM30\n%\n");
  EXPECT_EQ(statistics.blocks, 4);
  EXPECT_EQ(statistics.bytes, 29u);
  EXPECT_EQ(statistics.bytesWithoutComments, std::string("%\nO1\nG0 X1.\nM30\n%\n").size());
}

} // namespace
} // namespace cncc::backends
