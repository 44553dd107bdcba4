// The SVG plot: segment deviations, colours, and the picture's structure.
#include "report_test_paths.h"

#include "cncc/backends/svg_plot.h"

#include <gtest/gtest.h>

#include <numbers>
#include <string>

namespace cncc {
namespace {

using namespace report_test;

constexpr double pi = std::numbers::pi;

std::size_t occurrences(const std::string& text, const std::string& what) {
  std::size_t count = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
    ++count;
  }
  return count;
}

// The elements of `svg` whose opening tag contains `marker`.
std::vector<std::string> elementsWith(const std::string& svg, const std::string& marker) {
  std::vector<std::string> elements;
  for (std::size_t at = svg.find(marker); at != std::string::npos; at = svg.find(marker, at + 1)) {
    std::size_t begin = svg.rfind('<', at);
    elements.push_back(svg.substr(begin, svg.find('>', at) - begin + 1));
  }
  return elements;
}

// The value of ` name="value"` in the element; empty without it.
std::string attribute(const std::string& element, const std::string& name) {
  std::string key = " " + name + "=\"";
  std::size_t begin = element.find(key);
  if (begin == std::string::npos) {
    return "";
  }
  begin += key.size();
  std::size_t end = element.find('"', begin);
  return end == std::string::npos ? "" : element.substr(begin, end - begin);
}

TEST(ReportPlot, SegmentDeviationIsTheSagittaOfEachChord) {
  geom::ArcCurve arc(Eigen::Vector2d(0, 0), 10.0, 0.0, pi / 2);
  std::vector<Eigen::Vector3d> polyline = {
      {10, 0, 0}, {10 * std::cos(pi / 6), 10 * std::sin(pi / 6), 0}, {0, 10, 0}};
  std::vector<double> deviations = backends::segmentDeviations(polyline, arc, 1e-9);
  ASSERT_EQ(deviations.size(), 2u);
  EXPECT_NEAR(deviations[0], sagitta(pi / 6), 1e-8);
  EXPECT_NEAR(deviations[1], sagitta(pi / 3), 1e-8);
  EXPECT_TRUE(backends::segmentDeviations({{1, 2, 0}}, arc, 1e-6).empty());
}

TEST(ReportPlot, ColoursGoFromGreenThroughRedToPurpleBeyondTheTolerance) {
  EXPECT_EQ(backends::deviationColour(0.0, 1.0), backends::kOnTheCurveColour);
  EXPECT_EQ(backends::deviationColour(0.5, 1.0), "#f2c80f");
  EXPECT_EQ(backends::deviationColour(1.0, 1.0), "#d7191c");
  EXPECT_EQ(backends::deviationColour(1.0001, 1.0), backends::kBeyondToleranceColour);
  EXPECT_EQ(backends::deviationColour(0.1, std::nan("")), backends::kNoToleranceColour);
  // Continuous: every step of the ratio changes the colour.
  EXPECT_NE(backends::deviationColour(0.1, 1.0), backends::kOnTheCurveColour);
  EXPECT_NE(backends::deviationColour(0.2, 1.0), backends::deviationColour(0.3, 1.0));
  EXPECT_NE(backends::deviationColour(0.6, 1.0), "#f2c80f");
  EXPECT_NE(backends::deviationColour(0.6, 1.0), backends::deviationColour(0.9, 1.0));
}

class ReportPlotOfTwoCuts : public ::testing::Test {
protected:
  void SetUp() override {
    backends::PlotOptions options;
    options.title = "two cuts <test>";
    options.cutNames = {"first", "second"};
    // Cut 0 (two 45-degree chords, sagitta 0.761) exceeds its 0.5; cut 1
    // (four 22.5-degree chords, sagitta 0.192) is within 0.3 but above half of it.
    cuts_ = {quarterCircle(0.5), quarterCircle(0.3)};
    svg_ = backends::plotSvg(backends::executedPathOfToolPath(twoCutPath()), cuts_, options);
  }

  std::vector<ir::CutGeometry> cuts_;
  std::string svg_;
};

TEST_F(ReportPlotOfTwoCuts, HasACurvePerCutASegmentPerChordAndADotPerPoint) {
  EXPECT_EQ(svg_.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0), 0u);
  EXPECT_EQ(svg_.substr(svg_.size() - 7), "</svg>\n");
  EXPECT_EQ(occurrences(svg_, "class=\"curve\""), 2u);
  EXPECT_EQ(occurrences(svg_, "class=\"segment\""), 6u);
  EXPECT_EQ(occurrences(svg_, "class=\"point\""), 8u);
  // The retracts and plunges are vertical; only the rapid between the cuts shows.
  EXPECT_EQ(occurrences(svg_, "class=\"rapid\""), 1u);
  EXPECT_EQ(occurrences(svg_, "class=\"legend-cut\""), 2u);
  EXPECT_NE(svg_.find("<title>two cuts &lt;test&gt;</title>"), std::string::npos);
}

