// The sinumerik writer: program layout, the S-profile NURBS as BSPLINE
// blocks exactly, the polar contour of REFERENCE-CASES.md case 3 as C, A
// and B splines (counts against the reference figures), each program run
// in the virtual Sinumerik and measured against the true curve.
#include "sinumerik_test_parts.h"

#include "cncc/backends/path_statistics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

namespace cncc::backends {
namespace {

using testing::compileForSinumerik;
using testing::countLines;
using testing::exampleText;
using testing::replaced;
using testing::SinumerikPart;

// Runs the part's program in the virtual Sinumerik: the largest deviation
// of its cut 0 from the true curve, as `--stats` measures the sampled path
// (and, more exactly, the executed splines themselves).
struct Verified {
  double pathDeviation = 0;
  double splineDeviation = 0;
};

Verified verify(const SinumerikPart& part) {
  // Chords sagging a thousandth of the tolerance, at least 1e-6 mm.
  sinumerik::SinumerikRunOptions options;
  options.sampleTolerance = std::max(1e-6, part.cuts.front().tolerance * 1e-3);
  sinumerik::SinumerikRun run = sinumerik::runSinumerikProgram(part.output.text, options);
  EXPECT_FALSE(run.error) << (run.error ? run.error->what() : "");
  const std::vector<ir::CutGeometry>& cuts = part.cuts;
  ExecutedProgram program{part.output.text, 0,
                          sinumerik::executedPathOf(run, part.output.cutOfLine)};
  PathStatistics statistics = measureProgram(program, cuts, {});
  EXPECT_FALSE(statistics.cuts.empty());
  Verified verified;
  verified.pathDeviation = statistics.maxDeviation();
  verified.splineDeviation =
      testing::splineDeviation(run, *cuts.front().curve, cuts.front().tolerance * 1e-3);
  return verified;
}

std::string polarContour(const std::string& method, double tolerance) {
  std::ostringstream modifiers;
  modifiers << "tolerance=" << tolerance << " method=" << method;
  return replaced(exampleText("polar_contour.cdl"), "tolerance=0.01", modifiers.str());
}

TEST(SinumerikWriter, Numbers) {
  EXPECT_EQ(formatSinumerikNumber(10.0, 5), "10");
  EXPECT_EQ(formatSinumerikNumber(-1.25, 5), "-1.25");
  EXPECT_EQ(formatSinumerikNumber(-0.000001, 5), "0");
  EXPECT_EQ(formatSinumerikNumber(0.123456, 5), "0.12346");
}

TEST(SinumerikWriter, LinearCutsAreG1BlocksInTheUsualLayout) {
  auto part = compileForSinumerik(exampleText("s_profile.cdl"));
  ASSERT_TRUE(part);
  const std::string& text = part->output.text;
  EXPECT_EQ(text.rfind("; ", 0), 0u);
  for (const char* line : {"G54\n", "T=\"T1\" D1", "\nM6\n", "\nCYCLE832(0.01, _FINISH, 1)\n",
                           "M3 S3000\n", "\nCYCLE832()\nSUPA G0 Z0 D0\nM5\nM30\n"}) {
    EXPECT_NE(text.find(line), std::string::npos) << line;
  }
  EXPECT_EQ(text.find("SPLINE"), std::string::npos);
  // One feed block per feed move of the tool path.
  std::size_t feeds = 0;
  for (const ir::MachineEvent& event : part->path.events) {
    feeds += event.kind == ir::MachineEvent::Kind::Feed ? 1 : 0;
  }
  // The chords are chosen again with the printed rounding taken off the
  // tolerance: about the 115 per pass of REFERENCE-CASES.md case 1.
  std::size_t chords = part->output.cuts[0].blocksPerPass;
  EXPECT_EQ(part->output.cuts[0].method, "linear");
  EXPECT_GE(chords, 115u);
  EXPECT_LE(chords, 117u);
  EXPECT_GE(feeds, 3 * 115u);
  // Per pass: the rapid over the start, the plunge, the chords.
  std::size_t motion = countLines(text, "X") + countLines(text, "Y") + countLines(text, "G1 ");
  EXPECT_EQ(motion, 3 * (chords + 2));
  EXPECT_LE(verify(*part).pathDeviation, 0.01);
}

TEST(SinumerikWriter, SProfileNurbsIsWrittenExactly) {
  auto part = compileForSinumerik(
      replaced(exampleText("s_profile.cdl"), "tolerance=0.01", "tolerance=0.01 method=bspline"));
  ASSERT_TRUE(part);
  const std::string& text = part->output.text;
  // The 7 control points: the start and one block per other point, each pass.
  EXPECT_EQ(countLines(text, "BSPLINE SD=3 X42.8735 Y24.1467 PW=1 PL=0"), 3u);
  EXPECT_EQ(countLines(text, "X132.4671 Y35.1148 PW=3 PL=0.25"), 3u);
  EXPECT_EQ(part->output.cuts[0].blocksPerPass, 6u);
  EXPECT_EQ(countLines(text, "; 6 BSPLINE control points, deviation "), 3u);
  EXPECT_NE(text.find("mm, the NURBS as it is\n"), std::string::npos);
  Verified verified = verify(*part);
  EXPECT_LT(verified.splineDeviation, 1e-6);
  EXPECT_LE(verified.pathDeviation, 1e-5); // the sampled path, chords of 1e-6 mm
}

TEST(SinumerikWriter, WeightsOutsidePwAreReparametrisedNotClipped) {
  // w6 = 5 is outside PW's 0..3 (relative to the first weight, 1): a
  // reparametrisation brings it in, the curve unchanged.
  auto part = compileForSinumerik(replaced(
      replaced(exampleText("s_profile.cdl"), "tolerance=0.01", "tolerance=0.01 method=bspline"),
      "w6 = 3", "w6 = 5"));
  ASSERT_TRUE(part);
  EXPECT_NE(part->output.text.find("the NURBS as it is, reparametrised (lambda "),
            std::string::npos);
  EXPECT_EQ(part->output.text.find("PW=5"), std::string::npos);
  EXPECT_EQ(part->output.cuts[0].blocksPerPass, 6u);
  Verified verified = verify(*part);
  // Only the printed numbers move it: PW in steps of 0.0001 (2.3e-4 mm).
  EXPECT_LE(verified.splineDeviation, 5e-4);
  EXPECT_LE(verified.pathDeviation, 0.01);
  // A weight no reparametrisation brings into PW's range: re-fitted.
  auto refitted = compileForSinumerik(replaced(
      replaced(exampleText("s_profile.cdl"), "tolerance=0.01", "tolerance=0.01 method=bspline"),
      "weights=[1,1,1,1,1,w6,1]", "weights=[1,1,1,0.000001,1,1,1]"));
  ASSERT_TRUE(refitted);
  EXPECT_NE(refitted->output.text.find(", re-fitted: no reparametrisation brings its weights"),
            std::string::npos);
  EXPECT_EQ(refitted->output.text.find("the NURBS as it is"), std::string::npos);
  Verified refit = verify(*refitted);
  EXPECT_LE(refit.splineDeviation, 0.01);
  EXPECT_LE(refit.pathDeviation, 0.01);
  // Scaling all weights keeps a NURBS: first weight 2, the others up to 6.
  auto scaled = compileForSinumerik(replaced(
      replaced(exampleText("s_profile.cdl"), "tolerance=0.01", "tolerance=0.01 method=bspline"),
      "weights=[1,1,1,1,1,w6,1]", "weights=[2,2,2,2,2,6,2]"));
  ASSERT_TRUE(scaled);
  EXPECT_NE(scaled->output.text.find("mm, the NURBS as it is\n"), std::string::npos);
  EXPECT_EQ(countLines(scaled->output.text, "X132.4671 Y35.1148 PW=3 PL=0.25"), 3u);
}

TEST(SinumerikWriter, QuadraticNurbsIsSdTwoWithRoundedWeights) {
  // A quarter circle: the middle weight cos(45 degrees) becomes PW=0.7071,
  // which moves the curve by about 1e-5 mm, well within the tolerance.
  auto part = compileForSinumerik(
      "part arc {\n  tool 1 diameter=6 feed=200\n  safe z=5\n"
      "  curve nurbs(order=3, points=[(10,0),(10,10),(0,10)], weights=[1,0.70710678,1]) "
      "tolerance=0.001 method=bspline\n}\n");
  ASSERT_TRUE(part);
  EXPECT_EQ(countLines(part->output.text, "BSPLINE SD=2 X10 Y10 PW=0.7071 PL=0"), 1u);
  EXPECT_EQ(countLines(part->output.text, "X0 Y10 PW=1 PL=1"), 1u);
  EXPECT_NE(part->output.text.find("the NURBS as it is"), std::string::npos);
  Verified verified = verify(*part);
  EXPECT_LT(verified.splineDeviation, 1e-4);
  EXPECT_GT(verified.splineDeviation, 1e-7); // the rounded weight is what runs
}

// REFERENCE-CASES.md case 3: equally spaced knots need 106 (C spline) and
// 128 (A spline), least-squares control points 96 at 0.01 mm.
TEST(SinumerikWriter, PolarContourCSplineAtTenMicrometres) {
  auto part = compileForSinumerik(polarContour("cspline", 0.01));
  ASSERT_TRUE(part);
  std::size_t knots = part->output.cuts[0].blocksPerPass;
  EXPECT_LE(knots, 106u * 11 / 10);
  EXPECT_GE(knots, 50u);
  EXPECT_EQ(countLines(part->output.text, "CSPLINE "), 1u);
  EXPECT_EQ(countLines(part->output.text, "BTAN ENAT"), 1u); // after the ramp
  Verified verified = verify(*part);
  EXPECT_LE(verified.splineDeviation, 0.01);
  EXPECT_LE(verified.pathDeviation, 0.01);
}

TEST(SinumerikWriter, PolarContourASplineAtTenMicrometres) {
  auto part = compileForSinumerik(polarContour("aspline", 0.01));
  ASSERT_TRUE(part);
  EXPECT_LE(part->output.cuts[0].blocksPerPass, 128u * 11 / 10);
  Verified verified = verify(*part);
  EXPECT_LE(verified.splineDeviation, 0.01);
  EXPECT_LE(verified.pathDeviation, 0.01);
}

TEST(SinumerikWriter, PolarContourBSplineAtTenMicrometres) {
  auto part = compileForSinumerik(polarContour("bspline", 0.01));
  ASSERT_TRUE(part);
  EXPECT_LE(part->output.cuts[0].blocksPerPass + 1, 96u * 11 / 10);
  Verified verified = verify(*part);
  EXPECT_LE(verified.splineDeviation, 0.01);
  EXPECT_LE(verified.pathDeviation, 0.01);
}

TEST(SinumerikWriter, PolarContourCSplineAtOneMicrometre) {
  auto part = compileForSinumerik(polarContour("cspline", 0.001));
  ASSERT_TRUE(part);
  EXPECT_LE(part->output.cuts[0].blocksPerPass, 182u * 11 / 10);
  Verified verified = verify(*part);
  EXPECT_LE(verified.splineDeviation, 0.001);
  EXPECT_LE(verified.pathDeviation, 0.001);
}

TEST(SinumerikWriter, TransitionsAsAsked) {
  for (SinumerikTransitions transitions :
       {SinumerikTransitions::Natural, SinumerikTransitions::Auto}) {
    SinumerikOptions options;
    options.transitions = transitions;
    auto part = compileForSinumerik(polarContour("cspline", 0.05), options);
    ASSERT_TRUE(part);
    const char* words = transitions == SinumerikTransitions::Natural ? "BNAT ENAT" : "BAUTO EAUTO";
    EXPECT_EQ(countLines(part->output.text, words), 1u);
    Verified verified = verify(*part);
    EXPECT_LE(verified.splineDeviation, 0.05);
  }
}

TEST(SinumerikWriter, SubprogramLayoutRunsAsTheInlineOne) {
  std::string text =
      replaced(exampleText("s_profile.cdl"), "tolerance=0.01", "tolerance=0.01 method=cspline");
  SinumerikOptions options;
  options.programName = "s_profile";
  auto inlined = compileForSinumerik(text, options);
  options.subprograms = true;
  auto layout = compileForSinumerik(text, options);
  ASSERT_TRUE(inlined && layout);
  const std::string& program = layout->output.text;
  EXPECT_EQ(program.rfind("%_N_S_PROFILE_MPF\n", 0), 0u);
  EXPECT_EQ(countLines(program, "%_N_S_PROFILE_CUT1_SPF"), 1u); // one for all three passes
  EXPECT_EQ(countLines(program, "S_PROFILE_CUT1"), 3u);
  EXPECT_EQ(countLines(program, "CSPLINE"), 1u);
  sinumerik::SinumerikRun a = sinumerik::runSinumerikProgram(inlined->output.text);
  sinumerik::SinumerikRun b = sinumerik::runSinumerikProgram(program);
  ASSERT_FALSE(a.error || b.error);
  ASSERT_EQ(a.moves.size(), b.moves.size());
  for (std::size_t i = 0; i < a.moves.size(); ++i) {
    ASSERT_TRUE(a.moves[i].end.isApprox(b.moves[i].end, 1e-12)) << i;
  }
  EXPECT_LE(verify(*layout).pathDeviation, 0.01);
}

// Every cut of a part within its tolerance in the virtual Sinumerik: loops,
// transforms and method=cspline (the rosette, imports resolved against the
// examples), and a helix, whose z is not the spline plane's (G1 chords).
void expectEveryCutWithinTolerance(const SinumerikPart& part) {
  sinumerik::SinumerikRunOptions options;
  options.sampleTolerance = 1e-5; // the tightest tolerance here is 0.005 mm
  sinumerik::SinumerikRun run = sinumerik::runSinumerikProgram(part.output.text, options);
  ASSERT_FALSE(run.error) << run.error->what();
  const std::vector<ir::CutGeometry>& cuts = part.cuts;
  ExecutedProgram program{part.output.text, 0,
                          sinumerik::executedPathOf(run, part.output.cutOfLine)};
  PathStatistics statistics = measureProgram(program, cuts, {});
  ASSERT_EQ(statistics.cuts.size(), cuts.size());
  for (const CutDeviation& cut : statistics.cuts) {
    EXPECT_GT(cut.feedMoves, 0u) << "cut " << cut.cut + 1;
    EXPECT_TRUE(cut.withinTolerance()) << "cut " << cut.cut + 1 << ": " << cut.maxDeviation;
  }
}

TEST(SinumerikWriter, RosetteAndHelixWithinTheirTolerances) {
  auto rosette = compileForSinumerik(exampleText("rosette_plate.cdl"));
  ASSERT_TRUE(rosette);
  EXPECT_EQ(countLines(rosette->output.text, "CSPLINE "), 6u * 3); // 6 petals, 3 passes
  expectEveryCutWithinTolerance(*rosette);
  auto helix = compileForSinumerik(exampleText("helix_bore.cdl"), {}, "bore_plate_mm");
  ASSERT_TRUE(helix);
  EXPECT_EQ(helix->output.text.find("SPLINE"), std::string::npos);
  expectEveryCutWithinTolerance(*helix);
}

} // namespace
} // namespace cncc::backends
