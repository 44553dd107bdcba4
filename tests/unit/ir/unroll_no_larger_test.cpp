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

// `loops` loops of one trip (unrolling one leaves the function smaller),
// each with a feed move that reads a parameter, every tenth of eight trips.
Function manyLoops(std::size_t loops) {
  FunctionBuilder builder("many");
  ValueId scale = builder.parameter(builder.addParameter("scale", 2));
  ValueId zero = builder.constant(0);
  ValueId feed = builder.constant(300);
  for (std::size_t k = 0; k < loops; ++k) {
    ValueId last = builder.constant(k % 10 == 0 ? 8 : 1);
    ValueId index = builder.beginLoop(builder.constant(1), last);
    ValueId x = builder.binary(Opcode::Mul, index, scale);
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

TEST(UnrollNoLarger, ManyLoopsAreTriedInGroupsAndStayNoLarger) {
  Function function = manyLoops(800);
  ASSERT_TRUE(verifyFunction(function).empty());
  ToolPath before = interpret(function);
  std::size_t sizeBefore = cleanedUpSize(function);
  UnrollOptions options;
  options.onlyWhenNoLarger = true;
  EXPECT_TRUE(unrollLoops(function, options));
  EXPECT_TRUE(verifyFunction(function).empty());
  EXPECT_LE(cleanedUpSize(function), sizeBefore);
  EXPECT_LT(loopCount(function), 800u);
  ToolPath after = interpret(function);
  ASSERT_EQ(before.events.size(), after.events.size());
  for (std::size_t k = 0; k < before.events.size(); ++k) {
    EXPECT_EQ(before.events[k].x, after.events[k].x) << k;
    EXPECT_EQ(before.events[k].y, after.events[k].y) << k;
  }
}

} // namespace
} // namespace cncc::ir
