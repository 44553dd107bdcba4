// The IR core: builder, printer/parser round trip, verifier, interpreter.
#include "cncc/ir/builder.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/printer.h"
#include "cncc/ir/verifier.h"
#include "text_round_trip.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace cncc::ir {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;

// A square of side `side`, cut in passes of `step` down to `depth`: a loop
// over passes with a loop over corners reading a table.
Function squarePasses() {
  FunctionBuilder builder("square");
  std::uint32_t side = builder.addParameter("side", 10);
  std::uint32_t passes = builder.addParameter("passes", 2);
  std::uint32_t corners = builder.addTable({0, 1, 1, 0, 0});
  builder.comment("square \"passes\"");
  builder.tool(3, builder.constant(6));
  builder.spindle(builder.constant(3000));
  ValueId zero = builder.constant(0);
  ValueId one = builder.constant(1);
  ValueId sideValue = builder.parameter(side);
  ValueId pass = builder.beginLoop(one, builder.parameter(passes));
  ValueId z = builder.unary(Opcode::Neg, pass);
  builder.rapid(zero, zero, builder.constant(5));
  ValueId corner = builder.beginLoop(zero, builder.constant(4));
  ValueId x = builder.binary(Opcode::Mul, sideValue, builder.tableLoad(corners, corner));
  ValueId shifted = builder.binary(Opcode::Add, corner, builder.constant(1));
  ValueId wrapped = builder.binary(Opcode::Rem, shifted, builder.constant(5));
  ValueId y = builder.binary(Opcode::Mul, sideValue, builder.tableLoad(corners, wrapped));
  ValueId isFirst = builder.binary(Opcode::Eq, corner, zero);
  builder.beginIf(isFirst);
  builder.feed(x, y, z, builder.constant(100));
  builder.beginElse();
  builder.feed(x, y, z, builder.constant(300));
  builder.endIf();
  builder.endLoop();
  builder.endLoop();
  return builder.finish();
}

TEST(IrTest, BuiltFunctionVerifies) {
  EXPECT_THAT(verifyFunction(squarePasses()), IsEmpty());
}

TEST(IrTest, PrintParsePrintIsStable) {
  std::string text = printFunction(squarePasses());
  std::optional<Function> parsed = test_support::parsedBack(text);
  ASSERT_TRUE(parsed);
  EXPECT_THAT(verifyFunction(*parsed), IsEmpty());
  EXPECT_THAT(text, HasSubstr("func @square(side = 10, passes = 2) {"));
  EXPECT_THAT(text, HasSubstr("  table @0 = [0, 1, 1, 0, 0]"));
  EXPECT_THAT(text, HasSubstr("comment \"square \\\"passes\\\"\""));
}

// A parameter whose default was read as a constant says so in the text: the
// printed program checks it.
TEST(IrTest, AFixedParameterKeepsItsMarkThroughTheText) {
  Function function = squarePasses();
  function.parameters[1].fixed = true;
  std::string text = printFunction(function);
  EXPECT_THAT(text, HasSubstr("func @square(side = 10, passes = 2 fixed) {"));
  ParseError error;
  std::optional<Function> parsed = parseFunction(text, error);
  ASSERT_TRUE(parsed) << error.line << ": " << error.message;
  EXPECT_FALSE(parsed->parameters[0].fixed);
  EXPECT_TRUE(parsed->parameters[1].fixed);
  EXPECT_EQ(parsed->parameters[1].defaultValue, 2);
  EXPECT_EQ(printFunction(*parsed), text);
}

