// unroll-no-larger on a function of hundreds of loops (a part of thousands
// of cuts has a pass loop each): the trials go in groups, and what is kept
// still leaves the function no larger and runs the same path.
#include "cncc/ir/builder.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/verifier.h"

#include <gtest/gtest.h>

namespace cncc::ir {
namespace {

// `loops` loops: every tenth of eight trips, its feed move reading the
// index and a parameter (unrolling it makes the function larger), the
// others of `trips` trips, a feed move at a fixed point.
Function manyLoops(std::size_t loops, double trips) {
  FunctionBuilder builder("many");
  ValueId scale = builder.parameter(builder.addParameter("scale", 2));
  ValueId zero = builder.constant(0);
  ValueId feed = builder.constant(300);
  for (std::size_t k = 0; k < loops; ++k) {
    bool long_ = k % 10 == 0;
    ValueId last = builder.constant(long_ ? 8 : trips);
    ValueId index = builder.beginLoop(builder.constant(1), last);
    ValueId x = long_ ? builder.binary(Opcode::Mul, index, scale) : scale;
    builder.feed(x, builder.constant(static_cast<double>(k)), zero, feed);
    builder.endLoop();
  }
  return builder.finish();
}

// The size fold, cse and dce leave (what unroll-no-larger compares).
std::size_t cleanedUpSize(Function function) {
  foldConstants(function);
  eliminateCommonSubexpressions(function);
  eliminateDeadCode(function);
  return instructionCount(function);
}

std::size_t loopCount(const Function& function) {
  std::size_t count = 0;
  for (InstructionId id : function.body.instructions) {
    count += function.instructions[id].opcode == Opcode::Loop ? 1 : 0;
  }
  return count;
}

void expectSamePath(const ToolPath& before, const ToolPath& after) {
  ASSERT_EQ(before.events.size(), after.events.size());
  for (std::size_t k = 0; k < before.events.size(); ++k) {
    EXPECT_EQ(before.events[k].x, after.events[k].x) << k;
    EXPECT_EQ(before.events[k].y, after.events[k].y) << k;
  }
}

// 300 loops of two trips: trials in groups (300 times the function's size is
// past the 100,000 instructions the trials may copy here); the groups holding
// a loop of eight trips are not kept, the others are.
TEST(UnrollNoLarger, ManyLoopsAreTriedInGroupsAndStayNoLarger) {
  Function function = manyLoops(300, 2);
  ASSERT_TRUE(verifyFunction(function).empty());
  ToolPath before = interpret(function);
  std::size_t sizeBefore = cleanedUpSize(function);
  UnrollOptions options;
  options.onlyWhenNoLarger = true;
  options.maximumTrialInstructions = 100'000;
  EXPECT_TRUE(unrollLoops(function, options));
  EXPECT_TRUE(verifyFunction(function).empty());
  EXPECT_LE(cleanedUpSize(function), sizeBefore);
  EXPECT_LT(loopCount(function), 300u);
  EXPECT_GE(loopCount(function), 30u); // every loop of eight trips stays
  expectSamePath(before, interpret(function));
}

// A loop of one trip is never larger written out: each is, beside loops of
// eight trips that stay.
TEST(UnrollNoLarger, LoopsOfOneTripAreWrittenOut) {
  Function function = manyLoops(300, 1);
  ToolPath before = interpret(function);
  std::size_t sizeBefore = cleanedUpSize(function);
  UnrollOptions options;
  options.onlyWhenNoLarger = true;
  EXPECT_TRUE(unrollLoops(function, options));
  EXPECT_TRUE(verifyFunction(function).empty());
  EXPECT_LE(cleanedUpSize(function), sizeBefore);
  EXPECT_EQ(loopCount(function), 30u);
  expectSamePath(before, interpret(function));
}

// Only loops of one trip: written out without a trial.
TEST(UnrollNoLarger, OnlyLoopsOfOneTrip) {
  FunctionBuilder builder("once");
  ValueId zero = builder.constant(0);
  ValueId feed = builder.constant(300);
  for (int k = 0; k < 5; ++k) {
    ValueId index = builder.beginLoop(builder.constant(k), builder.constant(k));
    builder.feed(index, zero, zero, feed);
    builder.endLoop();
  }
  Function function = builder.finish();
  ToolPath before = interpret(function);
  UnrollOptions options;
  options.onlyWhenNoLarger = true;
  EXPECT_TRUE(unrollLoops(function, options));
  EXPECT_TRUE(verifyFunction(function).empty());
  EXPECT_EQ(loopCount(function), 0u);
  expectSamePath(before, interpret(function));
}

} // namespace
} // namespace cncc::ir
