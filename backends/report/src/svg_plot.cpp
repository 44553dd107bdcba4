#include "cncc/backends/svg_plot.h"

#include "cncc/backends/path_statistics.h"
#include "cncc/geom/deviation.h"
#include "plane_projection.h"
#include "svg_plot_parts.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace cncc::backends {

namespace plot {

std::string escaped(std::string_view text) {
  std::string out;
  for (char c : text) {
    switch (c) {
    case '&':
      out += "&amp;";
      break;
    case '<':
      out += "&lt;";
      break;
    case '>':
      out += "&gt;";
      break;
    case '"':
      out += "&quot;";
      break;
    default:
      out += c;
    }
  }
  return out;
}

std::vector<PlottedCut> plottedCuts(const ExecutedPath& path, std::span<const ir::CutGeometry> cuts,
                                    double accuracy) {
  std::vector<PlottedCut> plotted(cuts.size());
  for (std::size_t cut = 0; cut < cuts.size(); ++cut) {
    plotted[cut].tolerance = cuts[cut].tolerance;
    for (std::vector<Eigen::Vector3d>& points : cutPolylines(path, cut)) {
      PlottedPolyline line;
      if (cuts[cut].curve != nullptr) {
        PlaneProjection plan(*cuts[cut].curve);
        line.deviations = segmentDeviations(points, plan, accuracy);
      }
      line.points = std::move(points);
      plotted[cut].polylines.push_back(std::move(line));
    }
  }
  return plotted;
}

} // namespace plot

namespace {

using plot::escaped;
using plot::PlottedCut;
using plot::PlottedPolyline;

constexpr double kMargin = 60;           // pixels around the drawing area, for the axes
constexpr double kTitleHeight = 30;      // pixels above it
constexpr double kLegendLineHeight = 18; // pixels per legend line
constexpr int kSamplesPerSegment = 16;
constexpr int kRefinementSteps = 40;

using Rgb = std::array<double, 3>;

std::string hexColour(const Rgb& colour) {
  auto channel = [](double value) { return static_cast<int>(std::lround(value)); };
  return fmt::format("#{:02x}{:02x}{:02x}", channel(colour[0]), channel(colour[1]),
                     channel(colour[2]));
}

Rgb mix(const Rgb& from, const Rgb& to, double fraction) {
  return {from[0] + fraction * (to[0] - from[0]), from[1] + fraction * (to[1] - from[1]),
          from[2] + fraction * (to[2] - from[2])};
}

// Part coordinates to pixels, y up.
class Frame {
public:
  Frame(Eigen::Vector2d low, Eigen::Vector2d high, double width) {
    Eigen::Vector2d range = high - low;
    double pad = std::max(0.05 * range.maxCoeff(), 1e-3);
    low_ = low - Eigen::Vector2d(pad, pad);
    high_ = high + Eigen::Vector2d(pad, pad);
    range = high_ - low_;
    scale_ = std::min(width / range.x(), 1.5 * width / range.y());
    plotWidth_ = range.x() * scale_;
    plotHeight_ = range.y() * scale_;
  }

