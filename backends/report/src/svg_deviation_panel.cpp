// `cncc plot`'s deviation panels and the magnified inset around the worst
// point (svg_plot_parts.h).
#include "cncc/backends/svg_plot.h"
#include "cncc/geom/deviation.h"
#include "plane_projection.h"
#include "svg_plot_parts.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace cncc::backends::plot {

namespace {

constexpr double kPanelTitle = 16; // pixels above a panel's plot area
constexpr double kPanelPlot = 64;  // its plot area
constexpr double kPanelGap = 22;   // below it, for the axis labels

double panelHeight() {
  return kPanelTitle + kPanelPlot + kPanelGap;
}

double planLength(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return (b - a).head<2>().norm();
}

bool hasDeviations(const PlottedCut& cut) {
  return std::any_of(cut.polylines.begin(), cut.polylines.end(),
                     [](const PlottedPolyline& line) { return !line.deviations.empty(); });
}

// The segment that is worst against its cut's tolerance (against nothing,
// its deviation, when no cut has one).
struct WorstSegment {
  std::size_t cut = 0;
  Eigen::Vector3d from, to;
  double deviation = -1;
  double length = 0; // of path cut before its middle
};

std::optional<WorstSegment> worstOfCut(const PlottedCut& cut, std::size_t index) {
  std::optional<WorstSegment> worst;
  double length = 0;
  for (const PlottedPolyline& line : cut.polylines) {
    for (std::size_t i = 0; i < line.deviations.size(); ++i) {
      double segment = planLength(line.points[i], line.points[i + 1]);
      if (!worst || line.deviations[i] > worst->deviation) {
        worst = WorstSegment{index, line.points[i], line.points[i + 1], line.deviations[i],
                             length + segment / 2};
      }
      length += segment;
    }
  }
  return worst;
}

std::string panel(const PlottedCut& cut, std::size_t index, const std::string& name, double left,
                  double top, double width, const std::string& unit) {
  double total = 0;
  double largest = 0;
  for (const PlottedPolyline& line : cut.polylines) {
    for (std::size_t i = 0; i < line.deviations.size(); ++i) {
      total += planLength(line.points[i], line.points[i + 1]);
      largest = std::max(largest, line.deviations[i]);
    }
  }
  bool tolerance = !std::isnan(cut.tolerance);
  double high = 1.15 * std::max(largest, tolerance ? cut.tolerance : 0.0);
  high = high > 0 ? high : 1.0;
  double plotTop = top + kPanelTitle;
  auto x = [&](double length) { return left + (total > 0 ? length / total : 0.0) * width; };
  auto y = [&](double deviation) { return plotTop + kPanelPlot * (1 - deviation / high); };
  std::string out =
      fmt::format("<g class=\"deviation-panel\" data-cut=\"{}\" font-size=\"11\">\n", index);
  std::optional<WorstSegment> worst = worstOfCut(cut, index);
  out += fmt::format("<text x=\"{:.2f}\" y=\"{:.2f}\">{}: deviation along {:.3f} {} of cut path, "
                     "largest {:.5f} {}</text>\n",
                     left, top + 12, escaped(name), total, escaped(unit), largest, escaped(unit));
  out += fmt::format("<rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\" "
                     "fill=\"none\" stroke=\"#999\"/>\n",
                     left, plotTop, width, kPanelPlot);
  if (tolerance) {
    out += fmt::format("<line class=\"tolerance-line\" data-tolerance=\"{:g}\" x1=\"{:.2f}\" "
                       "y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\" stroke=\"#d7191c\" "
                       "stroke-dasharray=\"5 3\"/>\n",
                       cut.tolerance, left, y(cut.tolerance), left + width, y(cut.tolerance));
  }
  out += "<polyline class=\"deviation-curve\" fill=\"none\" stroke=\"#333\" points=\"";
  double length = 0;
  for (const PlottedPolyline& line : cut.polylines) {
    for (std::size_t i = 0; i < line.deviations.size(); ++i) {
      double next = length + planLength(line.points[i], line.points[i + 1]);
      out += fmt::format("{:.2f},{:.2f} {:.2f},{:.2f} ", x(length), y(line.deviations[i]), x(next),
                         y(line.deviations[i]));
      length = next;
    }
  }
  out.back() = '"';
  out += "/>\n";
  if (worst) {
    out += fmt::format("<circle class=\"worst-point\" data-deviation=\"{:.6f}\" "
                       "data-length=\"{:.4f}\" cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"3.5\" "
                       "fill=\"none\" stroke=\"#000\"/>\n",
                       worst->deviation, worst->length, x(worst->length), y(worst->deviation));
  }
  double labels = plotTop + kPanelPlot + 13;
  out += fmt::format("<text x=\"{:.2f}\" y=\"{:.2f}\">0</text><text x=\"{:.2f}\" y=\"{:.2f}\" "
                     "text-anchor=\"end\">{:.3f} {}</text>\n",
                     left, labels, left + width, labels, total, escaped(unit));
  out += fmt::format("<text x=\"{:.2f}\" y=\"{:.2f}\" text-anchor=\"end\">{:.4f}</text>\n",
                     left - 4, plotTop + 9, high);
  return out + "</g>\n";
}

// Part coordinates around `centre` to the inset's pixels, y up.
struct InsetFrame {
  Eigen::Vector2d centre;
  double halfWidth = 1;
  double x0 = 0, y0 = 0, size = 1;

