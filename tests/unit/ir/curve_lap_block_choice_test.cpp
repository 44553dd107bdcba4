// choose-curve-blocks: the chords a cut's method= asks to be curve blocks
// (blocksAsked) become the blocks its target prints (the cut table's
// `prints`) where they can follow the lap, and stay chords with a
// spline-as-chords warning where they cannot; the answer is given once.
#include "cncc/geom/nurbs_curve.h"
#include "cncc/ir/curve_lap.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/printer.h"
#include "cncc/ir/verifier.h"
#include "curve_lap_fixtures.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace cncc::ir {
namespace {

using curve_lap_test::countOf;
using curve_lap_test::parsed;
using curve_lap_test::replaced;

// A parabola from (0, 0) to (20, 5), x = 20 t, y = 5 t^2, in one pass at
// z = -1, cut as chords its method= asks to be SPL spans.
constexpr std::string_view parabolaText = R"(func @parabola() {
  curve @0 chords 0.009 over 0 .. 1 {
    piece at 0 over 0 .. 1
    blocks asked
  }
  cut @0 tolerance 0.01 increment 0.001 method bspline prints polynomial
  %0 = const 0
  %1 = const -1
  %2 = const 300
  %3 = const 20
  %4 = const 5
  cut.begin 0
  move.rapid %0, %0, %1
  %5 = curve.lap @0, %1, %1, %2 {
    %6 = mul %3, %5
    %7 = mul %5, %5
    %8 = mul %4, %7
    curve.point %6, %8, %0
  }
}
)";

// The same parabola with a lap ramping from z = 0 down to -1 too.
std::string rampedParabola(std::string_view prints) {
  std::string text = replaced(parabolaText, "prints polynomial", prints);
  return replaced(text, "    curve.point %6, %8, %0\n  }\n", R"(    curve.point %6, %8, %0
  }
  %9 = curve.lap @0, %0, %1, %2 {
    %10 = mul %3, %9
    %11 = mul %9, %9
    %12 = mul %4, %11
    curve.point %10, %12, %0
  }
)");
}

std::vector<std::string> warningsOf(const Function& function) {
  std::vector<std::string> messages;
  for (const LegalisationWarning& warning : function.warnings) {
    EXPECT_EQ(warning.kind, LegalisationWarning::Kind::SplineAsChords);
    messages.push_back(warning.message);
  }
  return messages;
}

TEST(CurveBlockChoice, AskedChordsPrintAndParseBack) {
  Function function = parsed(parabolaText);
  EXPECT_TRUE(function.curves[0].blocksAsked);
  EXPECT_EQ(function.cuts[0].printedBlocks, PrintedBlocks::Polynomial);
  EXPECT_EQ(printFunction(function), parabolaText);
}

TEST(CurveBlockChoice, SplSpansKeepTheToleranceLessTheRoundingOfTheirEnds) {
  Function function = parsed(parabolaText);
  EXPECT_TRUE(chooseCurveBlocks(function));
  ASSERT_EQ(function.curves.size(), 1u); // the entry itself becomes the blocks
  const CurveTableEntry& entry = function.curves[0];
  EXPECT_EQ(entry.sampling, CurveSampling::PolynomialBlocks);
  EXPECT_NEAR(entry.amount, 0.01 - 0.0005 * std::sqrt(3.0), 1e-12);
  EXPECT_EQ(entry.grid, 0.001);
  EXPECT_FALSE(entry.blocksAsked);
  EXPECT_TRUE(function.warnings.empty());
  EXPECT_TRUE(verifyFunction(function).empty());
  runCurveLegalisation(function);
  EXPECT_EQ(countOf(function, Opcode::Polynomial), 1u); // a parabola is one cubic span
  EXPECT_EQ(countOf(function, Opcode::Feed), 0u);
}

TEST(CurveBlockChoice, ANurbsBlockOnlyForMethodNurbs) {
  Function nurbs = parsed(replaced(replaced(parabolaText, "prints polynomial", "prints nurbs"),
                                   "method bspline", "method nurbs"));
  EXPECT_TRUE(chooseCurveBlocks(nurbs));
  EXPECT_EQ(nurbs.curves[0].sampling, CurveSampling::NurbsBlocks);
  runCurveLegalisation(nurbs);
  EXPECT_EQ(countOf(nurbs, Opcode::Nurbs), 1u);

  Function cspline = parsed(replaced(replaced(parabolaText, "prints polynomial", "prints nurbs"),
                                     "method bspline", "method cspline"));
  EXPECT_TRUE(chooseCurveBlocks(cspline));
  EXPECT_EQ(cspline.curves[0].sampling, CurveSampling::ChordTolerance);
  EXPECT_FALSE(cspline.curves[0].blocksAsked); // answered once
  EXPECT_EQ(warningsOf(cspline),
            std::vector<std::string>{"this target has no spline interpolation: method=cspline is "
                                     "cut as straight feed moves within the cut's tolerance"});
  EXPECT_FALSE(chooseCurveBlocks(cspline));
  EXPECT_EQ(cspline.warnings.size(), 1u);
}

