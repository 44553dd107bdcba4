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

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace cncc::ir {
namespace {

// The part lowered to its IR before the legalisations: its text without
// the cut table's lines, and how many laps and arcs it moves on.
struct LoweredMotion {
  std::string text;
  int laps = 0;
  int arcs = 0;
};

// The curve blocks a target prints (none: gcode, linuxcnc).
enum class Blocks { None, Nurbs, Polynomial, Spline };

LoweredMotion loweredMotion(const std::string& source, bool controllerComputes,
                            const std::string& file = "test.cdl", const std::string& part = "",
                            Blocks blocks = Blocks::None) {
  LoweringOptions lowering;
  lowering.nurbsBlocks = blocks == Blocks::Nurbs;
  lowering.polynomialBlocks = blocks == Blocks::Polynomial;
  lowering.splineBlocks = blocks == Blocks::Spline;
  lowering.splineInterpolation = blocks == Blocks::Spline;
  lowering.expandCurveLaps = false;
  lowering.coordinateIncrement = 0.0001; // an inch part's tolerances too
  lowering.controllerLoops = controllerComputes;
  lowering.keepLoops = true; // as every target lowers a `for`
  lowering.literalSignificantDigits = controllerComputes ? 8 : 0;
  lowering.cutterCompensation = true; // for comp=controller: both print it
  std::unique_ptr<test_support::LoweredText> lowered =
      test_support::lowerText(source, lowering, file, part);
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

// A method= that asks for curve blocks gives the same chords or steps on
// every target, the blocks a legalisation's (choose-curve-blocks): on a
// host, a controller and each target that prints blocks (Fanuc's G06.2
// computed by a controller, Heidenhain's SPL too, Sinumerik's splines by
// the host); a curve of constants, one that reads a parameter, an offset.
TEST(TargetNeutralLowering, ACurveAskingForBlocks) {
  for (std::string curve :
       {"bezier(points=[(0, 0), (10, 8), (20, 0)]) method=nurbs sweep depth=2 step=1",
        "polar(r = 10 + cos(3*t), t = 0 .. 2*pi) method=cspline entry=ramp",
        "param(x = 10*cos(t), y = 5*sin(t), z = t, t = 0 .. pi) method=bspline",
        "polar(r = a + 2*cos(3*t), t = 0 .. 2*pi) method=nurbs sweep depth=2 step=1",
        "polar(r = 18 + 2*cos(3*t), t = 0 .. 2*pi) side=right method=bspline entry=ramp"}) {
    std::string source =
        "part p(a = 18) {\n  tool 1 diameter=6 feed=300\n  safe z=5\n  curve " + curve + "\n}\n";
    LoweredMotion host = loweredMotion(source, false);
    EXPECT_NE(host.text.find("blocks asked"), std::string::npos) << curve;
    for (auto [controllerComputes, blocks] :
         {std::pair{true, Blocks::None}, std::pair{true, Blocks::Nurbs},
          std::pair{true, Blocks::Polynomial}, std::pair{false, Blocks::Spline}}) {
      LoweredMotion target = loweredMotion(source, controllerComputes, "test.cdl", "", blocks);
      EXPECT_EQ(host.text, target.text) << curve << " " << static_cast<int>(blocks);
    }
  }
}

// The names of the parts of a CDL source (`part NAME(` at a line's start).
std::vector<std::string> partNames(const std::string& source) {
  std::vector<std::string> names;
  std::istringstream lines(source);
  for (std::string line; std::getline(lines, line);) {
    if (line.starts_with("part ")) {
      names.push_back(line.substr(5, line.find_first_of("( {", 5) - 5));
    }
  }
  return names;
}

// Every example's parts are lowered the same for both. (A curve with arcs
// that reads parameters since split-arc-laps: cam_profile, bore_plate_mm
// and _inch; a `for` or `if` on parameters since unroll-host-control:
// bolt_circle, rosette_plate and flange; an offset since the host chooses
// the chords of the controller's laps, at the compiled radius where it is a
// parameter: offset_contours and worn_cutter; comp=controller's chords and
// a host's offset, numbers where a controller computes the program:
// compensated_contours.) A change that makes one differ shows here
// (CNCC_SHOW_DIFF=1 writes both to /tmp/PART.host and .controller).
std::set<std::string> examplePartsThatDiffer(Blocks blocks, std::size_t& same);

TEST(TargetNeutralLowering, EveryExamplesParts) {
  std::size_t same = 0;
  EXPECT_EQ(examplePartsThatDiffer(Blocks::None, same), std::set<std::string>{});
  EXPECT_GE(same, 13u);
}

// And with the blocks each target prints (cam_profile's mark, rosette_plate's
// petals, which read the loop's variable and its bound's parameter).
TEST(TargetNeutralLowering, EveryExamplesPartsWithTheTargetsBlocks) {
  for (Blocks blocks : {Blocks::Nurbs, Blocks::Polynomial, Blocks::Spline}) {
    std::size_t same = 0;
    EXPECT_EQ(examplePartsThatDiffer(blocks, same), std::set<std::string>{})
        << static_cast<int>(blocks);
    EXPECT_GE(same, 13u);
  }
}

// The example parts whose IR differs between a host and a controller that
// prints `blocks` (Sinumerik's: a host that prints them); `same` counts the others.
std::set<std::string> examplePartsThatDiffer(Blocks blocks, std::size_t& same) {
  std::set<std::string> differ;
  bool hostPrints = blocks == Blocks::Spline;
  for (const auto& entry :
       std::filesystem::recursive_directory_iterator(CNCC_SOURCE_DIR "/examples")) {
    if (entry.path().extension() != ".cdl") {
      continue;
    }
    std::ifstream file(entry.path());
    std::stringstream buffer;
    buffer << file.rdbuf();
    std::string source = buffer.str();
    for (const std::string& part : partNames(source)) {
      std::string path = entry.path().string();
      std::string host = loweredMotion(source, false, path, part).text;
      std::string controller = loweredMotion(source, !hostPrints, path, part, blocks).text;
      EXPECT_FALSE(host.empty()) << path << " " << part;
      if (host == controller) {
        ++same;
      } else {
        differ.insert(part);
        if (std::getenv("CNCC_SHOW_DIFF") != nullptr) {
          std::ofstream("/tmp/" + part + ".host") << host;
          std::ofstream("/tmp/" + part + ".controller") << controller;
        }
      }
    }
  }
  return differ;
}

} // namespace
} // namespace cncc::ir
