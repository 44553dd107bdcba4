// The compensation op: text round trip, verifier, interpreter events, and
// the tool centre's path (tool_centre_path.h) of a compensated square
// entered and left by lines, against the geometry worked by hand.
#include "cncc/ir/builder.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/printer.h"
#include "cncc/ir/tool_centre_path.h"
#include "cncc/ir/verifier.h"
#include "text_round_trip.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace cncc::ir {
namespace {

using ::testing::HasSubstr;
using ::testing::IsEmpty;
using Kind = MachineEvent::Kind;

// The programmed path: from (0, -10) a start-up line to (0, 0) with G41 of
// radius 2, then (20, 0), (20, 10) and a cancel line to (30, 10).
Function compensatedSteps() {
  FunctionBuilder builder("steps");
  auto c = [&](double value) { return builder.constant(value); };
  ValueId zero = c(0);
  ValueId feed = c(100);
  builder.rapid(zero, c(-10), zero);
  builder.compensation(2, 7);
  builder.feed(zero, zero, zero, feed);
  builder.feed(c(20), zero, zero, feed);
  builder.feed(c(20), c(10), zero, feed);
  builder.compensation(0, 0);
  builder.feed(c(30), c(10), zero, feed);
  return builder.finish();
}

std::vector<MachineEvent> movesOf(const ToolPath& path) {
  std::vector<MachineEvent> moves;
  for (const MachineEvent& event : path.events) {
    if (event.kind == Kind::Feed || event.kind == Kind::Arc || event.kind == Kind::Rapid) {
      moves.push_back(event);
    }
  }
  return moves;
}

TEST(CompensationIrTest, PrintsParsesAndVerifies) {
  Function function = compensatedSteps();
  EXPECT_THAT(verifyFunction(function), IsEmpty());
  std::string text = printFunction(function);
  EXPECT_THAT(text, HasSubstr("compensation left 7 2\n"));
  EXPECT_THAT(text, HasSubstr("compensation off\n"));
  std::optional<Function> parsed = test_support::parsedBack(text);
  ASSERT_TRUE(parsed);
  ParseError error;
  EXPECT_FALSE(parseFunction("func @f() {\n  compensation up 1 2\n}\n", error));
  EXPECT_THAT(error.message, HasSubstr("compensation left|right"));
}

TEST(CompensationIrTest, VerifierWantsARegisterWithAnOffset) {
  FunctionBuilder builder("bad");
  builder.compensation(2, 0);
  EXPECT_THAT(verifyFunction(builder.finish()), testing::Contains(HasSubstr("radius register")));
}

TEST(CompensationIrTest, InterpreterRecordsTheProgrammedPath) {
  ToolPath path = interpret(compensatedSteps());
  ASSERT_EQ(path.events[1].kind, Kind::Compensation);
  EXPECT_EQ(path.events[1].number, 2);
  EXPECT_EQ(path.events[1].offsetRegister, 7u);
  EXPECT_EQ(movesOf(path).size(), 5u);
}

TEST(CompensationIrTest, ToolCentreRunsBesideTheSteps) {
  std::vector<MachineEvent> moves = movesOf(toolCentrePath(interpret(compensatedSteps())));
  // Rapid, start-up, the first step offset up by 2, the concave corner cut
  // back to (18, 2), the second step offset left, the cancel line.
  ASSERT_EQ(moves.size(), 5u);
  EXPECT_NEAR(moves[1].x, 0, 1e-12); // start-up to the first offset start
  EXPECT_NEAR(moves[1].y, 2, 1e-12);
  EXPECT_NEAR(moves[2].x, 18, 1e-12); // concave corner: the offsets cross
  EXPECT_NEAR(moves[2].y, 2, 1e-12);
  EXPECT_NEAR(moves[3].x, 18, 1e-12);
  EXPECT_NEAR(moves[3].y, 10, 1e-12);
  EXPECT_NEAR(moves[4].x, 30, 1e-12); // cancel: to the uncompensated end
  EXPECT_NEAR(moves[4].y, 10, 1e-12);
}

TEST(CompensationIrTest, ConvexCornerGetsAnArcOfTheRadius) {
  FunctionBuilder builder("convex");
  auto c = [&](double value) { return builder.constant(value); };
  ValueId zero = c(0);
  ValueId feed = c(100);
  builder.rapid(zero, c(-10), zero);
  builder.compensation(-2, 1); // right: the corner at (20, 0) is convex
  builder.feed(zero, zero, zero, feed);
  builder.feed(c(20), zero, zero, feed);
  builder.feed(c(20), c(10), zero, feed);
  builder.compensation(0, 0);
  builder.feed(c(30), c(10), zero, feed);
  std::vector<MachineEvent> moves = movesOf(toolCentrePath(interpret(builder.finish())));
  ASSERT_EQ(moves.size(), 6u);
  EXPECT_EQ(moves[3].kind, Kind::Arc);
  EXPECT_NEAR(moves[3].centreX, 20, 1e-12);
  EXPECT_NEAR(moves[3].centreY, 0, 1e-12);
  EXPECT_NEAR(moves[3].x, 22, 1e-12);
  EXPECT_NEAR(moves[3].y, 0, 1e-12);
}

// The convex corner of ConvexCornerGetsAnArcOfTheRadius with G39 at it:
// the op prints, parses and is recorded with its direction; the tool centre
// is the same (the offset already goes round convex corners on that arc).
TEST(CompensationIrTest, CornerArcAtAConvexCorner) {
  FunctionBuilder builder("corner");
  auto c = [&](double value) { return builder.constant(value); };
  ValueId zero = c(0);
  ValueId feed = c(100);
  builder.rapid(zero, c(-10), zero);
  builder.compensation(-2, 1);
  builder.feed(zero, zero, zero, feed);
  builder.feed(c(20), zero, zero, feed);
  builder.cornerArc(zero, c(10));
  builder.feed(c(20), c(10), zero, feed);
  builder.compensation(0, 0);
  builder.feed(c(30), c(10), zero, feed);
  Function function = builder.finish();
  EXPECT_THAT(verifyFunction(function), IsEmpty());
  std::string text = printFunction(function);
  EXPECT_THAT(text, HasSubstr("corner.arc %"));
  std::optional<Function> parsed = test_support::parsedBack(text);
  ASSERT_TRUE(parsed);
  ToolPath path = interpret(function);
  auto corner = std::find_if(path.events.begin(), path.events.end(), [](const MachineEvent& event) {
    return event.kind == Kind::CornerArc;
  });
  ASSERT_NE(corner, path.events.end());
  EXPECT_EQ(corner->x, 0);
  EXPECT_EQ(corner->y, 10);
  ToolPath centre = toolCentrePath(path);
  for (const MachineEvent& event : centre.events) {
    EXPECT_NE(event.kind, Kind::CornerArc);
  }
  std::vector<MachineEvent> moves = movesOf(centre);
  ASSERT_EQ(moves.size(), 6u);
  EXPECT_EQ(moves[3].kind, Kind::Arc);
  EXPECT_NEAR(moves[3].x, 22, 1e-12);
}

TEST(CompensationIrTest, CornerArcWithoutCompensationIsRefused) {
  FunctionBuilder builder("loose");
  ValueId zero = builder.constant(0);
  builder.feed(builder.constant(5), zero, zero, builder.constant(100));
  builder.cornerArc(zero, builder.constant(1));
  EXPECT_THROW(toolCentrePath(interpret(builder.finish())), InterpreterError);
}

TEST(CompensationIrTest, RefusedRatherThanGuessed) {
  FunctionBuilder builder("open");
  ValueId zero = builder.constant(0);
  builder.compensation(2, 1);
  builder.feed(builder.constant(5), zero, zero, builder.constant(100));
  EXPECT_THROW(toolCentrePath(interpret(builder.finish())), InterpreterError);
  FunctionBuilder plunge("plunge");
  auto c = [&](double value) { return plunge.constant(value); };
  plunge.compensation(2, 1);
  plunge.feed(c(5), c(0), c(0), c(100));
  plunge.feed(c(5), c(0), c(-1), c(100));
  plunge.feed(c(9), c(0), c(-1), c(100));
  plunge.compensation(0, 0);
  plunge.feed(c(9), c(5), c(-1), c(100));
  EXPECT_THROW(toolCentrePath(interpret(plunge.finish())), InterpreterError);
}

} // namespace
} // namespace cncc::ir
