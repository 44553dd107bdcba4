// The cut table as IR text: each cut's tolerance, the target's increment
// and controller digits, method, arcs, tool radius beside the curve and
// spline blocks' summary print and parse back; its
// curves and spans are not text. A cut.begin names a cut of the table.
#include "cncc/ir/printer.h"
#include "cncc/ir/verifier.h"
#include "curve_lap_fixtures.h"

#include <gtest/gtest.h>

#include <cmath>

namespace cncc::ir {
namespace {

using curve_lap_test::parseComplaint;
using curve_lap_test::parsed;
using curve_lap_test::replaced;

constexpr std::string_view twoCutsText = R"(func @two() {
  cut @0 tolerance 0.01 increment 0.001 controller 8 method bspline prints spline-natural blocks "6 BSPLINE control points, \"the NURBS\""
  cut @1 tolerance nan arcs fitted beside 2.5
  %0 = const 0
  %1 = const 100
  cut.begin 0
  move.feed %0, %0, %0, %1
  cut.begin 1
  move.feed %1, %0, %0, %1
}
)";

TEST(CutTableText, EveryFieldPrintsAndParsesBack) {
  Function function = parsed(twoCutsText);
  EXPECT_EQ(printFunction(function), twoCutsText);
  EXPECT_TRUE(verifyFunction(function).empty());
  ASSERT_EQ(function.cuts.size(), 2u);
  const CutGeometry& first = function.cuts[0];
  EXPECT_EQ(first.tolerance, 0.01);
  EXPECT_EQ(first.increment, 0.001);
  EXPECT_EQ(first.controllerDigits, 8);
  EXPECT_EQ(first.method, "bspline");
  EXPECT_EQ(first.printedBlocks, PrintedBlocks::Spline);
  EXPECT_EQ(first.splineEnds, SplineEnds::Natural);
  EXPECT_EQ(first.arcMoves, CutArcs::None);
  EXPECT_EQ(first.splineBlocks, "6 BSPLINE control points, \"the NURBS\"");
  EXPECT_EQ(first.curve, nullptr); // not text
  const CutGeometry& second = function.cuts[1];
  EXPECT_TRUE(std::isnan(second.tolerance)); // samples= chose the points
  EXPECT_EQ(second.increment, 0);
  EXPECT_FALSE(second.controllerDigits); // the host computes its numbers
  EXPECT_EQ(second.method, "");
  EXPECT_EQ(second.printedBlocks, PrintedBlocks::None);
  EXPECT_EQ(second.arcMoves, CutArcs::Fitted);
  EXPECT_EQ(second.toolRadius, 2.5);
}

TEST(CutTableText, EveryPrintedBlocksPrintsAndParsesBack) {
  for (std::string_view blocks :
       {"nurbs", "polynomial", "spline-automatic", "spline-natural", "spline-auto"}) {
    std::string text = replaced(twoCutsText, "spline-natural", blocks);
    EXPECT_EQ(printFunction(parsed(text)), text) << blocks;
  }
  EXPECT_EQ(parseComplaint(replaced(twoCutsText, "prints spline-natural", "prints arcs")),
            "2: expected 'prints' with nurbs, polynomial or spline-automatic|natural|auto, found "
            "'arcs'");
}

TEST(CutTableText, BadLinesAreRefusedWithTheirLine) {
  EXPECT_EQ(parseComplaint(replaced(twoCutsText, "cut @1", "cut @3")), "3: expected cut @1 next");
  EXPECT_EQ(parseComplaint(replaced(twoCutsText, "arcs fitted", "arcs always")),
            "3: expected 'arcs' with native or fitted, found 'always'");
  EXPECT_EQ(parseComplaint(replaced(twoCutsText, "beside 2.5", "side 2.5")),
            "3: expected 'increment', 'controller', 'method', 'prints', 'arcs', 'beside' or "
            "'blocks', found 'side'");
  EXPECT_EQ(parseComplaint(replaced(twoCutsText, "tolerance nan arcs", "nan arcs")),
            "3: expected 'cut @n tolerance T [increment I] [controller D] [method M] "
            "[prints BLOCKS] [arcs native|fitted] [beside R] [blocks \"...\"]'");
}

TEST(CutTableText, ACutBeginNamesACutOfTheTable) {
  std::vector<std::string> problems =
      verifyFunction(parsed(replaced(twoCutsText, "cut.begin 1", "cut.begin 2")));
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("begins cut 2, but the cut table has 2"), std::string::npos)
      << problems[0];
  // Built by hand without a table, any.
  std::string withoutTable = replaced(twoCutsText, "  cut @0", "  // cut @0");
  withoutTable = replaced(withoutTable, "  cut @1", "  // cut @1");
  EXPECT_TRUE(verifyFunction(parsed(withoutTable)).empty());
}

} // namespace
} // namespace cncc::ir
