// The contour a cut beside its curve (side=) leaves: d(C(t), tool-centre
// path) - r along the drawn curve C, as gouge and undercut.
#include "cncc/backends/contour_left.h"
#include "cncc/backends/svg_plot.h"
#include "cncc/backends/verification.h"
#include "cncc/geom/composite_curve.h"
#include "cncc/geom/line_arc_curves.h"
#include "cncc/geom/offset_curve.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

namespace cncc {
namespace {

constexpr double pi = std::numbers::pi;
using Polylines = std::vector<std::vector<Eigen::Vector3d>>;

std::shared_ptr<const geom::Curve> line(double x0, double y0, double x1, double y1) {
  return std::make_shared<geom::LineCurve>(Eigen::Vector3d(x0, y0, 0), Eigen::Vector3d(x1, y1, 0));
}

// A straight edge from (0, 0) to (100, 0), the tool of radius 3 on its left.
ir::CutGeometry straightEdge() {
  ir::CutGeometry cut;
  cut.drawnCurve = line(0, 0, 100, 0);
  cut.curve = line(0, 3, 100, 3);
  cut.toolRadius = 3;
  cut.tolerance = 0.01;
  return cut;
}

// The tool centre along y = `height` over the edge, in a few feed moves.
Polylines pathAlong(double height) {
  std::vector<Eigen::Vector3d> points;
  for (int k = 0; k <= 4; ++k) {
    points.emplace_back(25.0 * k, height, 0);
  }
  return {points};
}

TEST(ContourLeft, APathOnTheExactOffsetLeavesTheDrawnCurve) {
  backends::ContourLeft left = backends::measureContourLeft(0, straightEdge(), pathAlong(3), 1e-6);
  EXPECT_NEAR(left.largestGouge, 0, 1e-9);
  EXPECT_NEAR(left.largestUndercut, 0, 1e-9);
  EXPECT_TRUE(left.withinTolerance());
  EXPECT_EQ(left.toolRadius, 3);
  EXPECT_GE(left.samples, 100.0 / (0.01 / 4));
}

TEST(ContourLeft, APathMovedTowardTheCurveGougesByTheMove) {
  backends::ContourLeft left =
      backends::measureContourLeft(2, straightEdge(), pathAlong(3 - 0.05), 1e-6);
  EXPECT_EQ(left.cut, 2u);
  EXPECT_NEAR(left.largestGouge, 0.05, 1e-9);
  EXPECT_NEAR(left.largestUndercut, 0, 1e-9);
  EXPECT_NEAR(left.gougeAt.y(), 0, 1e-12); // on the drawn curve
  EXPECT_FALSE(left.withinTolerance());
}

TEST(ContourLeft, APathMovedAwayLeavesMaterial) {
  backends::ContourLeft left =
      backends::measureContourLeft(0, straightEdge(), pathAlong(3 + 0.004), 1e-6);
  EXPECT_NEAR(left.largestUndercut, 0.004, 1e-9);
  EXPECT_NEAR(left.largestGouge, 0, 1e-9);
  EXPECT_TRUE(left.withinTolerance()); // 0.004 of 0.01
}

// Chords on the outside offset of an arc (radius 10, tool radius 2 outside:
// centre on radius 12) cut into the part by their sagitta 12 (1 - cos(a/2)),
// largest at a chord's middle, found between the samples.
TEST(ContourLeft, ChordsOutsideAnArcGougeByTheirSagitta) {
  ir::CutGeometry cut;
  cut.drawnCurve = std::make_shared<geom::ArcCurve>(Eigen::Vector2d(0, 0), 10.0, 0.0, pi / 2);
  cut.curve = std::make_shared<geom::ArcCurve>(Eigen::Vector2d(0, 0), 12.0, 0.0, pi / 2);
  cut.toolRadius = 2;
  cut.tolerance = 0.01;
  std::vector<Eigen::Vector3d> chords;
  const int count = 9;
  for (int k = 0; k <= count; ++k) {
    double angle = pi / 2 * k / count;
    chords.emplace_back(12 * std::cos(angle), 12 * std::sin(angle), 0);
  }
  backends::ContourLeft left = backends::measureContourLeft(0, cut, {chords}, 1e-6);
  double sagitta = 12 * (1 - std::cos(pi / 2 / count / 2));
  EXPECT_NEAR(left.largestGouge, sagitta, 1e-7);
  EXPECT_NEAR(left.largestUndercut, 0, 1e-9);
  double angle = std::atan2(left.gougeAt.y(), left.gougeAt.x());
  double chord = angle / (pi / 2 / count);
  EXPECT_NEAR(chord - std::floor(chord), 0.5, 1e-3); // a chord's middle
  EXPECT_FALSE(left.withinTolerance());              // 0.0183 > 0.01
}

// An L with the tool outside its convex corner: the path goes round the
// corner on an arc of the tool radius (distance r from the corner point), as
// chords well within the tolerance. Inside the L (its concave corner) the
// exact offset stops short of the corner, and what it leaves there is not
// the path's undercut.
TEST(ContourLeft, CornersLeaveOnlyWhatTheExactOffsetLeaves) {
  std::vector<std::shared_ptr<const geom::Curve>> pieces = {line(0, 0, 20, 0), line(20, 0, 20, 20)};
  auto drawn = std::make_shared<geom::CompositeCurve>(pieces);
  for (double side : {-2.0, 2.0}) {
    ir::CutGeometry cut;
    cut.drawnCurve = drawn;
    cut.curve = geom::offsetOfPieces(pieces, side);
    cut.toolRadius = 2;
    cut.tolerance = 0.01;
    // The exact offset as fine chords (within 1e-5).
    std::vector<Eigen::Vector3d> path;
    geom::ParameterRange domain = cut.curve->domain();
    for (int k = 0; k <= 20000; ++k) {
      path.push_back(cut.curve->point(domain.t0 + domain.length() * k / 20000));
    }
    backends::ContourLeft left = backends::measureContourLeft(0, cut, {path}, 1e-7);
    EXPECT_LT(left.largestGouge, 2e-5) << side;
    EXPECT_LT(left.largestUndercut, 2e-5) << side;
    EXPECT_TRUE(left.withinTolerance()) << side;
  }
}

TEST(ContourLeft, ThePlotDrawsTheDrawnContourOfACutBesideIt) {
  ir::CutGeometry edge = straightEdge();
  backends::ExecutedPath path;
  path.start = {0, 3, 0};
  for (int k = 1; k <= 4; ++k) {
    path.moves.push_back({false, Eigen::Vector3d(25.0 * k, 3, 0), 100, 0});
  }
  std::vector<ir::CutGeometry> cuts = {edge};
  std::string svg = backends::plotSvg(path, cuts, {});
  std::size_t drawn = svg.find("class=\"drawn-contour\" data-cut=\"0\"");
  ASSERT_NE(drawn, std::string::npos);
  EXPECT_NE(svg.find(std::string("stroke=\"") + backends::kDrawnContourColour), std::string::npos);
  EXPECT_NE(svg.find("drawn contour of a cut beside it (side=)"), std::string::npos);
  cuts.front().drawnCurve = nullptr;
  std::string onItsCurve = backends::plotSvg(path, cuts, {});
  EXPECT_EQ(onItsCurve.find("drawn-contour"), std::string::npos);
  EXPECT_EQ(onItsCurve.find("drawn contour"), std::string::npos);
}

TEST(ContourLeft, AGougeBeyondTheToleranceFailsTheVerdictAndIsPrinted) {
  backends::VerificationReport report;
  report.target = "gcode";
  report.contours.push_back(
      backends::measureContourLeft(0, straightEdge(), pathAlong(3 - 0.05), 1e-6));
  EXPECT_FALSE(report.passed());
  std::string text = backends::formatVerification(report, {});
  EXPECT_NE(
      text.find("cut 1: tool radius 3, material left none, cut past the curve 0.05000 mm at "),
      std::string::npos)
      << text;
  EXPECT_NE(text.find("tolerance 0.01 mm, EXCEEDED"), std::string::npos);
  report.contours.front() =
      backends::measureContourLeft(0, straightEdge(), pathAlong(3 + 0.002), 1e-6);
  EXPECT_TRUE(report.passed());
}

} // namespace
} // namespace cncc
