// `cncc plot`: an SVG picture of a compiled part for a person to look at.
// Each cut's true curve is a thin line; the executed path is drawn over it
// segment by segment, coloured by how far the segment strays from the curve
// on a continuous scale (green on the curve, yellow at half the tolerance,
// red at the tolerance, a distinct purple beyond it); the emitted points are
// dots, rapids dashed. A magnified inset shows the path around the point
// worst against its tolerance; under the picture, per cut, a panel plots the
// deviation against the length of path cut, with the tolerance line and the
// worst point marked. A legend gives each cut's largest deviation and
// tolerance; axes are in the part's unit with y up.
#pragma once

#include "cncc/backends/executed_path.h"
#include "cncc/geom/curve.h"
#include "cncc/ir/cut_geometry.h"

#include <Eigen/Core>

#include <span>
#include <string>
#include <vector>

namespace cncc::backends {

struct PlotOptions {
  std::string title;                 // one line above the picture
  std::string unit = "mm";           // of the axes and the legend
  std::vector<std::string> cutNames; // as in StatisticsOptions
  double width = 800;                // of the drawing area, in pixels
};

// The colours, for the picture's legend and for tests.
inline constexpr const char* kOnTheCurveColour = "#1a9641";
inline constexpr const char* kBeyondToleranceColour = "#5e3c99";
inline constexpr const char* kNoToleranceColour = "#2c7bb6";
// The drawn curve of a cut beside it (side=), a thin line by the path.
inline constexpr const char* kDrawnContourColour = "#e7298a";

// The colour of a segment `deviation` away from the curve: from green (0)
// through yellow (half the tolerance) to red at the tolerance, purple
// beyond; blue when the cut has no tolerance (NaN).
std::string deviationColour(double deviation, double tolerance);

// For each segment of `polyline` (segment i joins vertices i and i + 1), the
// largest distance from a point of it to `curve`, found by sampling and then
// refining the largest sample (to about `accuracy`).
std::vector<double> segmentDeviations(const std::vector<Eigen::Vector3d>& polyline,
                                      const geom::Curve& curve, double accuracy);

std::string plotSvg(const ExecutedPath& path, std::span<const ir::CutGeometry> cuts,
                    const PlotOptions& options);

} // namespace cncc::backends
