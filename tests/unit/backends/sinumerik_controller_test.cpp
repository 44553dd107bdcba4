// The virtual Sinumerik: its reader, G0/G1, the B spline model (exact NURBS
// evaluation from SD/PW/PL), the C and A spline models with their
// transitions, subprograms, and errors that name the line.
#include "cncc/backends/sinumerik_controller.h"
#include "cncc/geom/curve_deviation.h"
#include "cncc/geom/interpolating_splines.h"
#include "cncc/geom/nurbs_curve.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace cncc::backends::sinumerik {
namespace {

using Eigen::Vector3d;

SinumerikRun runOk(const std::string& text) {
  SinumerikRun run = runSinumerikProgram(text);
  EXPECT_FALSE(run.error) << (run.error ? run.error->what() : "");
  return run;
}

TEST(SinumerikController, LinearAndRapidMoves) {
  SinumerikRun run = runOk("; header\nG54\nG17 G90 G71\nG0 Z5\nX10 Y0\nG1 Z-1 F200\n"
                           "X20 Y=5\nG0 Z5\nM30\n");
  EXPECT_EQ(run.start, Vector3d(10, 0, 5));
  ASSERT_EQ(run.moves.size(), 3u);
  EXPECT_EQ(run.moves[0].kind, MotionKind::Linear);
  EXPECT_EQ(run.moves[0].end, Vector3d(10, 0, -1));
  EXPECT_DOUBLE_EQ(run.moves[0].feed, 200);
  EXPECT_EQ(run.moves[1].end, Vector3d(20, 5, -1));
  EXPECT_EQ(run.moves[1].line, 7);
  EXPECT_EQ(run.moves[2].kind, MotionKind::Rapid);
  EXPECT_FALSE(run.inches);
}

TEST(SinumerikController, BSplineBlocksAreTheClampedNurbs) {
  // A cubic Bezier: start and three points, PL 0 inside the clamped start.
  SinumerikRun run = runOk("G0 X0 Y0 Z0\nG1 F100\nBSPLINE SD=3 X10 Y20 PL=0\n"
                           "X30 Y20 PL=0\nX40 Y0 PW=1 PL=2\nG0 Z5\nM30\n");
  ASSERT_EQ(run.splines.size(), 1u);
  geom::NurbsCurve bezier =
      geom::NurbsCurve::bezier({{0, 0, 0}, {10, 20, 0}, {30, 20, 0}, {40, 0, 0}});
  // The same curve, its parameter stretched to PL's length 2.
  const geom::Curve& executed = *run.splines[0].curve;
  EXPECT_DOUBLE_EQ(executed.domain().t1, 2.0);
  for (int i = 0; i <= 50; ++i) {
    double u = i / 50.0;
    EXPECT_LT((executed.point(2 * u) - bezier.point(u)).norm(), 1e-12) << u;
  }
  EXPECT_EQ(run.splines[0].points, 3u);
  // The sampled moves end at the last point, then the retract.
  ASSERT_GE(run.moves.size(), 3u);
  EXPECT_TRUE(run.moves[run.moves.size() - 2].end.isApprox(Vector3d(40, 0, 0)));
  EXPECT_EQ(run.moves.back().kind, MotionKind::Rapid);
}

TEST(SinumerikController, WeightsMakeAnExactCircle) {
  // A quarter circle of radius 10 as a quadratic NURBS, middle weight
  // cos(45 degrees) rounded to PW's 0.0001 steps.
  SinumerikRun run =
      runOk("G0 X10 Y0 Z0\nG1 F100\nBSPLINE SD=2 X10 Y10 PW=0.7071 PL=0\nX0 Y10 PL=1\nM30\n");
  ASSERT_EQ(run.splines.size(), 1u);
  const geom::Curve& curve = *run.splines[0].curve;
  double worst = 0;
  for (int i = 0; i <= 100; ++i) {
    Vector3d point = curve.point(curve.domain().t0 + curve.domain().length() * i / 100.0);
    worst = std::max(worst, std::abs(point.norm() - 10.0));
  }
  EXPECT_LT(worst, 2e-4); // the weight's rounding
  EXPECT_GT(worst, 1e-7); // ... which is not nothing: the weight is used
  // Samples are dense: no chord sags more than the sample tolerance.
  EXPECT_GT(run.moves.size(), 100u);
}

TEST(SinumerikController, CSplineIsTheModelThroughItsPoints) {
  SinumerikRun run = runOk("G0 X0 Y0 Z-1\nG1 F100\nBNAT ENAT\nCSPLINE X10 Y5\nX20 Y-3\nX30 Y2\n"
                           "X40 Y0\nX50 Y4\nG0 Z5\nM30\n");
  ASSERT_EQ(run.splines.size(), 1u);
  std::vector<Vector3d> points{{0, 0, -1},  {10, 5, -1}, {20, -3, -1},
                               {30, 2, -1}, {40, 0, -1}, {50, 4, -1}};
  geom::SplineTransitions natural{geom::SplineEndCondition::Natural,
                                  geom::SplineEndCondition::Natural, std::nullopt, std::nullopt};
  geom::PiecewisePolynomialCurve model = geom::cSpline(points, natural);
  EXPECT_LT(geom::measureCurveDeviation(*run.splines[0].curve, model, {1e-7}).maxDeviation(), 1e-7);
  // With the default BTAN ETAN the spline is another one.
  SinumerikRun tangent = runOk("G0 X0 Y0 Z-1\nG1 F100\nCSPLINE X10 Y5\nX20 Y-3\nX30 Y2\n"
                               "X40 Y0\nX50 Y4\nG0 Z5\nM30\n");
  EXPECT_GT(geom::measureCurveDeviation(*tangent.splines[0].curve, model, {1e-6}).maxDeviation(),
            1e-3);
}

TEST(SinumerikController, BtanContinuesTheLineBeforeTheASpline) {
  SinumerikRun run = runOk("G0 X-10 Y-10 Z0\nG1 X0 Y0 F100\nBTAN EAUTO\nASPLINE X10 Y3\n"
                           "X20 Y-2\nX30 Y1\nX40 Y0\nM30\n");
  ASSERT_EQ(run.splines.size(), 1u);
  const geom::Curve& curve = *run.splines[0].curve;
  Vector3d start = curve.derivative(curve.domain().t0).normalized();
  EXPECT_NEAR(start.x(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(start.y(), std::sqrt(0.5), 1e-12);
  EXPECT_EQ(run.splines[0].kind, MotionKind::ASpline);
}

TEST(SinumerikController, SubprogramsRunAsIfWrittenInline) {
  std::string inline_ = "G0 X0 Y0 Z-1\nG1 F100\nCSPLINE X10 Y5\nX20 Y-3\nX30 Y2\nG0 Z5\nM30\n";
  std::string archive = "%_N_MAIN_MPF\n;$PATH=/_N_MPF_DIR\nG0 X0 Y0 Z-1\nG1 F100\nMAIN_CUT1\n"
                        "G0 Z5\nM30\n%_N_MAIN_CUT1_SPF\n;$PATH=/_N_SPF_DIR\nCSPLINE X10 Y5\n"
                        "X20 Y-3\nX30 Y2\nM17\n";
  SinumerikRun a = runOk(inline_);
  SinumerikRun b = runOk(archive);
  ASSERT_EQ(a.moves.size(), b.moves.size());
  for (std::size_t i = 0; i < a.moves.size(); ++i) {
    EXPECT_TRUE(a.moves[i].end.isApprox(b.moves[i].end, 1e-12));
  }
  // Moves made by the subprogram belong to the line that called it.
  EXPECT_EQ(b.moves.front().mainLine, 5);
  EXPECT_EQ(b.moves.front().line, 10);
}

TEST(SinumerikController, ExecutedPathTakesTheCutsOfItsLines) {
  SinumerikRun run = runOk("G0 X0 Y0 Z0\nG1 X5 F100\nX10\nM30\n");
  std::vector<std::optional<std::size_t>> cutOfLine{std::nullopt, std::nullopt, 0, std::nullopt};
  ExecutedPath path = executedPathOf(run, cutOfLine);
  ASSERT_EQ(path.moves.size(), 2u);
  EXPECT_FALSE(path.moves[0].cut);
  EXPECT_EQ(path.moves[1].cut, 0u);
}

void expectError(const std::string& text, int line, const std::string& words) {
  SinumerikRun run = runSinumerikProgram(text);
  ASSERT_TRUE(run.error) << text;
  EXPECT_EQ(run.error->line(), line) << run.error->what();
  EXPECT_NE(std::string(run.error->what()).find(words), std::string::npos) << run.error->what();
}

TEST(SinumerikController, ErrorsNameTheLine) {
  expectError("G0 X0 Y0 Z0\nG1 F100\nBSPLINE X1 Y1 PW=4 PL=0\nM30\n", 3, "PW=4");
  expectError("G0 X0 Y0 Z0\nG1 X1\nM30\n", 2, "feed");
  expectError("G0 X0 Y0 Z0\nG1 F100\nBSPLINE X1 Y1 PL=1\nX2 Y0\nX3 Y1\nM30\n", 3, "PL of point 1");
  expectError("G0 X0 Y0 Z0\nG1 F100\nBSPLINE SD=4 X1\nM30\n", 3, "SD=4");
  expectError("G0 X0 Y0 Z0\nFOO\nM30\n", 2, "'FOO'");
  expectError("G0 X0 Y0 Z0\nG1 X1 F100\n", 2, "M30");
  expectError("G0 X=R1*\nM30\n", 1, "a value is missing");
  expectError("G0 X0 Y0 Z0\nSPLINEPATH(1,X,Y)\nG1 F1\nCSPLINE X1 Y1 Z2\nM30\n", 4, "spline axes");
  expectError("G0 X0 Y0 Z0\nG1 F10\nCSPLINE X1 Y1\nX1 Y1\nM30\n", 3, "cannot be built");
}

TEST(SinumerikController, BSplineOfBlocksChecksItsNumbers) {
  EXPECT_THROW(bsplineOfBlocks({0, 0, 0}, 3, {{1, 0, 0}, {2, 0, 0}}, {1, 1}, {0, 0}),
               geom::GeometryError);
  geom::NurbsCurve line = bsplineOfBlocks({0, 0, 0}, 2, {{1, 0, 0}, {2, 0, 0}}, {1, 1}, {0, 3});
  EXPECT_EQ(line.knots().values(), (std::vector<double>{0, 0, 0, 3, 3, 3}));
}

} // namespace
} // namespace cncc::backends::sinumerik