  double x(double partX) const { return kMargin + (partX - low_.x()) * scale_; }
  double y(double partY) const { return kTitleHeight + (high_.y() - partY) * scale_; }
  double scale() const { return scale_; }
  const Eigen::Vector2d& low() const { return low_; }
  const Eigen::Vector2d& high() const { return high_; }
  double left() const { return kMargin; }
  double top() const { return kTitleHeight; }
  double right() const { return kMargin + plotWidth_; }
  double bottom() const { return kTitleHeight + plotHeight_; }

private:
  Eigen::Vector2d low_, high_;
  double scale_ = 1;
  double plotWidth_ = 0, plotHeight_ = 0;
};

// 1, 2 or 5 times a power of ten, giving about five ticks over `range`.
double tickStep(double range) {
  double rough = range / 5.0;
  double power = std::pow(10.0, std::floor(std::log10(rough)));
  for (double factor : {1.0, 2.0, 5.0}) {
    if (factor * power >= rough) {
      return factor * power;
    }
  }
  return 10.0 * power;
}

void includeInBounds(const Eigen::Vector3d& point, Eigen::Vector2d& low, Eigen::Vector2d& high) {
  low = low.cwiseMin(point.head<2>());
  high = high.cwiseMax(point.head<2>());
}

Frame frameFor(const ExecutedPath& path, std::span<const ir::CutGeometry> cuts, double width) {
  Eigen::Vector2d low = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d high = -low;
  includeInBounds(path.start, low, high);
  for (const ExecutedMove& move : path.moves) {
    includeInBounds(move.end, low, high);
  }
  for (const ir::CutGeometry& cut : cuts) {
    for (const geom::Curve* curve : {cut.curve.get(), cut.drawnCurve.get()}) {
      if (curve == nullptr) {
        continue;
      }
      geom::ParameterRange domain = curve->domain();
      for (int i = 0; i <= 64; ++i) {
        includeInBounds(curve->point(domain.t0 + domain.length() * i / 64.0), low, high);
      }
    }
  }
  if (!(low.x() <= high.x())) {
    low = high = Eigen::Vector2d::Zero();
  }
  return Frame(low, high, width);
}

std::string axes(const Frame& frame, const std::string& unit) {
  std::string out = "<g class=\"axes\" font-size=\"11\" fill=\"#444\">\n";
  out += fmt::format("<rect x=\"{:.2f}\" y=\"{:.2f}\" width=\"{:.2f}\" height=\"{:.2f}\" "
                     "fill=\"none\" stroke=\"#999\"/>\n",
                     frame.left(), frame.top(), frame.right() - frame.left(),
                     frame.bottom() - frame.top());
  Eigen::Vector2d range = frame.high() - frame.low();
  double step = tickStep(range.maxCoeff());
  for (double value = std::ceil(frame.low().x() / step) * step; value <= frame.high().x();
       value += step) {
    double x = frame.x(value);
    out += fmt::format("<line x1=\"{0:.2f}\" y1=\"{1:.2f}\" x2=\"{0:.2f}\" y2=\"{2:.2f}\" "
                       "stroke=\"#999\"/>\n<text x=\"{0:.2f}\" y=\"{3:.2f}\" "
                       "text-anchor=\"middle\">{4:g}</text>\n",
                       x, frame.bottom(), frame.bottom() + 5, frame.bottom() + 17,
                       std::abs(value) < step * 1e-9 ? 0.0 : value);
  }
  for (double value = std::ceil(frame.low().y() / step) * step; value <= frame.high().y();
       value += step) {
    double y = frame.y(value);
    out += fmt::format("<line x1=\"{0:.2f}\" y1=\"{1:.2f}\" x2=\"{2:.2f}\" y2=\"{1:.2f}\" "
                       "stroke=\"#999\"/>\n<text x=\"{3:.2f}\" y=\"{4:.2f}\" "
                       "text-anchor=\"end\">{5:g}</text>\n",
                       frame.left() - 5, y, frame.left(), frame.left() - 8, y + 4,
                       std::abs(value) < step * 1e-9 ? 0.0 : value);
  }
  // A scale bar one tick long, under the right end of the x axis.
  double barRight = frame.right();
  double barLeft = barRight - step * frame.scale();
  double barY = frame.bottom() + 40;
  out += fmt::format("<g class=\"scale-bar\"><line x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" "
                     "y2=\"{:.2f}\" stroke=\"#000\" stroke-width=\"2\"/><text x=\"{:.2f}\" "
                     "y=\"{:.2f}\" text-anchor=\"middle\">{:g} {}</text></g>\n",
                     barLeft, barY, barRight, barY, 0.5 * (barLeft + barRight), barY - 4, step,
                     escaped(unit));
  out += fmt::format("<text x=\"{:.2f}\" y=\"{:.2f}\">x, y in {}</text>\n", frame.left(),
                     frame.bottom() + 40, escaped(unit));
  return out + "</g>\n";
}

// Cut `cut`'s curve as a polyline of samples within a fifth of a pixel of it.
std::string curvePolyline(const Frame& frame, const geom::Curve& curve, std::string_view kind,
                          std::size_t cut) {
  geom::CurveProximity samples(curve, 0.2 / frame.scale());
  std::string out = fmt::format("<polyline class=\"{}\" data-cut=\"{}\" points=\"", kind, cut);
  for (const Eigen::Vector3d& point : samples.samplePoints()) {
    out += fmt::format("{:.2f},{:.2f} ", frame.x(point.x()), frame.y(point.y()));
  }
  out.back() = '"';
  return out + "/>\n";
}

std::string curveLines(const Frame& frame, std::span<const ir::CutGeometry> cuts) {
  std::string out = "<g class=\"curves\" fill=\"none\" stroke=\"#555\" stroke-width=\"0.6\">\n";
  for (std::size_t i = 0; i < cuts.size(); ++i) {
    if (cuts[i].curve == nullptr) {
      continue;
    }
    out += curvePolyline(frame, *cuts[i].curve, "curve", i);
  }
  return out + "</g>\n";
}

bool hasDrawnContours(std::span<const ir::CutGeometry> cuts) {
  return std::any_of(cuts.begin(), cuts.end(),
                     [](const ir::CutGeometry& cut) { return cut.drawnCurve != nullptr; });
}

// The curves as drawn of the cuts beside them (side=), whose offsets the
// tool centre runs: thin, in their own colour.
std::string drawnContourLines(const Frame& frame, std::span<const ir::CutGeometry> cuts) {
  if (!hasDrawnContours(cuts)) {
    return "";
  }
  std::string out =
      fmt::format("<g class=\"drawn-contours\" fill=\"none\" stroke=\"{}\" stroke-width=\"0.8\">\n",
                  kDrawnContourColour);
  for (std::size_t i = 0; i < cuts.size(); ++i) {
    if (cuts[i].drawnCurve == nullptr) {
      continue;
    }
    out += curvePolyline(frame, PlaneProjection(*cuts[i].drawnCurve), "drawn-contour", i);
  }
  return out + "</g>\n";
}

std::string rapidLines(const Frame& frame, const ExecutedPath& path) {
  std::string out = "<g class=\"rapids\" stroke=\"#aaa\" stroke-width=\"0.8\" "
                    "stroke-dasharray=\"4 3\">\n";
  for (std::size_t i = 0; i < path.moves.size(); ++i) {
    const Eigen::Vector3d& from = path.startOf(i);
    const Eigen::Vector3d& to = path.moves[i].end;
    // A vertical rapid (a retract, a descent) would be a dot.
    if (!path.moves[i].rapid || (to - from).head<2>().norm() * frame.scale() < 0.05) {
      continue;
    }
    out += fmt::format("<line class=\"rapid\" x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" "
                       "y2=\"{:.2f}\"/>\n",
                       frame.x(from.x()), frame.y(from.y()), frame.x(to.x()), frame.y(to.y()));
  }
  return out + "</g>\n";
}

// The coloured segments and the dots of every cut.
std::string cutPaths(const Frame& frame, const std::vector<PlottedCut>& plotted) {
  std::string segments = "<g class=\"path\" stroke-width=\"1.6\" stroke-linecap=\"round\">\n";
  std::string points = "<g class=\"points\" fill=\"#000\">\n";
  for (std::size_t cut = 0; cut < plotted.size(); ++cut) {
    for (const PlottedPolyline& line : plotted[cut].polylines) {
      const std::vector<Eigen::Vector3d>& polyline = line.points;
      for (std::size_t i = 0; i < line.deviations.size(); ++i) {
        segments += fmt::format(
            "<line class=\"segment\" data-cut=\"{}\" data-deviation=\"{:.6f}\" x1=\"{:.2f}\" "
            "y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\" stroke=\"{}\"/>\n",
            cut, line.deviations[i], frame.x(polyline[i].x()), frame.y(polyline[i].y()),
            frame.x(polyline[i + 1].x()), frame.y(polyline[i + 1].y()),
            deviationColour(line.deviations[i], plotted[cut].tolerance));
      }
      for (const Eigen::Vector3d& point : polyline) {
        points += fmt::format("<circle class=\"point\" cx=\"{:.2f}\" cy=\"{:.2f}\" r=\"1.3\"/>\n",
                              frame.x(point.x()), frame.y(point.y()));
      }
    }
  }
  return segments + "</g>\n" + points + "</g>\n";
}

std::string swatch(double x, double y, const std::string& colour, std::string_view label) {
  return fmt::format(
      "<line x1=\"{:.2f}\" y1=\"{:.2f}\" x2=\"{:.2f}\" y2=\"{:.2f}\" "
      "stroke=\"{}\" stroke-width=\"3\"/><text x=\"{:.2f}\" y=\"{:.2f}\">{}</text>\n",
      x, y - 4, x + 20, y - 4, colour, x + 26, y, escaped(label));
}

std::string legend(double top, std::span<const ir::CutGeometry> cuts,
                   const std::vector<CutDeviation>& deviations, const PlotOptions& options) {
  std::string out = "<g class=\"legend\" font-size=\"12\" fill=\"#000\">\n";
  double y = top;
  for (const CutDeviation& cut : deviations) {
    std::string name = cut.cut < options.cutNames.size() ? options.cutNames[cut.cut]
                                                         : fmt::format("cut {}", cut.cut + 1);
    std::string deviation =
        std::isnan(cut.maxDeviation)
            ? "no feed moves"
            : fmt::format("max deviation {:.5f} {}", cut.maxDeviation, options.unit);
    std::string tolerance = std::isnan(cut.tolerance)
                                ? "no tolerance (samples= or spacing=)"
                                : fmt::format("tolerance {:g} {}{}", cut.tolerance, options.unit,
                                              cut.withinTolerance() ? "" : ": EXCEEDED");
    std::string colour = deviationColour(cut.maxDeviation, cuts[cut.cut].tolerance);
    out += fmt::format("<g class=\"legend-cut\" data-cut=\"{}\">", cut.cut) +
           swatch(kMargin, y, colour, fmt::format("{}: {}, {}", name, deviation, tolerance)) +
           "</g>\n";
    y += kLegendLineHeight;
  }
  double x = kMargin;
  out += swatch(x, y, kOnTheCurveColour, "on the curve");
  out += swatch(x + 130, y, deviationColour(0.5, 1), "half the tolerance");
  out += swatch(x + 290, y, deviationColour(1, 1), "the tolerance");
  out += swatch(x + 410, y, kBeyondToleranceColour, "beyond it");
  out += swatch(x + 510, y, "#555", "true curve");
  if (hasDrawnContours(cuts)) {
    out += swatch(x, y + kLegendLineHeight, kDrawnContourColour,
                  "drawn contour of a cut beside it (side=): its true curve is the tool "
                  "centre's offset path");
  }
  return out + "</g>\n";
}

double distanceAt(const geom::CurveProximity& proximity, const Eigen::Vector3d& a,
                  const Eigen::Vector3d& b, double u) {
  return proximity.closestPoint(a + u * (b - a)).distance;
}

} // namespace