TEST(IrTest, InterpreterRunsLoopsTablesAndBranches) {
  ToolPath path = interpret(squarePasses());
  ASSERT_EQ(path.events.size(), 3u + 2 * 6);
  EXPECT_EQ(path.events[0].kind, MachineEvent::Kind::Comment);
  EXPECT_EQ(path.events[1].kind, MachineEvent::Kind::Tool);
  EXPECT_DOUBLE_EQ(path.events[1].number, 3);
  EXPECT_DOUBLE_EQ(path.events[1].diameter, 6);
  EXPECT_DOUBLE_EQ(path.events[2].number, 3000);
  const MachineEvent& first = path.events[4];
  EXPECT_EQ(first.kind, MachineEvent::Kind::Feed);
  EXPECT_DOUBLE_EQ(first.x, 0);
  EXPECT_DOUBLE_EQ(first.y, 10);
  EXPECT_DOUBLE_EQ(first.z, -1);
  EXPECT_DOUBLE_EQ(first.feed, 100);
  const MachineEvent& last = path.events.back();
  EXPECT_DOUBLE_EQ(last.x, 0);
  EXPECT_DOUBLE_EQ(last.y, 0);
  EXPECT_DOUBLE_EQ(last.z, -2);
  EXPECT_DOUBLE_EQ(last.feed, 300);
}

TEST(IrTest, InterpreterTakesParameterValues) {
  InterpreterOptions options;
  options.parameters = {{"side", 4}, {"passes", 3}};
  ToolPath path = interpret(squarePasses(), options);
  ASSERT_EQ(path.events.size(), 3u + 3 * 6);
  EXPECT_DOUBLE_EQ(path.events[5].x, 4);
  EXPECT_DOUBLE_EQ(path.events.back().z, -3);
}

TEST(IrTest, EmptyLoopRunsNothing) {
  FunctionBuilder builder("empty");
  ValueId zero = builder.constant(0);
  builder.beginLoop(builder.constant(3), builder.constant(2));
  builder.rapid(zero, zero, zero);
  builder.endLoop();
  EXPECT_THAT(interpret(builder.finish()).events, IsEmpty());
}

TEST(IrTest, InterpreterStopsRunawayPrograms) {
  FunctionBuilder builder("runaway");
  builder.beginLoop(builder.constant(0), builder.constant(1e15));
  builder.comment("again");
  builder.endLoop();
  InterpreterOptions options;
  options.maximumSteps = 1000;
  EXPECT_THROW(interpret(builder.finish(), options), InterpreterError);
}

TEST(IrTest, TableIndexOutOfRangeIsAnError) {
  FunctionBuilder builder("table");
  std::uint32_t table = builder.addTable({1, 2});
  ValueId value = builder.tableLoad(table, builder.constant(2));
  builder.rapid(value, value, value);
  EXPECT_THROW(interpret(builder.finish()), InterpreterError);
}

TEST(IrTest, MathMatchesTheStandardLibrary) {
  FunctionBuilder builder("math");
  ValueId a = builder.constant(0.3);
  ValueId b = builder.constant(-1.7);
  ValueId atan2 = builder.binary(Opcode::Atan2, a, b);
  ValueId power = builder.binary(Opcode::Pow, builder.constant(2), builder.constant(10));
  ValueId rounded = builder.unary(Opcode::Round, builder.constant(-2.5));
  ValueId chosen = builder.operation(
      Opcode::Select, {builder.binary(Opcode::Lt, a, b), builder.constant(1), builder.constant(2)});
  builder.feed(atan2, power, rounded, chosen);
  ToolPath path = interpret(builder.finish());
  ASSERT_EQ(path.events.size(), 1u);
  EXPECT_DOUBLE_EQ(path.events[0].x, std::atan2(0.3, -1.7));
  EXPECT_DOUBLE_EQ(path.events[0].y, 1024);
  EXPECT_DOUBLE_EQ(path.events[0].z, -3);
  EXPECT_DOUBLE_EQ(path.events[0].feed, 2);
}

TEST(IrTest, VerifierFindsValuesOutOfScope) {
  ParseError error;
  std::optional<Function> function = parseFunction(R"(func @scope() {
  %0 = const 0
  %1 = const 3
  %2 = loop %0, %1 {
    %3 = add %2, %1
  }
  move.rapid %3, %0, %0
}
)",
                                                   error);
  ASSERT_TRUE(function) << error.message;
  std::vector<std::string> problems = verifyFunction(*function);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_THAT(problems[0], HasSubstr("not visible"));
}