TEST(CurveBlockChoice, ATargetWithoutBlocksKeepsTheChordsAndSaysSo) {
  Function function = parsed(replaced(parabolaText, " prints polynomial", ""));
  EXPECT_TRUE(chooseCurveBlocks(function));
  EXPECT_EQ(function.curves[0].sampling, CurveSampling::ChordTolerance);
  EXPECT_EQ(warningsOf(function).size(), 1u);
}

TEST(CurveBlockChoice, AnEntryThatAsksNothingIsLeft) {
  Function function = parsed(replaced(parabolaText, "    blocks asked\n", ""));
  EXPECT_FALSE(chooseCurveBlocks(function));
  EXPECT_EQ(printFunction(function), replaced(parabolaText, "    blocks asked\n", ""));
}

TEST(CurveBlockChoice, SplineBlocksAfterARampThroughTheRampsPoints) {
  Function function = parsed(rampedParabola("prints spline-automatic"));
  EXPECT_TRUE(chooseCurveBlocks(function));
  ASSERT_EQ(function.curves.size(), 2u);
  const CurveTableEntry& level = function.curves[0];
  const CurveTableEntry& ramp = function.curves[1];
  EXPECT_EQ(level.sampling, CurveSampling::SplineBlocks);
  EXPECT_EQ(level.amount, 0.01); // the whole tolerance: the fit shares it with the rounding
  ASSERT_TRUE(level.splineFit);
  EXPECT_EQ(level.splineFit->kind, SplineKind::BSpline);
  EXPECT_TRUE(level.splineFit->afterRamp);
  EXPECT_EQ(ramp.sampling, CurveSampling::ChordTolerance);
  ASSERT_NE(ramp.chosenParameters, nullptr);
  EXPECT_EQ(ramp.chosenParameters, level.chosenParameters); // the same points
  EXPECT_TRUE(verifyFunction(function).empty());
  runCurveLegalisation(function);
  EXPECT_EQ(countOf(function, Opcode::Spline), 1u);
  EXPECT_GT(countOf(function, Opcode::Feed), 0u); // the ramp's chords
}

TEST(CurveBlockChoice, SplAndNurbsBlocksCannotDescendARamp) {
  Function function = parsed(rampedParabola("prints polynomial"));
  EXPECT_TRUE(chooseCurveBlocks(function));
  EXPECT_EQ(function.curves.size(), 1u);
  EXPECT_EQ(function.curves[0].sampling, CurveSampling::ChordTolerance);
  EXPECT_EQ(warningsOf(function),
            std::vector<std::string>{"SPL blocks cannot descend an entry=ramp: method=bspline is "
                                     "cut as straight feed moves within the cut's tolerance"});
}

TEST(CurveBlockChoice, SplineBlocksOnlyInAPlane) {
  std::string text = replaced(parabolaText, "prints polynomial", "prints spline-automatic");
  Function function = parsed(replaced(text, "curve.point %6, %8, %0", "curve.point %6, %8, %8"));
  EXPECT_TRUE(chooseCurveBlocks(function));
  EXPECT_EQ(function.curves[0].sampling, CurveSampling::ChordTolerance);
  ASSERT_EQ(function.warnings.size(), 1u);
  EXPECT_NE(function.warnings[0].message.find("leaves its plane"), std::string::npos);
}

// Blocks are numbers the host computes: a lap whose points read a part
// parameter is cut as blocks at its value, which is fixed (on a controller
// with a warning: its program checks it); one that reads the variable of a
// loop the program runs stays chords.
TEST(CurveBlockChoice, ALapThatReadsAParameterFixesIt) {
  std::string text = replaced(parabolaText, "func @parabola() {", "func @parabola(h = 5) {");
  text = replaced(text, "  %4 = const 5\n", "  %4 = param h\n");
  Function host = parsed(text);
  EXPECT_TRUE(chooseCurveBlocks(host));
  EXPECT_EQ(host.curves[0].sampling, CurveSampling::PolynomialBlocks);
  EXPECT_TRUE(host.parameters[0].fixed);
  EXPECT_TRUE(host.warnings.empty()); // a host's program has no parameters to edit

  Function controller = parsed(replaced(text, "increment 0.001", "increment 0.001 controller 12"));
  EXPECT_TRUE(chooseCurveBlocks(controller));
  EXPECT_TRUE(controller.parameters[0].fixed);
  ASSERT_EQ(controller.warnings.size(), 1u);
  EXPECT_EQ(controller.warnings[0].kind, LegalisationWarning::Kind::ParameterFixed);
  EXPECT_EQ(controller.warnings[0].message,
            "'h' is fixed at its value 5 in this program: this curve's SPL blocks are computed "
            "when compiling; the program raises an alarm if it is changed");
}