std::string deviationColour(double deviation, double tolerance) {
  if (std::isnan(tolerance) || std::isnan(deviation)) {
    return kNoToleranceColour;
  }
  if (deviation > tolerance) {
    return kBeyondToleranceColour;
  }
  double ratio = tolerance > 0 ? deviation / tolerance : 0.0;
  const Rgb green = {0x1a, 0x96, 0x41}, yellow = {0xf2, 0xc8, 0x0f}, red = {0xd7, 0x19, 0x1c};
  // Continuous: green on the curve, yellow at half the tolerance, red at it.
  return ratio <= 0.5 ? hexColour(mix(green, yellow, ratio / 0.5))
                      : hexColour(mix(yellow, red, (ratio - 0.5) / 0.5));
}

std::vector<double> segmentDeviations(const std::vector<Eigen::Vector3d>& polyline,
                                      const geom::Curve& curve, double accuracy) {
  std::vector<double> deviations;
  if (polyline.size() < 2) {
    return deviations;
  }
  geom::CurveProximity proximity(curve, accuracy);
  for (std::size_t i = 0; i + 1 < polyline.size(); ++i) {
    const Eigen::Vector3d& a = polyline[i];
    const Eigen::Vector3d& b = polyline[i + 1];
    int best = 0;
    double largest = -1;
    for (int k = 0; k <= kSamplesPerSegment; ++k) {
      double d = distanceAt(proximity, a, b, double(k) / kSamplesPerSegment);
      if (d > largest) {
        largest = d;
        best = k;
      }
    }
    // Golden-section search for the peak between the neighbouring samples.
    double low = std::max(0, best - 1) / double(kSamplesPerSegment);
    double high = std::min(kSamplesPerSegment, best + 1) / double(kSamplesPerSegment);
    const double ratio = (std::sqrt(5.0) - 1.0) / 2.0;
    for (int step = 0; step < kRefinementSteps && high - low > 1e-12; ++step) {
      double left = high - ratio * (high - low);
      double right = low + ratio * (high - low);
      double atLeft = distanceAt(proximity, a, b, left);
      double atRight = distanceAt(proximity, a, b, right);
      largest = std::max({largest, atLeft, atRight});
      (atLeft < atRight ? low : high) = atLeft < atRight ? left : right;
    }
    deviations.push_back(largest);
  }
  return deviations;
}