  double x(double partX) const { return x0 + size / 2 + (partX - centre.x()) * scale(); }
  double y(double partY) const { return y0 + size / 2 - (partY - centre.y()) * scale(); }
  double scale() const { return size / (2 * halfWidth); }
  bool near(const Eigen::Vector3d& point) const {
    return (point.head<2>() - centre).cwiseAbs().maxCoeff() <= 3 * halfWidth;
  }
  // Whether the segment passes within the window (its ends may lie far out).
  bool crossedBy(const Eigen::Vector3d& from, const Eigen::Vector3d& to) const {
    Eigen::Vector2d a = from.head<2>() - centre, b = to.head<2>() - centre;
    Eigen::Vector2d along = b - a;
    double u =
        along.squaredNorm() > 0 ? std::clamp(-a.dot(along) / along.squaredNorm(), 0.0, 1.0) : 0.0;
    return (a + u * along).norm() <= 3 * halfWidth;
  }
};

std::string insetCurve(const geom::Curve& curve, const InsetFrame& frame) {
  geom::CurveProximity samples(curve, frame.halfWidth / 400);
  std::string out;
  std::string run;
  for (const Eigen::Vector3d& point : samples.samplePoints()) {
    if (!frame.near(point)) {
      if (!run.empty()) {
        out += "<polyline class=\"inset-curve\" points=\"" + run + "\"/>\n";
        run.clear();
      }
      continue;
    }
    run += fmt::format("{}{:.2f},{:.2f}", run.empty() ? "" : " ", frame.x(point.x()),
                       frame.y(point.y()));
  }
  if (!run.empty()) {
    out += "<polyline class=\"inset-curve\" points=\"" + run + "\"/>\n";
  }
  return out;
}

} // namespace

double panelsHeight(const std::vector<PlottedCut>& cuts) {
  return panelHeight() *
         static_cast<double>(std::count_if(cuts.begin(), cuts.end(), hasDeviations));
}

std::string deviationPanels(const std::vector<PlottedCut>& cuts,
                            const std::vector<std::string>& names, double left, double top,
                            double width, const std::string& unit) {
  std::string out = "<g class=\"deviation-panels\">\n";
  for (std::size_t k = 0; k < cuts.size(); ++k) {
    if (!hasDeviations(cuts[k])) {
      continue;
    }
    std::string name = k < names.size() ? names[k] : fmt::format("cut {}", k + 1);
    out += panel(cuts[k], k, name, left, top, width, unit);
    top += panelHeight();
  }
  return out + "</g>\n";
}

std::string worstPointInset(const std::vector<PlottedCut>& plotted,
                            std::span<const ir::CutGeometry> cuts, double x, double y,
                            double size) {
  std::optional<WorstSegment> worst;
  auto ratio = [&](const WorstSegment& segment) {
    double tolerance = plotted[segment.cut].tolerance;
    return std::isnan(tolerance) || tolerance <= 0 ? segment.deviation
                                                   : segment.deviation / tolerance;
  };
  for (std::size_t k = 0; k < plotted.size(); ++k) {
    std::optional<WorstSegment> candidate = worstOfCut(plotted[k], k);
    if (candidate && cuts[k].curve != nullptr && (!worst || ratio(*candidate) > ratio(*worst))) {
      worst = candidate;
    }
  }
  if (!worst || !(worst->deviation > 0)) {
    return "";
  }
  InsetFrame frame;
  frame.centre = (0.5 * (worst->from + worst->to)).head<2>();
  // Narrow enough that the deviation is a twentieth of the window: visible.
  frame.halfWidth = std::max(10 * worst->deviation, 1e-6);
  frame.x0 = x;
  frame.y0 = y;
  frame.size = size;
  std::string out = fmt::format(
      "<g class=\"inset\" data-cut=\"{}\" data-deviation=\"{:.6f}\">\n<clipPath id=\"inset-clip\">"
      "<rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\"/></clipPath>\n"
      "<rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\" fill=\"#fff\" "
      "stroke=\"#333\"/>\n<g clip-path=\"url(#inset-clip)\">\n",
      worst->cut, worst->deviation, x, y, size, size, x, y, size, size);
  PlaneProjection plan(*cuts[worst->cut].curve);
  out += "<g fill=\"none\" stroke=\"#555\" stroke-width=\"0.8\">\n" + insetCurve(plan, frame) +
         "</g>\n";
  for (const PlottedPolyline& line : plotted[worst->cut].polylines) {
    for (std::size_t i = 0; i < line.deviations.size(); ++i) {
      if (!frame.crossedBy(line.points[i], line.points[i + 1])) {
        continue;
      }
      out += fmt::format("<line class=\"inset-segment\" x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" "
                         "y2=\"{:.2f}\" stroke=\"{}\" stroke-width=\"2\"/>\n",
                         frame.x(line.points[i].x()), frame.y(line.points[i].y()),
                         frame.x(line.points[i + 1].x()), frame.y(line.points[i + 1].y()),
                         deviationColour(line.deviations[i], plotted[worst->cut].tolerance));
    }
  }
  out += fmt::format("</g>\n<text x=\"{:.2f}\" y=\"{:.2f}\" font-size=\"10\" "
                     "text-anchor=\"end\">worst: cut {}, {:.5f} at ({:.3f}, {:.3f})</text>\n"
                     "<text x=\"{:.2f}\" y=\"{:.2f}\" font-size=\"10\" text-anchor=\"end\">"
                     "window {:.4g} wide</text>\n",
                     x + size, y + size + 12, worst->cut + 1, worst->deviation, frame.centre.x(),
                     frame.centre.y(), x + size, y + size + 24, 2 * frame.halfWidth);
  return out + "</g>\n";
}

} // namespace cncc::backends::plot
