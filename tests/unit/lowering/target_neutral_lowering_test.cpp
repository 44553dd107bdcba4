// A part is lowered the same for a target whose controller computes the
// program as for one whose host computes every number: the same function
// (its curve table's points chosen by the legalisations: a curve of
// constants in steps by choose-controller-steps on the first; a curve that
// reads parameters in steps the program computes, whose chords
// bound-controller-steps chooses on the second; its sweeps' passes the
// same loop), but the cut table's line of what the target rounds.
#include "cncc/ir/printer.h"
#include "lowered_text.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

namespace cncc::ir {
namespace {

// The part lowered to its IR before the legalisations: its text without
// the cut table's lines, and how many laps and arcs it moves on.
struct LoweredMotion {
  std::string text;
  int laps = 0;
  int arcs = 0;
};

LoweredMotion loweredMotion(const std::string& source, bool controllerComputes) {
  LoweringOptions lowering;
  lowering.expandCurveLaps = false;
  lowering.coordinateIncrement = 0.001;
  lowering.controllerLoops = controllerComputes;
  lowering.literalSignificantDigits = controllerComputes ? 8 : 0;
  std::unique_ptr<test_support::LoweredText> lowered = test_support::lowerText(source, lowering);
  LoweredMotion motion;
  if (!lowered->part) {
    return motion;
  }
  std::istringstream printed(printFunction(lowered->part->function));
  for (std::string line; std::getline(printed, line);) {
    motion.text += line.starts_with("  cut @") ? "" : line + "\n";
    motion.laps += line.find("= curve.lap @") != std::string::npos ? 1 : 0;
    motion.arcs += line.find("move.arc") != std::string::npos ? 1 : 0;
  }
  return motion;
}

void expectSameOnEveryTarget(const std::string& curve, int arcs,
                             const std::string& parameters = "") {
  std::string source = "part p(" + parameters +
                       ") {\n  tool 1 diameter=6 feed=300\n  safe z=5\n  curve " + curve + "\n}\n";
  LoweredMotion host = loweredMotion(source, false);
  LoweredMotion controller = loweredMotion(source, true);
  EXPECT_NE(host.text.find("curve @0"), std::string::npos) << curve;
  EXPECT_EQ(host.text, controller.text) << curve;
  EXPECT_GT(host.laps, 0) << curve;
  EXPECT_EQ(host.laps, controller.laps) << curve;
  EXPECT_EQ(host.arcs, arcs) << curve;
  EXPECT_EQ(controller.arcs, arcs) << curve;
}

TEST(TargetNeutralLowering, APathOfConstantsWithArcsOnARamp) {
  expectSameOnEveryTarget("path(line((0, 0), (20, 0)), arc(center=(20, 5), radius=5, "
                          "from=-pi/2, to=pi/2), line((20, 10), (0, 10)), arc(center=(0, 5), "
                          "radius=5, from=pi/2, to=3*pi/2)) entry=ramp sweep depth=2 step=1",
                          4); // two on the ramp, two on the level lap
}

TEST(TargetNeutralLowering, AHelixOfConstantsBetweenLines) {
  expectSameOnEveryTarget("path(line((0, 0), (20, 0)), arc(center=(20, 5), radius=5, "
                          "from=-pi/2, to=3*pi/2 + 12*pi, z = 0 .. -3))",
                          1); // seven turns, a loop of one block
}

TEST(TargetNeutralLowering, SamplesOfOnePiece) {
  expectSameOnEveryTarget("polar(r = 10 + cos(3*t), t = 0 .. 2*pi) samples=37", 0);
}

TEST(TargetNeutralLowering, ChordsOfAParamCurve) {
  expectSameOnEveryTarget("param(x = t, y = t*t/10, t = 0 .. 10) tolerance=0.005 sweep "
                          "depth=1 step=0.5",
                          0);
}

TEST(TargetNeutralLowering, ACurveThatReadsParameters) {
  std::string polar = "polar(r = a + cos(3*t), t = 0 .. 2*pi) tolerance=0.01 sweep depth=d step=1";
  expectSameOnEveryTarget(polar, 0, "a = 10, d = 2");
  std::string bezier = "bezier(points=[(0, 0), (10, h), (20, 0)]) sweep depth=2 step=1";
  expectSameOnEveryTarget(bezier, 0, "h = 5");
  std::string ring = "polar(r = a, t = 0 .. 2*pi) entry=ramp";
  expectSameOnEveryTarget(ring, 0, "a = 12");
}

TEST(TargetNeutralLowering, ASweepOfOnePass) {
  expectSameOnEveryTarget("line((0, 0), (5, 0)) sweep depth=1 step=1", 0);
}

// The length offset is activated before the pass loop on every target,
// and the passes are the same loop whether or not the controller could
// compute them: its count a number, not round(depth / step + ...).
TEST(TargetNeutralLowering, APassLoopAfterAToolChange) {
  std::string source = "part p() {\n  tool 1 diameter=6 feed=300\n  safe z=5\n  curve "
                       "line((0, 0), (5, 0)) sweep depth=2 step=0.5\n}\n";
  for (bool controllerComputes : {false, true}) {
    std::string text = loweredMotion(source, controllerComputes).text;
    std::size_t loop = text.find("= loop");
    ASSERT_NE(loop, std::string::npos) << text;
    EXPECT_NE(text.rfind("move.rapid", loop), std::string::npos) << text;
    EXPECT_EQ(text.find("round"), std::string::npos) << text;
  }
}

} // namespace
} // namespace cncc::ir
