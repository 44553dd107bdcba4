// The modes in force in a `for` or `if` the controller runs: each trip and
// each branch starts with the modes the lowering assumed for it, so every
// cut runs in its own contouring tolerance whichever way the program went;
// the contouring a trip ends in is set once before the loop; a mode no trip
// or branch changes stays known after it (no M9 for a coolant never
// switched on), and a new tool's length offset is activated before the loop
// by a climb along Z alone.
#include "cncc/ir/interpreter.h"
#include "cncc/ir/ir.h"
#include "cncc/ir/printer.h"

#include "lowered_text.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <string>
#include <vector>

namespace cncc::ir {
namespace {

using test_support::lowerText;

LoweringOptions controllerOptions() {
  LoweringOptions options;
  options.controllerLoops = true;
  options.coordinateIncrement = 0.001;
  return options;
}

// The contouring tolerance in force at each cut.begin, in the order run.
std::vector<double> contouringAtEachCut(const Function& function,
                                        const std::map<std::string, double>& parameters) {
  InterpreterOptions options;
  options.parameters = parameters;
  std::vector<double> atCuts;
  double contouring = 0;
  for (const MachineEvent& event : interpret(function, options).events) {
    if (event.kind == MachineEvent::Kind::Contouring) {
      contouring = event.number;
    } else if (event.kind == MachineEvent::Kind::CutBegin) {
      atCuts.push_back(contouring);
    }
  }
  return atCuts;
}

std::size_t countOf(const Function& function, Opcode opcode) {
  std::size_t count = 0;
  for (const Instruction& instruction : function.instructions) {
    count += instruction.opcode == opcode ? 1 : 0;
  }
  return count;
}

bool hasLoop(const Function& function) {
  return countOf(function, Opcode::Loop) > 0;
}

constexpr const char* twoTolerancesInALoop = R"(part slots(n = 3) {
  units mm
  tool 1 diameter=4 spindle=9000 feed=400
  safe z=5
  curve line((0, -20), (0, -10)) sweep depth=1 step=1 tolerance=0.01
  for k in 0 .. n - 1 {
    curve line((k*5, 0), (k*5, 10)) sweep depth=1 step=1 tolerance=0.01
    curve line((k*5, 20), (k*5, 30)) sweep depth=1 step=1 tolerance=0.02
  }
}
)";

TEST(ControllerLoopModes, EveryTripCutsInItsOwnContouringTolerance) {
  auto lowered = lowerText(twoTolerancesInALoop, controllerOptions());
  ASSERT_TRUE(lowered->part);
  const Function& function = lowered->part->function;
  ASSERT_TRUE(hasLoop(function)) << printFunction(function);
  // The second trip starts in the first's 0.02: its first cut sets 0.01.
  EXPECT_EQ(contouringAtEachCut(function, {{"n", 3}}),
            (std::vector<double>{0.01, 0.01, 0.02, 0.01, 0.02, 0.01, 0.02}));
  EXPECT_EQ(contouringAtEachCut(function, {{"n", 1}}), (std::vector<double>{0.01, 0.01, 0.02}));
}

TEST(ControllerLoopModes, TheContouringEveryTripEndsInIsSetOnceBeforeTheLoop) {
  constexpr const char* holes = R"(part holes(n = 4) {
  units mm
  tool 1 diameter=4 spindle=9000 feed=400
  safe z=5
  for k in 0 .. n - 1 {
    curve line((k*5, 0), (k*5, 10)) sweep depth=1 step=1 tolerance=0.01
  }
}
)";
  auto lowered = lowerText(holes, controllerOptions());
  ASSERT_TRUE(lowered->part);
  const Function& function = lowered->part->function;
  ASSERT_TRUE(hasLoop(function));
  std::vector<double> set; // the contouring ops outside the loop, in order
  for (InstructionId id : function.body.instructions) {
    if (function.instructions[id].opcode == Opcode::Contouring) {
      set.push_back(function.instructions[id].number);
    }
  }
  EXPECT_EQ(set, (std::vector<double>{0.01, 0})) << printFunction(function); // on, off at the end
  EXPECT_EQ(countOf(function, Opcode::Contouring), 2u);
  EXPECT_EQ(contouringAtEachCut(function, {{"n", 3}}), (std::vector<double>{0.01, 0.01, 0.01}));
}

TEST(ControllerLoopModes, ACoolantNoTripChangesNeedsNoM9AtTheEnd) {
  auto lowered = lowerText(twoTolerancesInALoop, controllerOptions());
  ASSERT_TRUE(lowered->part);
  EXPECT_EQ(countOf(lowered->part->function, Opcode::Coolant), 0u);

  std::string flooded = twoTolerancesInALoop;
  flooded.replace(flooded.find("  for k"), 0, "  coolant flood\n");
  auto withCoolant = lowerText(flooded, controllerOptions());
  ASSERT_TRUE(withCoolant->part);
  EXPECT_EQ(countOf(withCoolant->part->function, Opcode::Coolant), 2u); // on, and off at the end
}

TEST(ControllerLoopModes, TheLengthOffsetIsActivatedBeforeTheLoopAlongZAlone) {
  std::string firstInTheLoop = twoTolerancesInALoop;
  std::size_t start = firstInTheLoop.find("  curve line((0, -20)");
  firstInTheLoop.erase(start, firstInTheLoop.find('\n', start) + 1 - start);
  auto lowered = lowerText(firstInTheLoop, controllerOptions());
  ASSERT_TRUE(lowered->part);
  const Function& function = lowered->part->function;
  ASSERT_TRUE(hasLoop(function));
  EXPECT_EQ(countOf(function, Opcode::Climb), 1u) << printFunction(function);
  InterpreterOptions options;
  options.parameters = {{"n", 2}};
  std::vector<MachineEvent> events = interpret(function, options).events;
  auto climb = std::find_if(events.begin(), events.end(),
                            [](const MachineEvent& event) { return event.alongZ; });
  ASSERT_NE(climb, events.end());
  EXPECT_EQ(climb->kind, MachineEvent::Kind::Rapid);
  EXPECT_EQ(climb->z, 5);
  auto firstMove = std::find_if(events.begin(), events.end(), isMove);
  EXPECT_EQ(firstMove, climb); // the first move: nothing goes sideways before it
}

TEST(ControllerLoopModes, EachBranchStartsWithTheModesBeforeTheIf) {
  constexpr const char* branches = R"(part choice(deep = 1) {
  units mm
  tool 1 diameter=4 spindle=9000 feed=400
  safe z=5
  curve line((0, -20), (0, -10)) sweep depth=1 step=1 tolerance=0.01
  if deep > 0 {
    curve line((0, 0), (0, 10)) sweep depth=2 step=1 tolerance=0.02
  } else {
    curve line((0, 0), (0, 10)) sweep depth=1 step=1 tolerance=0.02
  }
  curve line((0, 20), (0, 30)) sweep depth=1 step=1 tolerance=0.01
}
)";
  auto lowered = lowerText(branches, controllerOptions());
  ASSERT_TRUE(lowered->part);
  const Function& function = lowered->part->function;
  ASSERT_EQ(countOf(function, Opcode::If), 1u) << printFunction(function);
  EXPECT_EQ(contouringAtEachCut(function, {{"deep", 1}}), (std::vector<double>{0.01, 0.02, 0.01}));
  // The else branch was lowered after the then branch had set 0.02: it sets
  // its own, since the program comes to it in 0.01.
  EXPECT_EQ(contouringAtEachCut(function, {{"deep", 0}}), (std::vector<double>{0.01, 0.02, 0.01}));
}

} // namespace
} // namespace cncc::ir