TEST(CurveBlockChoice, ALapThatReadsALoopsVariableStaysChords) {
  std::string text = replaced(parabolaText, "  cut.begin 0\n", R"(  %9 = const 1
  %10 = const 3
  %11 = loop %9, %10 {
    cut.begin 0
)");
  text = replaced(text, "    %8 = mul %4, %7\n", "    %8 = mul %11, %7\n");
  text = replaced(text, "    curve.point %6, %8, %0\n  }\n}",
                  "    curve.point %6, %8, %0\n  }\n  }\n}");
  Function function = parsed(replaced(text, "increment 0.001", "increment 0.001 controller 12"));
  EXPECT_TRUE(chooseCurveBlocks(function));
  EXPECT_EQ(function.curves[0].sampling, CurveSampling::ChordTolerance);
  EXPECT_EQ(warningsOf(function),
            std::vector<std::string>{"this curve changes with a loop the program runs: "
                                     "method=bspline is cut as straight feed moves within the "
                                     "cut's tolerance"});
}

// An arch from (0, 0) to (20, 0) through the control point (10, 10) of
// weight w asking for a G06.2 block, its middle weight the parameter w
// (`weights 1 param 0`); its region here only the chord.
constexpr std::string_view archText = R"(func @arch(w = 2) {
  curve @0 chords 0.009 over 0 .. 1 {
    piece at 0 over 0 .. 1
    blocks asked
    weights 1 param 0
  }
  cut @0 tolerance 0.01 increment 0.001 controller 8 method nurbs prints nurbs
  %0 = param w
  %1 = const 0
  %2 = const -1
  %3 = const 300
  %4 = const 20
  cut.begin 0
  move.rapid %1, %1, %2
  %5 = curve.lap @0, %2, %2, %3 {
    %6 = mul %4, %5
    %7 = mul %0, %1
    curve.point %6, %7, %1
  }
}
)";

TEST(CurveBlockChoice, AWeightsParameterMustBeThePartsParameter) {
  Function function = parsed(archText);
  function.curves[0].parameterWeights[0].parameter = 1;
  std::vector<std::string> problems = verifyFunction(function);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("the weight of point 1 the parameter 1, but 1 parameters"),
            std::string::npos);
}

// The move.nurbs's weight operands: a parameter's index, or -1 for a number.
std::vector<int> nurbsWeights(const Function& function) {
  std::vector<int> weights;
  for (const Instruction& instruction : function.instructions) {
    if (instruction.opcode != Opcode::Nurbs) {
      continue;
    }
    for (std::size_t k = 2; k < instruction.operands.size(); ++k) {
      const Instruction& weight = function.definition(instruction.operands[k]);
      weights.push_back(weight.opcode == Opcode::Param ? static_cast<int>(weight.index) : -1);
    }
  }
  return weights;
}

TEST(CurveBlockChoice, AWeightThatIsAParameterStaysOneInItsNurbsBlock) {
  Function function = parsed(archText);
  EXPECT_EQ(printFunction(function), archText);
  std::vector<Eigen::Vector3d> points = {{0, 0, 0}, {10, 10, 0}, {20, 0, 0}};
  function.curves[0].geometry = std::make_shared<geom::NurbsCurve>(
      geom::KnotVector({0, 0, 0, 1, 1, 1}, 2), points, std::vector<double>{1, 2, 1});
  EXPECT_TRUE(chooseCurveBlocks(function));
  EXPECT_FALSE(function.parameters[0].fixed); // the block's own weight
  EXPECT_TRUE(function.warnings.empty());
  EXPECT_TRUE(writeCurveBlocks(function));
  EXPECT_EQ(nurbsWeights(function), (std::vector<int>{-1, 0, -1}));
}

// Read from text, the lap's curve is its region interpreted, not a NURBS of
// its own: its block is a fitted B-spline, and what it reads is fixed.
TEST(CurveBlockChoice, AFittedBlockFixesTheWeightsParameter) {
  Function function = parsed(archText);
  EXPECT_TRUE(chooseCurveBlocks(function));
  EXPECT_TRUE(function.parameters[0].fixed);
  ASSERT_EQ(function.warnings.size(), 1u);
  EXPECT_EQ(function.warnings[0].kind, LegalisationWarning::Kind::ParameterFixed);
  EXPECT_TRUE(writeCurveBlocks(function));
  std::vector<int> weights = nurbsWeights(function);
  EXPECT_FALSE(weights.empty());
  EXPECT_EQ(std::count(weights.begin(), weights.end(), 0), 0);
}

TEST(CurveBlockChoice, AToleranceTheRoundingTakesIsAnError) {
  std::string text = replaced(parabolaText, "tolerance 0.01", "tolerance 0.0015");
  CurveLapError error = curve_lap_test::passError(text, chooseCurveBlocks);
  EXPECT_EQ(error.kind, CurveLapError::Kind::InvalidTolerance);
  EXPECT_NE(std::string(error.what()).find("rounding of the spline end points"), std::string::npos);
}

} // namespace
} // namespace cncc::ir
