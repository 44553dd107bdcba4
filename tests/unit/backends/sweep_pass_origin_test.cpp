// Where the lowering says an instruction comes from beyond its statement:
// the pass of a cut's sweep (a trip of its pass loop, or a written-out
// pass: Instruction::pass, carried to the machine events and through the
// optimiser), and what made each loop
// (LoopRole), which source maps give for every program line.
#include "../lowering/lowered_text.h"

#include "cncc/lowering/lowering.h"

#include "cncc/backends/line_spans.h"
#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/passes.h"

#include <gtest/gtest.h>

#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace cncc::ir {
namespace {

constexpr const char* sweptSquare = R"(part p(depth = 3) {
  units mm
  tool 1 diameter=4 spindle=1000 feed=100
  safe z=5
  curve polar(r = 10 + cos(3*t), t = 0 .. 2*pi) sweep depth=depth step=1 entry=ramp
})";

using Lowered = test_support::LoweredText;

std::unique_ptr<Lowered> lower(const std::string& text, bool controllerLoops) {
  LoweringOptions lowering;
  lowering.controllerLoops = controllerLoops;
  lowering.coordinateIncrement = 0.001;
  return test_support::lowerText(text, lowering, "pass.cdl");
}

// The (pass, ramp) of each feed move, with repeats dropped.
std::vector<std::pair<std::uint32_t, bool>> feedPasses(const ToolPath& path) {
  std::vector<std::pair<std::uint32_t, bool>> passes;
  for (const MachineEvent& event : path.events) {
    if (event.kind != MachineEvent::Kind::Feed) {
      continue;
    }
    EXPECT_EQ(event.pass.count, 3u);
    std::pair<std::uint32_t, bool> pass{event.pass.number, event.pass.ramp};
    if (passes.empty() || passes.back() != pass) {
      passes.push_back(pass);
    }
  }
  return passes;
}

// The plunge of pass k, its ramp lap, then its lap at depth.
const std::vector<std::pair<std::uint32_t, bool>> threeRampedPasses{
    {1, false}, {1, true},  {1, false}, {2, false}, {2, true},
    {2, false}, {3, false}, {3, true},  {3, false}};

TEST(SweepPassOrigin, HostPassLoopNumbersItsEventsByTripThroughTheOptimiser) {
  auto lowered = lower(sweptSquare, false);
  ASSERT_TRUE(lowered->part);
  int passLoops = 0;
  for (const Instruction& instruction : lowered->part->function.instructions) {
    passLoops += instruction.opcode == Opcode::Loop &&
                 static_cast<LoopRole>(instruction.index) == LoopRole::Passes;
  }
  EXPECT_EQ(passLoops, 1); // the host's passes are a loop too
  EXPECT_EQ(feedPasses(interpret(lowered->part->function)), threeRampedPasses);
  runDefaultPipeline(lowered->part->function);
  EXPECT_EQ(feedPasses(interpret(lowered->part->function)), threeRampedPasses);
}

TEST(SweepPassOrigin, UnrolledPassLoopWritesEachTripsPassOnItsInstructions) {
  // A depth of its own: a count the program computes from a parameter is
  // no loop to unroll.
  std::string ofNumbers = sweptSquare;
  ofNumbers.replace(ofNumbers.find("depth=depth"), 11, "depth=3");
  auto lowered = lower(ofNumbers, false);
  ASSERT_TRUE(lowered->part);
  Function& function = lowered->part->function;
  UnrollOptions everything;
  everything.maximumBodySize = 100'000;
  ASSERT_TRUE(unrollLoops(function, everything));
  std::set<std::uint32_t> numbers;
  for (InstructionId id : function.body.instructions) {
    const Instruction& instruction = function.instructions[id];
    EXPECT_FALSE(instruction.opcode == Opcode::Loop &&
                 static_cast<LoopRole>(instruction.index) == LoopRole::Passes);
    if (instruction.opcode == Opcode::PassBegin || instruction.opcode == Opcode::Feed) {
      EXPECT_EQ(instruction.pass.count, 3u);
      numbers.insert(instruction.pass.number);
    }
  }
  EXPECT_EQ(numbers, (std::set<std::uint32_t>{1, 2, 3}));
  // The events are numbered so by their instructions alone.
  EXPECT_EQ(feedPasses(interpret(function)), threeRampedPasses);
}

TEST(SweepPassOrigin, ControllerPassLoopIsMarkedAndItsLinesHaveNoPassNumber) {
  auto lowered = lower(sweptSquare, true);
  ASSERT_TRUE(lowered->part);
  const Function& function = lowered->part->function;
  int passLoops = 0;
  for (const Instruction& instruction : function.instructions) {
    EXPECT_EQ(instruction.pass.number, 0u);
    if (instruction.opcode == Opcode::Loop &&
        static_cast<LoopRole>(instruction.index) == LoopRole::Passes) {
      ++passLoops;
      std::uint32_t line =
          lowered->sources.file(instruction.span.file).lineColumn(instruction.span.begin).line;
      EXPECT_EQ(line, 5u); // the cut statement
    }
  }
  EXPECT_EQ(passLoops, 1);
}

TEST(SweepPassOrigin, LinesInsideNestedLoopsNameTheLoopsAndLeaveThemAfterTheirEnd) {
  using backends::LineOrigin;
  Instruction outer;
  outer.opcode = Opcode::Loop;
  outer.span = {frontend::FileId{0}, 10, 20};
  Instruction inner = outer;
  inner.span = {frontend::FileId{0}, 12, 18};
  inner.index = static_cast<std::uint32_t>(LoopRole::Passes);
  Instruction move;
  move.opcode = Opcode::Feed;
  move.span = inner.span;
  move.pass = {.number = 0, .count = 0, .ramp = true};

  backends::LineSpans spans;
  std::vector<backends::ControllerLoop> loops;
  std::vector<std::string> lines{"header"};
  LineOrigin current;
  {
    backends::InstructionLines outerLines(spans, lines, outer, current);
    lines.push_back("#1=0");
    backends::enterLoop(spans, loops, lines.size(), outer, current);
    lines.push_back("WHILE DO1");
    {
      backends::InstructionLines innerLines(spans, lines, inner, current);
      backends::enterLoop(spans, loops, lines.size(), inner, current);
      lines.push_back("WHILE DO2");
      {
        backends::InstructionLines moveLines(spans, lines, move, current);
        lines.push_back("G01");
      }
      lines.push_back("END2");
    }
    lines.push_back("END1");
  }
  lines.push_back("M30");
  std::vector<LineOrigin> origins = spans.origins(lines.size());
  ASSERT_EQ(loops.size(), 2u);
  EXPECT_EQ(loops[1].outer, 0u);
  EXPECT_EQ(loops[1].role, LoopRole::Passes);
  std::vector<std::uint32_t> innermost;
  for (const LineOrigin& origin : origins) {
    innermost.push_back(origin.loop);
  }
  constexpr std::uint32_t none = backends::noControllerLoop;
  EXPECT_EQ(innermost, (std::vector<std::uint32_t>{none, none, 0, 1, 1, 1, 0, none}));
  EXPECT_TRUE(origins[4].pass.ramp);
  EXPECT_FALSE(origins[5].pass.ramp);
  EXPECT_EQ(origins[1].span, outer.span);
  EXPECT_FALSE(origins[7].span.valid());
}

} // namespace
} // namespace cncc::ir
