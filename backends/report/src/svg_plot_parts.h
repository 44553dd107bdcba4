// The pieces of `cncc plot` (svg_plot.h) shared by its files: the executed
// path of each cut with each segment's deviation, measured once, and text
// escaping.
#pragma once

#include "cncc/backends/executed_path.h"
#include "cncc/ir/cut_geometry.h"

#include <Eigen/Core>

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::backends::plot {

// One pass of a cut: its points, and the deviation of the segment from
// point i to point i + 1 (empty when the cut has no curve).
struct PlottedPolyline {
  std::vector<Eigen::Vector3d> points;
  std::vector<double> deviations;
};

struct PlottedCut {
  std::vector<PlottedPolyline> polylines;
  double tolerance = 0; // NaN: none
};

// Every cut's passes, each segment measured to `accuracy` in the plan view.
std::vector<PlottedCut> plottedCuts(const ExecutedPath& path, std::span<const ir::CutGeometry> cuts,
                                    double accuracy);

std::string escaped(std::string_view text);

// Per cut with feed moves, a panel of deviation against the length of path
// cut, with the tolerance line and the worst point marked; `top` is where
// they start. Their height is panelsHeight(...).
std::string deviationPanels(const std::vector<PlottedCut>& cuts,
                            const std::vector<std::string>& names, double left, double top,
                            double width, const std::string& unit);
double panelsHeight(const std::vector<PlottedCut>& cuts);

// A square of `size` pixels at (x, y) showing, magnified, the true curve and
// the path around the point that is worst against its tolerance; empty
// when no cut has a deviation.
std::string worstPointInset(const std::vector<PlottedCut>& plotted,
                            std::span<const ir::CutGeometry> cuts, double x, double y, double size);

} // namespace cncc::backends::plot
