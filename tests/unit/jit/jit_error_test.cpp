// The JIT stops where the interpreter stops, with the same message: a table
// index out of range, a loop bound that is not finite, one step more than
// the limit. A Function that does not verify is not compiled, nor one with
// a curve.lap.
#include "jit_test_support.h"

#include "cncc/ir/builder.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace cncc {
namespace {

using ir::FunctionBuilder;
using ir::Opcode;
using ir::ValueId;
using ::testing::HasSubstr;

ir::InterpreterOptions withParameter(const std::string& name, double value) {
  ir::InterpreterOptions options;
  options.parameters[name] = value;
  return options;
}

// Reads table {10, 20, 30} at the parameter `index`, after a first move.
ir::Function tableReader() {
  FunctionBuilder builder("table");
  std::uint32_t table = builder.addTable({10, 20, 30});
  std::uint32_t index = builder.addParameter("index", 0);
  ValueId zero = builder.constant(0);
  builder.rapid(zero, zero, zero);
  ValueId element = builder.tableLoad(table, builder.parameter(index));
  builder.feed(element, zero, zero, builder.constant(100));
  return builder.finish();
}

TEST(JitErrors, TableIndexOutOfRangeIsTheInterpretersError) {
  ir::Function function = tableReader();
  backends::CompiledFunction compiled(function);
  for (double index : {3.0, -1.0, -0.5, 1e20, std::numeric_limits<double>::quiet_NaN(),
                       std::numeric_limits<double>::infinity()}) {
    ir::InterpreterOptions options = withParameter("index", index);
    jit_test::RunOutcome outcome = jit_test::outcomeOf([&] { return compiled.run(options); });
    EXPECT_TRUE(outcome.failed) << "index " << index;
    EXPECT_THAT(outcome.error, HasSubstr("outside table @0 of 3 entries"));
    EXPECT_TRUE(jit_test::sameOutcome(
        jit_test::outcomeOf([&] { return ir::interpret(function, options); }), outcome));
  }
}

TEST(JitErrors, FractionalTableIndexIsTruncatedAsInTheInterpreter) {
  ir::Function function = tableReader();
  backends::CompiledFunction compiled(function);
  ir::ToolPath path = compiled.run(withParameter("index", 2.9));
  ASSERT_EQ(path.events.size(), 2u);
  EXPECT_EQ(path.events[1].x, 30);
  EXPECT_TRUE(jit_test::jitMatchesInterpreter(function, withParameter("index", 0.5)));
}

TEST(JitErrors, LoopBoundThatIsNotFiniteIsTheInterpretersError) {
  FunctionBuilder builder("bounds");
  std::uint32_t high = builder.addParameter("high", 2);
  ValueId i = builder.beginLoop(builder.constant(0), builder.parameter(high));
  builder.rapid(i, i, i);
  builder.endLoop();
  ir::Function function = builder.finish();
  backends::CompiledFunction compiled(function);
  for (double bound :
       {std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
        std::numeric_limits<double>::quiet_NaN()}) {
    ir::InterpreterOptions options = withParameter("high", bound);
    jit_test::RunOutcome outcome = jit_test::outcomeOf([&] { return compiled.run(options); });
    EXPECT_EQ(outcome.error, "a loop bound is not a finite number");
    EXPECT_TRUE(jit_test::sameOutcome(
        jit_test::outcomeOf([&] { return ir::interpret(function, options); }), outcome));
  }
  EXPECT_EQ(compiled.run().events.size(), 3u);
}

// Loops, an if and table loads that fail on the last pass: for every step
// limit around the program's length, the JIT finishes or stops exactly as
// the interpreter does, with the same message.
TEST(JitErrors, StepLimitIsExactlyTheInterpreters) {
  FunctionBuilder builder("steps");
  std::uint32_t table = builder.addTable({1, 2, 3, 4});
  std::uint32_t passes = builder.addParameter("passes", 3);
  ValueId zero = builder.constant(0);
  ValueId pass = builder.beginLoop(builder.constant(1), builder.parameter(passes));
  builder.comment("pass");
  ValueId index = builder.beginLoop(zero, builder.constant(3));
  ValueId value = builder.tableLoad(table, builder.binary(Opcode::Add, index, pass));
  builder.beginIf(builder.binary(Opcode::Gt, value, builder.constant(2)));
  builder.feed(value, pass, zero, builder.constant(10));
  builder.beginElse();
  builder.rapid(value, pass, zero);
  builder.endIf();
  builder.endLoop();
  builder.endLoop();
  ir::Function function = builder.finish();
  backends::CompiledFunction compiled(function);

  int finished = 0;
  int stoppedByLimit = 0;
  for (double passCount : {0.0, 1.0, 3.0}) {
    for (std::size_t limit = 0; limit <= 120; ++limit) {
      ir::InterpreterOptions options = withParameter("passes", passCount);
      options.maximumSteps = limit;
      jit_test::RunOutcome interpreted =
          jit_test::outcomeOf([&] { return ir::interpret(function, options); });
      jit_test::RunOutcome jitted = jit_test::outcomeOf([&] { return compiled.run(options); });
      EXPECT_TRUE(jit_test::sameOutcome(interpreted, jitted))
          << "passes " << passCount << ", limit " << limit;
      finished += interpreted.failed ? 0 : 1;
      stoppedByLimit += interpreted.error.find("steps") != std::string::npos ? 1 : 0;
    }
  }
  // The sweep saw all three endings: finished, step limit, table index.
  EXPECT_GT(finished, 0);
  EXPECT_GT(stoppedByLimit, 0);
  EXPECT_THAT(jit_test::outcomeOf([&] { return compiled.run(); }).error,
              HasSubstr("outside table"));
}

TEST(JitErrors, RunawayLoopStopsAtTheLimit) {
  FunctionBuilder builder("runaway");
  builder.beginLoop(builder.constant(0), builder.constant(1e15));
  builder.comment("again");
  builder.endLoop();
  ir::InterpreterOptions options;
  options.maximumSteps = 100'000;
  jit_test::RunOutcome outcome =
      jit_test::outcomeOf([&] { return backends::runJit(builder.function(), options); });
  EXPECT_EQ(outcome.error, "the program takes more than 100000 steps");
  EXPECT_TRUE(jit_test::jitMatchesInterpreter(builder.finish(), options));
}

TEST(JitErrors, FunctionThatDoesNotVerifyIsNotCompiled) {
  FunctionBuilder builder("broken");
  ValueId zero = builder.constant(0);
  builder.rapid(zero, zero, zero);
  ir::Function function = builder.finish();
  function.instructions.back().operands.pop_back();
  EXPECT_THROW(backends::CompiledFunction{function}, backends::JitError);
}

// The target pipeline expands laps first; one left over is refused, not run.
TEST(JitErrors, CurveLapIsRefusedUntilExpanded) {
  FunctionBuilder builder("lap");
  ir::CurveTableEntry entry;
  entry.pieces = {{0, 0, 1}};
  entry.sampling = ir::CurveSampling::Samples;
  entry.amount = 4;
  std::uint32_t curve = builder.addCurve(entry);
  ValueId zero = builder.constant(0);
  ValueId t = builder.beginCurveLap(curve, zero, zero, builder.constant(100));
  builder.curvePoint(t, zero, zero);
  ir::Function function = builder.finish();
  ASSERT_EQ(ir::interpret(function).events.size(), 3u); // it is a valid function
  try {
    backends::CompiledFunction compiled(function);
    FAIL() << "compiled";
  } catch (const backends::JitError& error) {
    EXPECT_THAT(error.what(), HasSubstr("curve.lap must be expanded"));
  }
}

TEST(JitErrors, JitIsAvailableOnThisHost) {
  EXPECT_TRUE(backends::jitAvailable());
}

} // namespace
} // namespace cncc
