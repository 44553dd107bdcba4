// move.arc in the IR: text round trip, verifier, interpreter, the traits of
// the operation table, and arcs flattened into chords.
#include "cncc/ir/builder.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/printer.h"
#include "cncc/ir/tool_path.h"
#include "cncc/ir/verifier.h"
#include "text_round_trip.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace cncc::ir {
namespace {

using ::testing::HasSubstr;
using ::testing::IsEmpty;

constexpr double pi = std::numbers::pi;

// From (10, 0): a clockwise quarter to (0, -10), then one helical turn
// counter-clockwise about the origin down to z = -3.
Function quarterAndHelix() {
  FunctionBuilder builder("arcs");
  ValueId radius = builder.parameter(builder.addParameter("radius", 10));
  ValueId zero = builder.constant(0);
  ValueId feed = builder.constant(300);
  ValueId below = builder.unary(Opcode::Neg, radius);
  builder.rapid(radius, zero, zero);
  builder.arc(ArcTurn::Clockwise, zero, below, zero, below, zero, feed);
  builder.arc(ArcTurn::CounterClockwise, zero, below, builder.constant(-3), zero, radius, feed);
  return builder.finish();
}

TEST(ArcIrTest, PrintsParsesAndVerifies) {
  Function function = quarterAndHelix();
  EXPECT_THAT(verifyFunction(function), IsEmpty());
  std::string text = printFunction(function);
  EXPECT_THAT(text, HasSubstr("move.arc cw %"));
  EXPECT_THAT(text, HasSubstr("move.arc ccw %"));
  std::optional<Function> parsed = test_support::parsedBack(text);
  ASSERT_TRUE(parsed);
  EXPECT_THAT(verifyFunction(*parsed), IsEmpty());
}

TEST(ArcIrTest, ParserWantsADirectionAndSixOperands) {
  ParseError error;
  std::string head = "func @f() {\n  %0 = const 1\n";
  EXPECT_FALSE(parseFunction(head + "  move.arc left %0, %0, %0, %0, %0, %0\n}\n", error));
  EXPECT_EQ(error.line, 3);
  EXPECT_THAT(error.message, HasSubstr("'move.arc cw' or 'move.arc ccw'"));
  EXPECT_FALSE(parseFunction(head + "  move.arc cw %0, %0, %0\n}\n", error));
  EXPECT_THAT(error.message, HasSubstr("takes 6 operands"));
}

TEST(ArcIrTest, VerifierRejectsAnUnknownDirection) {
  Function function = quarterAndHelix();
  for (Instruction& instruction : function.instructions) {
    if (instruction.opcode == Opcode::Arc) {
      instruction.index = 7;
    }
  }
  std::vector<std::string> problems = verifyFunction(function);
  ASSERT_FALSE(problems.empty());
  EXPECT_THAT(problems.front(), HasSubstr("neither clockwise nor counter-clockwise"));
}

TEST(ArcIrTest, InterpreterRecordsCentresFromTheCurrentPosition) {
  ToolPath path = interpret(quarterAndHelix());
  ASSERT_EQ(path.events.size(), 3u);
  const MachineEvent& quarter = path.events[1];
  EXPECT_EQ(quarter.kind, MachineEvent::Kind::Arc);
  EXPECT_TRUE(quarter.clockwise);
  EXPECT_DOUBLE_EQ(quarter.centreX, 0);
  EXPECT_DOUBLE_EQ(quarter.centreY, 0);
  const MachineEvent& helix = path.events[2];
  EXPECT_FALSE(helix.clockwise);
  EXPECT_DOUBLE_EQ(helix.centreX, 0);
  EXPECT_DOUBLE_EQ(helix.centreY, 0);
  EXPECT_DOUBLE_EQ(helix.z, -3);
  EXPECT_DOUBLE_EQ(arcSweep(0, -10, helix), 2 * pi); // ends where it starts
  EXPECT_DOUBLE_EQ(arcSweep(10, 0, quarter), pi / 2);
}

TEST(ArcIrTest, InterpreterRefusesAnArcWithoutARadiusOrOffItsCircle) {
  InterpreterOptions options;
  options.parameters["radius"] = 0;
  EXPECT_THROW(interpret(quarterAndHelix(), options), InterpreterError);
  EXPECT_THROW(arcMove({10, 0, 0}, ArcTurn::Clockwise, 0, -12, 0, -10, 0, 100), InterpreterError);
  MachineEvent fine = arcMove({10, 0, 0}, ArcTurn::Clockwise, 0, -10, 0, -10, 0, 100);
  EXPECT_DOUBLE_EQ(fine.centreX, 0);
}

TEST(ArcIrTest, FlattenedArcsStayOnTheHelixWithinTheSagitta) {
  ToolPath flat = flattenArcs(interpret(quarterAndHelix()), 1e-3);
  // Every chord end lies on the circle, and the helix's z follows its angle.
  std::size_t helixPoints = 0;
  for (const MachineEvent& event : flat.events) {
    ASSERT_NE(event.kind, MachineEvent::Kind::Arc);
    EXPECT_NEAR(std::hypot(event.x, event.y), 10, 1e-9);
    helixPoints += event.z < 0 ? 1 : 0;
  }
  // A chord of angle a sags 10 (1 - cos(a / 2)) <= 1e-3: a <= 0.02828 rad.
  EXPECT_GE(helixPoints, static_cast<std::size_t>(2 * pi / 0.02829));
  EXPECT_DOUBLE_EQ(flat.events.back().z, -3);
}

TEST(ArcIrTest, AnAlarmStopsTheRunWithItsText) {
  FunctionBuilder builder("guarded");
  ValueId radius = builder.parameter(builder.addParameter("radius", 2));
  builder.beginIf(builder.binary(Opcode::Le, radius, builder.constant(0)));
  builder.alarm("no \"radius\"");
  builder.endIf();
  builder.rapid(radius, radius, radius);
  Function function = builder.finish();
  std::string text = printFunction(function);
  EXPECT_THAT(text, HasSubstr("alarm \"no \\\"radius\\\"\""));
  ParseError error;
  std::optional<Function> parsed = parseFunction(text, error);
  ASSERT_TRUE(parsed) << error.message;
  EXPECT_EQ(printFunction(*parsed), text);
  EXPECT_EQ(interpret(function).events.size(), 1u);
  InterpreterOptions options;
  options.parameters["radius"] = -1;
  try {
    interpret(*parsed, options);
    ADD_FAILURE() << "no alarm";
  } catch (const InterpreterError& alarm) {
    EXPECT_STREQ(alarm.what(), "alarm: no \"radius\"");
  }
}

TEST(ArcIrTest, TraitsComeFromTheOperationTable) {
  EXPECT_TRUE(isEffect(Opcode::Arc));
  EXPECT_TRUE(isEffect(Opcode::Feed));
  EXPECT_FALSE(isPure(Opcode::Arc));
  EXPECT_TRUE(isPure(Opcode::Sin));
  EXPECT_TRUE(isPure(Opcode::TableLoad));
  EXPECT_TRUE(mayFail(Opcode::TableLoad));
  EXPECT_FALSE(mayFail(Opcode::Add));
  EXPECT_FALSE(isPure(Opcode::Loop));
  EXPECT_FALSE(isEffect(Opcode::If));
  for (Opcode opcode : allOpcodes()) {
    // An operation without a result that is not control flow does something.
    const OpcodeInfo& info = opcodeInfo(opcode);
    if (info.result == ValueType::None && info.traits != OpcodeTraits::Control) {
      EXPECT_TRUE(isEffect(opcode)) << info.spelling;
    }
  }
}

} // namespace
} // namespace cncc::ir