TEST_F(ReportPlotOfTwoCuts, SegmentsBeyondTheToleranceArePurpleOthersGreenToRed) {
  for (const std::string& segment : elementsWith(svg_, "class=\"segment\"")) {
    double deviation = std::stod(attribute(segment, "data-deviation"));
    if (attribute(segment, "data-cut") == "0") {
      EXPECT_NEAR(deviation, sagitta(pi / 4), 1e-6);
      EXPECT_EQ(attribute(segment, "stroke"), backends::kBeyondToleranceColour);
    } else {
      EXPECT_NEAR(deviation, sagitta(pi / 8), 1e-6);
      // 0.192 / 0.3 = 0.64: between yellow and red.
      std::string stroke = attribute(segment, "stroke");
      EXPECT_EQ(stroke, backends::deviationColour(sagitta(pi / 8), 0.3));
      EXPECT_NE(stroke, backends::kOnTheCurveColour);
      EXPECT_NE(stroke, backends::kBeyondToleranceColour);
    }
  }
}

TEST_F(ReportPlotOfTwoCuts, LegendGivesEachCutsDeviationAndTolerance) {
  EXPECT_NE(svg_.find("first: max deviation 0.76120 mm, tolerance 0.5 mm: EXCEEDED"),
            std::string::npos);
  EXPECT_NE(svg_.find("second: max deviation 0.19215 mm, tolerance 0.3 mm<"), std::string::npos);
  EXPECT_NE(svg_.find("x, y in mm"), std::string::npos);
  EXPECT_EQ(occurrences(svg_, "class=\"scale-bar\""), 1u);
}

// Per cut, a panel of deviation against path length: its curve has a step
// per chord, the tolerance line sits at the tolerance, the worst point at
// the largest deviation; the inset shows cut 0, the one beyond its tolerance.
TEST_F(ReportPlotOfTwoCuts, PanelsPlotDeviationAlongThePathAndTheInsetTheWorstPoint) {
  EXPECT_EQ(occurrences(svg_, "class=\"deviation-panel\""), 2u);
  std::vector<std::string> tolerances = elementsWith(svg_, "class=\"tolerance-line\"");
  ASSERT_EQ(tolerances.size(), 2u);
  EXPECT_EQ(attribute(tolerances[0], "data-tolerance"), "0.5");
  EXPECT_EQ(attribute(tolerances[1], "data-tolerance"), "0.3");
  std::vector<std::string> curves = elementsWith(svg_, "class=\"deviation-curve\"");
  ASSERT_EQ(curves.size(), 2u);
  // Two points (a step) per chord: 2 chords in cut 0, 4 in cut 1.
  EXPECT_EQ(occurrences(attribute(curves[0], "points"), ","), 4u);
  EXPECT_EQ(occurrences(attribute(curves[1], "points"), ","), 8u);
  std::vector<std::string> worst = elementsWith(svg_, "class=\"worst-point\"");
  ASSERT_EQ(worst.size(), 2u);
  EXPECT_NEAR(std::stod(attribute(worst[0], "data-deviation")), sagitta(pi / 4), 1e-6);
  // Above the tolerance line: a smaller y.
  EXPECT_LT(std::stod(attribute(worst[0], "cy")), std::stod(attribute(tolerances[0], "y1")));
  EXPECT_GT(std::stod(attribute(worst[1], "cy")), std::stod(attribute(tolerances[1], "y1")));
  std::vector<std::string> inset = elementsWith(svg_, "class=\"inset\"");
  ASSERT_EQ(inset.size(), 1u);
  EXPECT_EQ(attribute(inset[0], "data-cut"), "0");
  EXPECT_GE(occurrences(svg_, "class=\"inset-segment\""), 1u);
  EXPECT_GE(occurrences(svg_, "class=\"inset-curve\""), 1u);
}

TEST_F(ReportPlotOfTwoCuts, YGoesUp) {
  std::vector<std::string> points = elementsWith(svg_, "class=\"point\"");
  ASSERT_EQ(points.size(), 8u);
  // The first dot is (10, 0), the third (0, 10): higher up, so nearer the top.
  EXPECT_GT(std::stod(attribute(points[0], "cy")), std::stod(attribute(points[2], "cy")));
  EXPECT_GT(std::stod(attribute(points[0], "cx")), std::stod(attribute(points[2], "cx")));
}

} // namespace
} // namespace cncc
