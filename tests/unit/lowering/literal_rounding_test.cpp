// The controller's rounding of a program's numbers where it reaches a cut
// through sin, cos or tan (cncc/lowering/literal_rounding.h): how the
// controller reads a number, how far a rounded angle moves a bolt circle's
// holes, and the lowering's taking of an angle's constant term modulo a
// turn, which keeps the points where they were and leaves the controller a
// number it reads with all its digits.
#include "cncc/lowering/literal_rounding.h"

#include "lowered_text.h"

#include "cncc/ir/interpreter.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/verifier.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace cncc::ir::lowering {
namespace {

// Four holes on a 38 mm bolt circle, turned by `turn` (a CDL angle).
std::string boltCircle(const std::string& turn) {
  return "import \"std/curves\"\n"
         "part p(holes = 4) {\n"
         "  units mm\n"
         "  tool 4 diameter=3 feed=300\n"
         "  safe z=5\n"
         "  for j in 1 .. holes {\n"
         "    let a = 360deg*j/holes + " +
         turn +
         "\n"
         "    curve circle(38*cos(a), 38*sin(a), 1.75) sweep depth=2 step=2 samples=36\n"
         "  }\n"
         "}\n";
}

LoweringOptions controllerOptions(int digits) {
  LoweringOptions options;
  options.controllerLoops = true;
  options.coordinateIncrement = 0.001;
  options.literalSignificantDigits = digits;
  return options;
}

std::vector<MachineEvent> feedMoves(const Function& function) {
  std::vector<MachineEvent> feeds;
  for (const MachineEvent& event : interpret(function).events) {
    if (event.kind == MachineEvent::Kind::Feed) {
      feeds.push_back(event);
    }
  }
  return feeds;
}

double largestMovement(const Function& function, int digits) {
  double largest = 0;
  for (const LiteralRoundingMove& move : trigonometricRoundingMoves(function, digits)) {
    largest = std::max(largest, move.movement);
  }
  return largest;
}

TEST(ControllerReading, KeepsTheDigitsTheMacroPrintersWrite) {
  EXPECT_EQ(controllerReading(17453292.519943297, 8), 17453293);
  EXPECT_DOUBLE_EQ(controllerReading(57.29577951308232, 8), 57.29578);
  EXPECT_DOUBLE_EQ(controllerReading(0.028571428571428571, 8), 0.02857143);
  EXPECT_DOUBLE_EQ(controllerReading(-6.283185307179586, 8), -6.2831853);
  EXPECT_EQ(controllerReading(38, 8), 38);
  EXPECT_EQ(controllerReading(1e12, 8), 1e12); // whole numbers keep their digits
  EXPECT_DOUBLE_EQ(controllerReading(0.1, 0), 0.1);
}

// 1e9 deg read as 17453293. rad turns the holes by 0.48 rad: some 18 mm on
// the 38 mm circle, which the estimate finds and lays on that number.
TEST(TrigonometricRoundingMoves, FindsALargeAngleConstantOnABoltCircle) {
  auto lowered = test_support::lowerText(boltCircle("1e9deg"), controllerOptions(0));
  ASSERT_TRUE(lowered->part);
  const Function& function = lowered->part->function;
  std::vector<LiteralRoundingMove> moves = trigonometricRoundingMoves(function, 8);
  ASSERT_FALSE(moves.empty());
  const LiteralRoundingMove& move = moves.front();
  double angleError = 17453293 - 1e9 * std::numbers::pi / 180;
  EXPECT_GT(move.movement, 38 * angleError);
  EXPECT_LT(move.movement, 38 * 2 * angleError);
  const Instruction& source = function.instructions[move.source];
  EXPECT_EQ(source.opcode, Opcode::Const);
  EXPECT_DOUBLE_EQ(source.number, 1e9 * std::numbers::pi / 180);
  // With 16 digits the same number is read to within a nanometre's turn.
  EXPECT_LT(largestMovement(function, 16), 1e-6);
}

TEST(TrigonometricRoundingMoves, LeavesASmallAngleWithinMicrometres) {
  auto lowered = test_support::lowerText(boltCircle("45deg"), controllerOptions(0));
  ASSERT_TRUE(lowered->part);
  double movement = largestMovement(lowered->part->function, 8);
  EXPECT_GT(movement, 0); // 2 pi and 45 deg are rounded
  EXPECT_LT(movement, 1e-4);
}

// 9000 turns of a helix: the controller computes each arc's end from the
// angle 2 pi depth/pitch with 2 pi and 180/pi rounded, which moves the ends
// along the circle (every coordinate reads the same angle), not off it.
TEST(TrigonometricRoundingMoves, LeavesACurvesOwnParameterAlone) {
  std::string helix =
      "part p(depth = 9, pitch = 0.001) {\n"
      "  units mm\n"
      "  tool 5 diameter=8 feed=300\n"
      "  safe z=3\n"
      "  curve arc(center = (20, 20), radius = 2, from = 0, to = 2*pi*depth/pitch,\n"
      "            z = 0 .. -depth) tolerance=0.01\n"
      "}\n";
  auto lowered = test_support::lowerText(helix, controllerOptions(0));
  ASSERT_TRUE(lowered->part);
  EXPECT_EQ(largestMovement(lowered->part->function, 8), 0);
}

// On a controller target the constant term 1e9 deg becomes -80 deg: the
// same points to within a nanometre, and nothing the rounding moves far.
TEST(AngleModuloTurns, KeepsThePointsAndTheDigits) {
  auto exact = test_support::lowerText(boltCircle("1e9deg"), controllerOptions(0));
  auto reduced = test_support::lowerText(boltCircle("1e9deg"), controllerOptions(8));
  ASSERT_TRUE(exact->part);
  ASSERT_TRUE(reduced->part);
  EXPECT_FALSE(reduced->diagnostics.hasErrors());
  Function& function = reduced->part->function;
  runDefaultPipeline(function);
  ASSERT_TRUE(verifyFunction(function).empty());
  bool largeConstant = false;
  bool turned = false;
  auto visit = [&](const Region& region, auto& self) -> void {
    for (InstructionId id : region.instructions) {
      const Instruction& instruction = function.instructions[id];
      if (instruction.opcode == Opcode::Const) {
        double number = instruction.number;
        largeConstant = largeConstant || std::abs(number - 1e9 * std::numbers::pi / 180) < 1;
        turned = turned || std::abs(number - (280 - 360) * std::numbers::pi / 180) < 1e-8;
      }
      for (const Region& inner : instruction.regions) {
        self(inner, self);
      }
    }
  };
  visit(function.body, visit);
  EXPECT_FALSE(largeConstant);
  EXPECT_TRUE(turned);
  std::vector<MachineEvent> before = feedMoves(exact->part->function);
  std::vector<MachineEvent> after = feedMoves(function);
  ASSERT_EQ(before.size(), after.size());
  ASSERT_FALSE(after.empty());
  for (std::size_t i = 0; i < after.size(); ++i) {
    EXPECT_NEAR(before[i].x, after[i].x, 1e-6);
    EXPECT_NEAR(before[i].y, after[i].y, 1e-6);
  }
  EXPECT_LT(largestMovement(function, 8), 1e-4);
}

// A constant the angle is multiplied by a fraction of cannot be taken
// modulo a turn: the lowering refuses the program at the statement.
TEST(AngleModuloTurns, LeavesAFractionalMultipleToTheCheck) {
  std::string scaled = "import \"std/curves\"\n"
                       "part p(holes = 4) {\n"
                       "  units mm\n"
                       "  tool 4 diameter=3 feed=300\n"
                       "  safe z=5\n"
                       "  for j in 1 .. holes {\n"
                       "    let a = 1e9deg*j/holes\n"
                       "    curve circle(38*cos(a), 38*sin(a), 1.75) sweep depth=2 step=2\n"
                       "  }\n"
                       "}\n";
  frontend::SourceManager sources;
  frontend::DiagnosticEngine diagnostics;
  frontend::FileId id = sources.addFile("scaled.cdl", scaled);
  frontend::CheckOptions options;
  options.importPaths = {CNCC_STDLIB_DIR};
  options.requirePart = true;
  std::optional<frontend::CheckedProgram> program =
      frontend::checkProgram(sources, id, options, diagnostics);
  ASSERT_TRUE(program && program->selectedPart != nullptr);
  std::optional<LoweredPart> part =
      lowerPartWithCuts(*program, *program->selectedPart, diagnostics, controllerOptions(8));
  EXPECT_FALSE(part);
  ASSERT_FALSE(diagnostics.diagnostics().empty());
  const frontend::Diagnostic& refusal = diagnostics.diagnostics().back();
  EXPECT_EQ(refusal.kind, frontend::DiagnosticKind::LiteralRounding);
  EXPECT_TRUE(sources.text(refusal.span).starts_with("let a = 1e9deg*j/holes"));
}

} // namespace
} // namespace cncc::ir::lowering