TEST(IrTest, VerifierFindsTypeErrors) {
  ParseError error;
  std::optional<Function> function = parseFunction(R"(func @types() {
  %0 = const 1
  %1 = const.bool true
  %2 = add %0, %1
  if %0 {
  }
}
)",
                                                   error);
  ASSERT_TRUE(function) << error.message;
  std::vector<std::string> problems = verifyFunction(*function);
  ASSERT_EQ(problems.size(), 2u);
  EXPECT_THAT(problems[0], HasSubstr("is bool, needs f64"));
  EXPECT_THAT(problems[1], HasSubstr("is f64, needs bool"));
}

TEST(IrTest, ParserReportsLineAndReason) {
  ParseError error;
  EXPECT_FALSE(parseFunction("func @bad() {\n  %0 = const 1\n  %1 = frobnicate %0\n}\n", error));
  EXPECT_EQ(error.line, 3);
  EXPECT_THAT(error.message, HasSubstr("unknown operation 'frobnicate'"));
  EXPECT_FALSE(parseFunction("func @bad() {\n  move.rapid %9, %9, %9\n}\n", error));
  EXPECT_THAT(error.message, HasSubstr("'%9' is not defined"));
  EXPECT_FALSE(parseFunction("func @open() {\n  %0 = const 1\n", error));
  EXPECT_THAT(error.message, HasSubstr("not closed"));
}

// u = 0, then u + max(u, 0.25) capped at 1: moves at 0.25, 0.5, 1.
constexpr const char* advancingLoopText = R"(func @advance() {
  %0 = const 0
  %1 = const 1
  %2 = const 0.25
  %3 = loop %0, %1 {
    %4 = max %3, %2
    %5 = add %3, %4
    %6 = min %5, %1
    move.feed %6, %3, %0, %1
    loop.next %6
  }
}
)";

TEST(IrTest, AnAdvancingLoopRunsWhileBelowItsBound) {
  ParseError error;
  std::optional<Function> function = parseFunction(advancingLoopText, error);
  ASSERT_TRUE(function) << error.message;
  EXPECT_THAT(verifyFunction(*function), IsEmpty());
  EXPECT_EQ(printFunction(*function), advancingLoopText);
  std::vector<std::pair<double, double>> moves;
  for (const MachineEvent& event : interpret(*function).events) {
    moves.emplace_back(event.x, event.y);
  }
  EXPECT_THAT(moves, ElementsAre(std::pair{0.25, 0.0}, std::pair{0.5, 0.25}, std::pair{1.0, 0.5}));
}

TEST(IrTest, ALoopThatDoesNotAdvanceIsAnError) {
  FunctionBuilder builder("stuck");
  ValueId zero = builder.constant(0);
  ValueId u = builder.beginLoop(zero, builder.constant(1));
  builder.rapid(u, u, u);
  builder.endLoopAdvancingTo(builder.binary(Opcode::Mul, u, zero));
  try {
    interpret(builder.finish());
    ADD_FAILURE() << "ran";
  } catch (const InterpreterError& failure) {
    EXPECT_THAT(failure.what(), HasSubstr("does not advance: 0 after 0"));
  }
}

TEST(IrTest, VerifierKeepsLoopNextAtTheEndOfALoopBody) {
  ParseError error;
  std::optional<Function> function = parseFunction(R"(func @misplaced() {
  %0 = const 0
  %1 = const 1
  loop.next %1
  %2 = loop %0, %1 {
    loop.next %1
    move.rapid %2, %0, %0
  }
}
)",
                                                   error);
  ASSERT_TRUE(function) << error.message;
  std::vector<std::string> problems = verifyFunction(*function);
  ASSERT_EQ(problems.size(), 2u);
  EXPECT_THAT(problems[0], HasSubstr("(loop.next) is not the last of a loop's body"));
  EXPECT_THAT(problems[1], HasSubstr("(loop.next) is not the last of a loop's body"));
}

TEST(IrTest, EveryOpcodeHasASpellingAndMeaning) {
  for (Opcode opcode : allOpcodes()) {
    EXPECT_FALSE(opcodeInfo(opcode).spelling.empty());
    EXPECT_FALSE(opcodeInfo(opcode).meaning.empty());
  }
}

} // namespace
} // namespace cncc::ir
