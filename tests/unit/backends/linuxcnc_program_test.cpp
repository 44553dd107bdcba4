// The LinuxCNC printer: layout, named parameters, o-word loops and ifs,
// LinuxCNC's expression syntax, and the line-length limit.
#include "cncc/backends/linuxcnc_program.h"
#include "cncc/ir/builder.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <sstream>

namespace cncc::backends {
namespace {

using ir::Opcode;
using ir::ValueId;
using ::testing::Contains;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Not;

std::vector<std::string> linesOf(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream stream(text);
  for (std::string line; std::getline(stream, line);) {
    lines.push_back(line);
  }
  return lines;
}

// A circle of radius r around the origin in 36 chords at depth -d.
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
  ValueId angleX = builder.binary(Opcode::Mul, index, builder.constant(0.17453292519943295));
  ValueId angleY = builder.binary(Opcode::Mul, index, builder.constant(0.17453292519943295));
  ValueId x = builder.binary(Opcode::Mul, radius, builder.unary(Opcode::Cos, angleX));
  ValueId y = builder.binary(Opcode::Mul, radius, builder.unary(Opcode::Sin, angleY));
  builder.feed(x, y, z, builder.constant(250));
  builder.endLoop();
  builder.rapid(radius, zero, builder.constant(5));
  return builder.finish();
}

LinuxcncProgramOptions circleOptions() {
  LinuxcncProgramOptions options;
  options.sourceName = "circle.cdl";
  options.partName = "circle";
  options.blendTolerance = 0.005;
  return options;
}

TEST(LinuxcncProgram, PrintsAMainProgramWithNamedParameters) {
  LinuxcncProgram program = writeLinuxcncProgram(circle(), circleOptions());
  ASSERT_THAT(program.errors, IsEmpty());
  std::vector<std::string> lines = linesOf(program.text);
  ASSERT_GE(lines.size(), 10u);
  EXPECT_EQ(lines[0], "; circle.cdl - part circle");
  EXPECT_THAT(lines, Contains("; #<_r> r, default 5."));
  EXPECT_THAT(lines, Contains("#<_r> = 5."));
  EXPECT_THAT(lines, Contains("#<_d> = 1."));
  EXPECT_THAT(lines, Contains("G21 G17 G90 G40 G49 G80 G94 G64 P0.005"));
  EXPECT_THAT(lines, Contains("T2 M6"));
  EXPECT_THAT(lines, Contains("S2000 M3"));
  EXPECT_EQ(lines[lines.size() - 2], "M5");
  EXPECT_EQ(lines.back(), "M2");
  // The parameters are set before they are read.
  auto set = std::find(lines.begin(), lines.end(), "#<_r> = 5.");
  auto firstUse = std::find_if(lines.begin(), lines.end(), [](const std::string& line) {
    return line.find("#<_r>") != std::string::npos && !line.starts_with(";") &&
           !line.starts_with("#<_r> =");
  });
  EXPECT_LT(set, firstUse);
}

TEST(LinuxcncProgram, LoopsAreWhileWithUniqueOWords) {
  ir::FunctionBuilder builder("loops");
  ValueId zero = builder.constant(0);
  ValueId feed = builder.constant(100);
  for (int loop = 0; loop < 2; ++loop) {
    ValueId i = builder.beginLoop(builder.constant(0), builder.constant(3));
    builder.feed(i, zero, zero, feed);
    builder.endLoop();
  }
  LinuxcncProgram program = writeLinuxcncProgram(builder.finish(), circleOptions());
  ASSERT_THAT(program.errors, IsEmpty());
  std::vector<std::string> lines = linesOf(program.text);
  EXPECT_THAT(lines, Contains("o100 while [#31 LE 3.]"));
  EXPECT_THAT(lines, Contains("o100 endwhile"));
  EXPECT_THAT(lines, Contains("o101 while [#31 LE 3.]"));
  EXPECT_THAT(lines, Contains("o101 endwhile"));
  EXPECT_THAT(lines, Contains("#31 = [#31+1]"));
  EXPECT_THAT(program.text, Not(HasSubstr("DO")));
}

TEST(LinuxcncProgram, IfElseAndDegreesAndArctangent) {
  ir::FunctionBuilder builder("branches");
  ValueId a = builder.parameter(builder.addParameter("k", 2));
  ValueId zero = builder.constant(0);
  ValueId feed = builder.constant(100);
  builder.beginIf(builder.binary(Opcode::Lt, a, builder.constant(3)));
  builder.feed(builder.unary(Opcode::Sin, a), zero, zero, feed);
  builder.beginElse();
  builder.feed(builder.binary(Opcode::Atan2, a, builder.constant(-1)), zero, zero, feed);
  builder.endIf();
  LinuxcncProgram program = writeLinuxcncProgram(builder.finish(), circleOptions());
  ASSERT_THAT(program.errors, IsEmpty());
  std::vector<std::string> lines = linesOf(program.text);
  EXPECT_THAT(lines, Contains("o100 if [#<_k> LT 3.]"));
  EXPECT_THAT(lines, Contains("o100 else"));
  EXPECT_THAT(lines, Contains("o100 endif"));
  EXPECT_THAT(lines, Contains("G1 X[SIN[#<_k>*57.2957795131]] Y0. Z0. F100."));
  EXPECT_THAT(lines, Contains("G1 X[ATAN[#<_k>]/[-1.]*0.01745329252] Y0. Z0. F100."));
}

TEST(LinuxcncProgram, PowerFloorAndNegationUseLinuxcncSyntax) {
  ir::FunctionBuilder builder("syntax");
  ValueId a = builder.parameter(builder.addParameter("k", 2));
  ValueId feed = builder.constant(100);
  // -(a ** 2): `-a**2` would be (-a)**2 in LinuxCNC.
  ValueId power = builder.binary(Opcode::Pow, a, builder.constant(2));
  builder.feed(builder.unary(Opcode::Neg, power), builder.unary(Opcode::Floor, a),
               builder.unary(Opcode::Ceil, a), feed);
  LinuxcncProgram program = writeLinuxcncProgram(builder.finish(), circleOptions());
  ASSERT_THAT(program.errors, IsEmpty());
  EXPECT_THAT(linesOf(program.text),
              Contains("G1 X[-[#<_k>**2.]] Y[FIX[#<_k>]] Z[FUP[#<_k>]] F100."));
}

TEST(LinuxcncProgram, MinMaxSelectAndRemainderAreStatements) {
  ir::FunctionBuilder builder("statements");
  ValueId a = builder.parameter(builder.addParameter("k", 2));
  ValueId b = builder.parameter(builder.addParameter("m", 3));
  ValueId feed = builder.constant(100);
  ValueId smaller = builder.binary(Opcode::Min, a, b);
  ValueId rest = builder.binary(Opcode::Rem, a, b);
  builder.feed(smaller, rest, builder.binary(Opcode::Max, a, b), feed);
  LinuxcncProgram program = writeLinuxcncProgram(builder.finish(), circleOptions());
  ASSERT_THAT(program.errors, IsEmpty());
  std::vector<std::string> lines = linesOf(program.text);
  EXPECT_THAT(lines, Contains("o100 if [#<_m> LT #<_k>]"));
  EXPECT_THAT(lines, Contains("#32 = -[ABS[#<_k>] MOD ABS[#<_m>]]"));
  EXPECT_THAT(lines, Contains("G1 X#31 Y#32 Z#33 F100."));
}

TEST(LinuxcncProgram, AMacroIsASubroutineTakingTheParametersAsArguments) {
  LinuxcncProgramOptions options = circleOptions();
  options.callable = true;
  LinuxcncProgram program = writeLinuxcncProgram(circle(), options);
  ASSERT_THAT(program.errors, IsEmpty());
  std::vector<std::string> lines = linesOf(program.text);
  EXPECT_THAT(lines, Contains("; call: o<circle> call [5.] [1.]"));
  EXPECT_THAT(lines, Contains("o<circle> sub"));
  EXPECT_THAT(lines, Contains("#<_r> = #1"));
  EXPECT_THAT(lines, Contains("#<_d> = #2"));
  EXPECT_EQ(lines[lines.size() - 2], "o<circle> endsub");
}

TEST(LinuxcncProgram, ParameterNamesAvoidPredefinedOnesAndEachOther) {
  std::vector<std::string> names =
      linuxcncParameterNames({{"a", 1}, {"A", 2}, {"depth", 3}, {"feed", 4}});
  EXPECT_EQ(names, (std::vector<std::string>{"_a_", "_a__", "_depth", "_feed_"}));
}

TEST(LinuxcncProgram, SplitsLongExpressionsIntoParameters) {
  ir::FunctionBuilder builder("long");
  ValueId a = builder.parameter(builder.addParameter("k", 2));
  ValueId sum = a;
  for (int i = 0; i < 30; ++i) {
    ValueId term = builder.binary(Opcode::Mul, a, builder.constant(i + 0.123456789));
    sum = builder.binary(Opcode::Add, sum, term);
  }
  builder.feed(sum, a, a, builder.constant(100));
  LinuxcncProgram program = writeLinuxcncProgram(builder.finish(), circleOptions());
  ASSERT_THAT(program.errors, IsEmpty());
  for (const std::string& line : linesOf(program.text)) {
    EXPECT_LE(line.size(), 255u) << line;
  }
  EXPECT_THAT(program.text, HasSubstr("#31 = ["));
}

TEST(LinuxcncProgram, RefusesALineLongerThan255Characters) {
  ir::FunctionBuilder builder("long");
  ValueId a = builder.parameter(builder.addParameter(std::string(100, 'a'), 2));
  builder.feed(a, a, a, builder.constant(100));
  LinuxcncProgram program = writeLinuxcncProgram(builder.finish(), circleOptions());
  ASSERT_EQ(program.errors.size(), 1u);
  EXPECT_THAT(program.errors.front(), HasSubstr("LinuxCNC's 255 characters"));
  EXPECT_THAT(program.errors.front(), HasSubstr("the longest has 326"));
  EXPECT_TRUE(program.text.empty());
}

TEST(LinuxcncProgram, RefusesMoreValuesThanTheNumberedParameters) {
  ir::FunctionBuilder builder("table");
  std::uint32_t table = builder.addTable(std::vector<double>(5000, 1.5));
  ValueId zero = builder.constant(0);
  ValueId i = builder.beginLoop(zero, builder.constant(4999));
  builder.feed(builder.tableLoad(table, i), zero, zero, builder.constant(100));
  builder.endLoop();
  LinuxcncProgram program = writeLinuxcncProgram(builder.finish(), circleOptions());
  ASSERT_EQ(program.errors.size(), 1u);
  EXPECT_THAT(program.errors.front(), HasSubstr("4970"));
  EXPECT_TRUE(program.text.empty());
}

TEST(LinuxcncProgram, RefusesANumberThatIsNotFinite) {
  ir::FunctionBuilder builder("infinite");
  ValueId zero = builder.constant(0);
  builder.feed(builder.constant(std::numeric_limits<double>::infinity()), zero, zero,
               builder.constant(100));
  LinuxcncProgram program = writeLinuxcncProgram(builder.finish(), circleOptions());
  ASSERT_EQ(program.errors.size(), 1u);
  EXPECT_THAT(program.errors.front(), HasSubstr("inf"));
  EXPECT_TRUE(program.text.empty());
}

TEST(LinuxcncProgram, LongCommentsAreShortened) {
  ir::FunctionBuilder builder("comment");
  builder.comment(std::string(300, 'c'));
  LinuxcncProgram program = writeLinuxcncProgram(builder.finish(), circleOptions());
  ASSERT_THAT(program.errors, IsEmpty());
  EXPECT_THAT(linesOf(program.text), Contains("; " + std::string(253, 'c')));
}

TEST(LinuxcncProgram, BlendToleranceIsTheSmallestCutTolerance) {
  std::vector<ir::CutGeometry> cuts(3);
  cuts[0].tolerance = 0.01;
  cuts[1].tolerance = std::nan("");
  cuts[2].tolerance = 0.005;
  EXPECT_EQ(linuxcncBlendTolerance(cuts), 0.005);
  EXPECT_EQ(linuxcncBlendTolerance({}), ir::defaultTolerance);
}

} // namespace
} // namespace cncc::backends
