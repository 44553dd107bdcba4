// The JIT's streaming run hands a sink exactly the events its stored run
// records, in the same order, on every example and every move that makes
// several events; an error stops it where the stored run stops, after the
// same events, with the same message; an exception of the sink stops the run.
#include "jit_test_support.h"

#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/geom/nurbs_curve.h"
#include "cncc/ir/builder.h"
#include "cncc/ir/nurbs_move.h"
#include "cncc/lowering/lowering.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace cncc {
namespace {

using ir::FunctionBuilder;
using ir::Opcode;
using ir::ValueId;

ir::InterpreterOptions withParameter(const std::string& name, double value) {
  ir::InterpreterOptions options;
  options.parameters[name] = value;
  return options;
}

// Every part of the example that lowers, stored and streamed; the names of
// those compared are added to `compared`.
void compareExample(const std::filesystem::path& path, std::vector<std::string>& compared) {
  frontend::SourceManager sources;
  frontend::DiagnosticEngine diagnostics;
  std::optional<frontend::FileId> file = sources.loadFile(path.string());
  ASSERT_TRUE(file) << "cannot read " << path;
  frontend::CheckOptions options;
  options.importPaths = {CNCC_STDLIB_DIR};
  frontend::CheckedProgram program = frontend::checkProgram(sources, *file, options, diagnostics);
  ASSERT_FALSE(diagnostics.hasErrors()) << path << " does not check";
  for (const frontend::PartItem* part : program.parts) {
    std::string name = path.filename().string() + ":" + std::string(part->name);
    frontend::DiagnosticEngine partDiagnostics;
    std::optional<ir::Function> function = ir::lowerPart(program, *part, partDiagnostics);
    if (!function) {
      continue;
    }
    backends::CompiledFunction compiled(*function);
    jit_test::RunOutcome stored = jit_test::storedOutcome(compiled);
    EXPECT_FALSE(stored.path.events.empty()) << name;
    EXPECT_TRUE(jit_test::identicalOutcomes(stored, jit_test::streamedOutcome(compiled))) << name;
    compared.push_back(name);
  }
}

TEST(JitStream, EveryLoweredExampleStreamsItsStoredEvents) {
  std::vector<std::filesystem::path> examples = jit_test::exampleFiles();
  std::vector<std::string> compared;
  for (const std::filesystem::path& example : examples) {
    SCOPED_TRACE(example.string());
    compareExample(example, compared);
  }
  for (const char* expected : {"archimedean_spiral.cdl:archimedean_spiral",
                               "polar_contour.cdl:polar_contour", "s_profile.cdl:s_profile"}) {
    EXPECT_NE(std::find(compared.begin(), compared.end(), expected), compared.end())
        << expected << " was not compared";
  }
}

// A rapid, a plunge, a NURBS move whose middle weight is a parameter, then
// an arc that starts where the NURBS move ended: the streaming run follows
// the position through the move's many events itself.
ir::Function nurbsThenArc() {
  FunctionBuilder builder("nurbs_then_arc");
  ValueId weight = builder.parameter(builder.addParameter("w", 3));
  geom::NurbsCurve curve(geom::KnotVector({0, 0, 0, 1, 1, 1}, 2),
                         {{0, 0, 0}, {5, 8, 0}, {10, 0, 0}}, {1, 1, 1});
  std::uint32_t table = builder.addTable(ir::nurbsMoveTable(curve));
  ValueId zero = builder.constant(0);
  ValueId one = builder.constant(1);
  ValueId feed = builder.constant(200);
  ValueId depth = builder.constant(-0.5);
  builder.rapid(zero, zero, zero);
  builder.feed(zero, zero, depth, feed);
  builder.nurbs(table, depth, feed, {one, weight, one});
  // A half turn about (15, 0) from the curve's end (10, 0) to (20, 0).
  builder.arc(ir::ArcTurn::Clockwise, builder.constant(20), zero, depth, builder.constant(5), zero,
              feed);
  return builder.finish();
}

TEST(JitStream, MovesOfManyEventsAndTheArcAfterThem) {
  ir::Function function = nurbsThenArc();
  backends::CompiledFunction compiled(function);
  jit_test::RunOutcome streamed = jit_test::streamedOutcome(compiled);
  ASSERT_FALSE(streamed.failed) << streamed.error;
  ASSERT_GT(streamed.path.events.size(), 4u);
  EXPECT_EQ(streamed.path.events.back().kind, ir::MachineEvent::Kind::Arc);
  EXPECT_EQ(streamed.path.events.back().centreX, 15);
  EXPECT_TRUE(jit_test::identicalOutcomes(jit_test::storedOutcome(compiled), streamed));
  EXPECT_TRUE(jit_test::jitMatchesInterpreter(function));
  // A weight no NURBS has: the move fails after the rapid and the plunge.
  for (double weight : {0.0, -1.0}) {
    jit_test::RunOutcome failed = jit_test::streamedOutcome(compiled, withParameter("w", weight));
    EXPECT_TRUE(failed.failed) << "w = " << weight;
    EXPECT_EQ(failed.path.events.size(), 2u) << "w = " << weight;
    EXPECT_TRUE(jit_test::streamedMatchesStored(compiled, withParameter("w", weight)));
  }
}

// Two moves, then table {10, 20, 30} read at the parameter `index`.
ir::Function movesThenTableRead() {
  FunctionBuilder builder("table");
  std::uint32_t table = builder.addTable({10, 20, 30});
  std::uint32_t index = builder.addParameter("index", 0);
  ValueId zero = builder.constant(0);
  builder.rapid(zero, zero, zero);
  builder.comment("read");
  ValueId element = builder.tableLoad(table, builder.parameter(index));
  builder.feed(element, zero, zero, builder.constant(100));
  return builder.finish();
}

TEST(JitStream, AnErrorMidRunStopsAfterTheSameEvents) {
  backends::CompiledFunction compiled(movesThenTableRead());
  jit_test::RunOutcome streamed = jit_test::streamedOutcome(compiled, withParameter("index", 3));
  EXPECT_TRUE(streamed.failed);
  EXPECT_EQ(streamed.error, "index 3 is outside table @0 of 3 entries");
  ASSERT_EQ(streamed.path.events.size(), 2u);
  EXPECT_EQ(streamed.path.events[1].text, "read");
  EXPECT_TRUE(jit_test::identicalOutcomes(
      jit_test::storedOutcome(compiled, withParameter("index", 3)), streamed));
  EXPECT_TRUE(jit_test::streamedMatchesStored(compiled, withParameter("index", 2)));
}

// Nested loops with a comment, table loads and an if: for every step limit
// around the program's length, the streamed run ends as the stored one.
TEST(JitStream, StepLimitStopsAfterTheSameEvents) {
  FunctionBuilder builder("steps");
  std::uint32_t table = builder.addTable({1, 2, 3, 4, 5, 6});
  ValueId zero = builder.constant(0);
  ValueId pass = builder.beginLoop(builder.constant(1), builder.constant(3));
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
  backends::CompiledFunction compiled(builder.finish());
  int stoppedByLimit = 0;
  for (std::size_t limit = 0; limit <= 120; ++limit) {
    ir::InterpreterOptions options;
    options.maximumSteps = limit;
    jit_test::RunOutcome streamed = jit_test::streamedOutcome(compiled, options);
    EXPECT_TRUE(jit_test::identicalOutcomes(jit_test::storedOutcome(compiled, options), streamed))
        << "limit " << limit;
    stoppedByLimit += streamed.error.find("steps") != std::string::npos ? 1 : 0;
  }
  EXPECT_GT(stoppedByLimit, 10);
}

TEST(JitStream, AnAlarmStopsAfterTheSameEvents) {
  FunctionBuilder builder("alarm");
  ValueId zero = builder.constant(0);
  builder.rapid(zero, zero, builder.constant(5));
  builder.alarm("stop here");
  builder.rapid(zero, zero, zero);
  backends::CompiledFunction compiled(builder.finish());
  jit_test::RunOutcome streamed = jit_test::streamedOutcome(compiled);
  EXPECT_EQ(streamed.error, "alarm: stop here");
  EXPECT_EQ(streamed.path.events.size(), 1u);
  EXPECT_TRUE(jit_test::identicalOutcomes(jit_test::storedOutcome(compiled), streamed));
}

// Takes `capacity` events and throws at the next.
class FullSink : public ir::MachineEventSink {
public:
  explicit FullSink(std::size_t capacity) : capacity_(capacity) {}
  void event(const ir::MachineEvent&) override {
    if (received == capacity_) {
      throw std::length_error("the sink is full");
    }
    ++received;
  }
  std::size_t received = 0;

private:
  std::size_t capacity_;
};

TEST(JitStream, TheSinksExceptionStopsTheRunAndReachesTheCaller) {
  ir::Function function = nurbsThenArc();
  backends::CompiledFunction compiled(function);
  std::size_t total = jit_test::storedOutcome(compiled).path.events.size();
  // Full at a single event, inside the NURBS move's events, before the arc.
  for (std::size_t capacity : {std::size_t{1}, std::size_t{3}, total - 1}) {
    FullSink sink(capacity);
    EXPECT_THROW(compiled.run({}, sink), std::length_error) << "capacity " << capacity;
    EXPECT_EQ(sink.received, capacity);
  }
  // The compiled function runs again after it.
  FullSink roomy(total);
  compiled.run({}, roomy);
  EXPECT_EQ(roomy.received, total);
}

} // namespace
} // namespace cncc
