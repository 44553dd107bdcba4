// move.nurbs in the IR: text round trip, the verifier's check of its block
// data, and the interpreter following the curve the controller cuts.
#include "cncc/geom/nurbs_curve.h"
#include "cncc/ir/builder.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/nurbs_move.h"
#include "cncc/ir/printer.h"
#include "cncc/ir/verifier.h"
#include "text_round_trip.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

namespace cncc::ir {
namespace {

using ::testing::HasSubstr;
using ::testing::IsEmpty;

// A quadratic NURBS from (0, 0) over (10, 10) to (20, 0), its middle weight
// the part parameter w; cut at z = -1 from a plunge onto its first point.
geom::NurbsCurve quadratic(double middleWeight) {
  return geom::NurbsCurve(geom::KnotVector({0, 0, 0, 1, 1, 1}, 2),
                          {{0, 0, 0}, {10, 10, 0}, {20, 0, 0}}, {1, middleWeight, 1});
}

Function nurbsPart() {
  FunctionBuilder builder("nurbs");
  ValueId weight = builder.parameter(builder.addParameter("w", 2));
  std::uint32_t table = builder.addTable(nurbsMoveTable(quadratic(1)));
  ValueId zero = builder.constant(0);
  ValueId one = builder.constant(1);
  ValueId depth = builder.constant(-1);
  ValueId feed = builder.constant(300);
  builder.rapid(zero, zero, builder.constant(5));
  builder.feed(zero, zero, depth, feed);
  builder.nurbs(table, depth, feed, {one, weight, one});
  return builder.finish();
}

TEST(NurbsIrTest, PrintsParsesAndVerifies) {
  Function function = nurbsPart();
  EXPECT_THAT(verifyFunction(function), IsEmpty());
  std::string text = printFunction(function);
  EXPECT_THAT(text, HasSubstr("move.nurbs @0, %"));
  std::optional<Function> parsed = test_support::parsedBack(text);
  ASSERT_TRUE(parsed);
  EXPECT_THAT(verifyFunction(*parsed), IsEmpty());
}

TEST(NurbsIrTest, VerifierChecksTheBlockDataAgainstTheWeights) {
  Function function = nurbsPart();
  function.tables[0].pop_back(); // one coordinate short
  std::vector<std::string> problems = verifyFunction(function);
  ASSERT_FALSE(problems.empty());
  EXPECT_THAT(problems.front(), HasSubstr("does not hold order 3, 6 knots and 3 control points"));
  Function noTable = nurbsPart();
  noTable.tables.clear();
  ASSERT_FALSE(verifyFunction(noTable).empty());
  EXPECT_THAT(verifyFunction(noTable).front(), HasSubstr("table 0, which does not exist"));
}

TEST(NurbsIrTest, ParserWantsATableAndOperands) {
  ParseError error;
  EXPECT_FALSE(parseFunction("func @f() {\n  %0 = const 1\n  move.nurbs %0, %0\n}\n", error));
  EXPECT_EQ(error.line, 3);
  EXPECT_THAT(error.message, HasSubstr("move.nurbs @n"));
}

// The interpreter cuts the curve with the weight the run gives (an edit at
// the machine), within the chords' 1e-5, ending at the last control point.
TEST(NurbsIrTest, InterpreterFollowsTheCurveWithTheRunsWeight) {
  Function function = nurbsPart();
  for (double weight : {2.0, 0.5}) {
    InterpreterOptions options;
    options.parameters["w"] = weight;
    ToolPath path = interpret(function, options);
    geom::NurbsCurve curve = quadratic(weight);
    ASSERT_GT(path.events.size(), 10u);
    const MachineEvent& last = path.events.back();
    EXPECT_NEAR(last.x, 20, 1e-12);
    EXPECT_NEAR(last.z, -1, 1e-12);
    // The chords' vertices lie on the curve (at z = -1), and they bend.
    double largestY = 0;
    for (std::size_t i = 2; i < path.events.size(); ++i) {
      const MachineEvent& event = path.events[i];
      EXPECT_EQ(event.kind, MachineEvent::Kind::Feed);
      EXPECT_EQ(event.feed, 300);
      largestY = std::max(largestY, event.y);
    }
    EXPECT_NEAR(largestY, curve.point(0.5).y(), 1e-4) << weight;
  }
}

TEST(NurbsIrTest, InterpreterStopsWhereAControllerAlarms) {
  Function function = nurbsPart();
  InterpreterOptions options;
  options.parameters["w"] = 0; // no NURBS has a weight of 0
  EXPECT_THROW(interpret(function, options), InterpreterError);
  Function elsewhere = nurbsPart();
  elsewhere.tables[0][1 + 6] = 3; // the first control point is not where the tool is
  try {
    interpret(elsewhere);
    FAIL() << "expected an error";
  } catch (const InterpreterError& error) {
    EXPECT_THAT(error.what(), HasSubstr("not at its first control point"));
  }
}

// Keeps what it is handed: the events of a run, one at a time.
class EventList : public MachineEventSink {
public:
  void event(const MachineEvent& event) override { events.push_back(event); }
  std::vector<MachineEvent> events;
};

TEST(NurbsIrTest, ASinkIsHandedTheEventsTheToolPathHolds) {
  Function function = nurbsPart();
  ToolPath path = interpret(function);
  EventList sink;
  interpret(function, sink);
  ASSERT_EQ(sink.events.size(), path.events.size());
  ASSERT_GT(path.events.size(), 10u); // the block's points are many events
  for (std::size_t k = 0; k < path.events.size(); ++k) {
    EXPECT_EQ(sink.events[k].kind, path.events[k].kind) << k;
    EXPECT_EQ(sink.events[k].x, path.events[k].x) << k;
    EXPECT_EQ(sink.events[k].y, path.events[k].y) << k;
    EXPECT_EQ(sink.events[k].z, path.events[k].z) << k;
  }
}

TEST(NurbsIrTest, ARunKeepsAtMostItsLimitOfEvents) {
  Function function = nurbsPart();
  std::size_t events = interpret(function).events.size();
  InterpreterOptions options;
  options.maximumEvents = events - 1;
  EXPECT_THROW(interpret(function, options), InterpreterError);
  options.maximumEvents = events;
  EXPECT_EQ(interpret(function, options).events.size(), events);
  // A sink keeps none: the limit is not its.
  EventList sink;
  options.maximumEvents = 1;
  interpret(function, sink, options);
  EXPECT_EQ(sink.events.size(), events);
}

} // namespace
} // namespace cncc::ir
