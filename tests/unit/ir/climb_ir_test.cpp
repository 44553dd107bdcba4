// move.climb in the IR: text round trip, verifier, and the rapid along Z
// alone that the interpreter records from where the tool is.
#include "cncc/ir/builder.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/printer.h"
#include "cncc/ir/tool_path.h"
#include "cncc/ir/verifier.h"
#include "text_round_trip.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace cncc::ir {
namespace {

using ::testing::HasSubstr;
using ::testing::IsEmpty;

// A climb at the start, a rapid to (3, 4, 1), then a climb to `safe`.
Function climbs() {
  FunctionBuilder builder("climbs");
  ValueId safe = builder.parameter(builder.addParameter("safe", 5));
  builder.climb(safe);
  builder.rapid(builder.constant(3), builder.constant(4), builder.constant(1));
  builder.climb(safe);
  return builder.finish();
}

TEST(ClimbIrTest, PrintsParsesAndVerifies) {
  Function function = climbs();
  EXPECT_THAT(verifyFunction(function), IsEmpty());
  std::string text = printFunction(function);
  EXPECT_THAT(text, HasSubstr("move.climb %0\n"));
  std::optional<Function> parsed = test_support::parsedBack(text);
  ASSERT_TRUE(parsed);
  ParseError wrong;
  EXPECT_FALSE(parseFunction("func @bad() {\n  %0 = const 1\n  move.climb %0, %0\n}\n", wrong));
}

TEST(ClimbIrTest, TheInterpreterMovesZAloneFromWhereTheToolIs) {
  InterpreterOptions options;
  options.parameters = {{"safe", 7}};
  std::vector<MachineEvent> events = interpret(climbs(), options).events;
  ASSERT_EQ(events.size(), 3u);
  for (std::size_t k : {0u, 2u}) {
    EXPECT_EQ(events[k].kind, MachineEvent::Kind::Rapid);
    EXPECT_TRUE(events[k].alongZ);
    EXPECT_EQ(events[k].z, 7);
  }
  EXPECT_FALSE(events[1].alongZ);
  EXPECT_EQ(events[0].x, 0); // where the interpreter starts
  EXPECT_EQ(events[0].y, 0);
  EXPECT_EQ(events[2].x, 3); // where the rapid left the tool
  EXPECT_EQ(events[2].y, 4);
}

} // namespace
} // namespace cncc::ir