std::string plotSvg(const ExecutedPath& path, std::span<const ir::CutGeometry> cuts,
                    const PlotOptions& options) {
  Frame frame = frameFor(path, cuts, options.width);
  ExecutedProgram program{"", 0, path};
  std::vector<CutDeviation> deviations =
      measureProgram(program, cuts, {.rapidRate = 1, .unit = options.unit, .cutNames = {}}).cuts;
  std::vector<PlottedCut> plotted = plot::plottedCuts(path, cuts, 1e-3 / frame.scale());
  double panelsTop = frame.bottom() + 66;
  double legendTop = panelsTop + plot::panelsHeight(plotted) + 12;
  double width = frame.right() + kMargin;
  double legendLines = double(cuts.size() + 1) + (hasDrawnContours(cuts) ? 1 : 0);
  double height = legendTop + kLegendLineHeight * legendLines + 10;
  double insetSize = std::min(160.0, (frame.right() - frame.left()) / 3);
  std::string out =
      fmt::format("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{0:.0f}\" height=\"{1:.0f}\" "
                  "viewBox=\"0 0 {0:.0f} {1:.0f}\" font-family=\"sans-serif\">\n",
                  std::ceil(width), std::ceil(height));
  out += fmt::format("<title>{}</title>\n", escaped(options.title));
  out += "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>\n";
  out += fmt::format("<text class=\"title\" x=\"{:.2f}\" y=\"20\" font-size=\"14\">{}</text>\n",
                     kMargin, escaped(options.title));
  out += axes(frame, options.unit);
  out += curveLines(frame, cuts);
  out += drawnContourLines(frame, cuts);
  out += rapidLines(frame, path);
  out += cutPaths(frame, plotted);
  out += plot::worstPointInset(plotted, cuts, frame.right() - insetSize - 6, frame.top() + 6,
                               insetSize);
  out += plot::deviationPanels(plotted, options.cutNames, frame.left(), panelsTop,
                               frame.right() - frame.left(), options.unit);
  out += legend(legendTop, cuts, deviations, options);
  return out + "</svg>\n";
}

} // namespace cncc::backends
