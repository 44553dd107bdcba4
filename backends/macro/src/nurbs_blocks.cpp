#include "cncc/backends/nurbs_blocks.h"

#include "cncc/backends/gcode_writer.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace cncc::backends {

namespace {

constexpr double smallestMitsubishiValue = 0.0001;
constexpr double largestMitsubishiValue = 99.9999;

// At most 8 significant digits (the conservative Fanuc constant), always
// with a decimal point.
std::string formatParameter(double value) {
  std::string text = fmt::format("{:.8g}", value);
  if (text.find_first_of(".e") == std::string::npos) {
    text += '.';
  }
  return text;
}

double roundToDecimals(double value, int decimals) {
  double scale = std::pow(10.0, decimals);
  return std::round(value * scale) / scale;
}

void checkKnotRules(const std::vector<double>& knots, int order, std::size_t points,
                    std::vector<std::string>& errors) {
  if (order < 2 || order > 4) {
    errors.push_back(fmt::format("G06.2 rule: the order P must be 2 to 4; this curve has order {} "
                                 "(degree {})",
                                 order, order - 1));
    return;
  }
  if (knots.size() != points + static_cast<std::size_t>(order)) {
    errors.push_back(fmt::format("G06.2 rule: the knot count must be the control points plus the "
                                 "order ({} + {}); this curve has {} knots",
                                 points, order, knots.size()));
    return;
  }
  auto count = static_cast<std::size_t>(order);
  bool clamped = true;
  for (std::size_t i = 1; i < count; ++i) {
    clamped = clamped && knots[i] == knots[0] && knots[knots.size() - 1 - i] == knots.back();
  }
  if (!clamped) {
    errors.push_back(fmt::format("G06.2 rule: the first and the last {} knots must be equal "
                                 "(clamped ends)",
                                 order));
  }
  std::size_t run = 1;
  for (std::size_t i = 1; i < knots.size(); ++i) {
    run = knots[i] == knots[i - 1] ? run + 1 : 1;
    bool interior = knots[i] != knots.front() && knots[i] != knots.back();
    if (interior && run > count) {
      errors.push_back(fmt::format("G06.2 rule: an interior knot may repeat at most {} times; "
                                   "{} repeats {} times",
                                   order, knots[i], run));
      return;
    }
  }
}

// The knots mapped affinely onto 1..99 (M80: 0.0001..99.9999, 4 decimals);
// mapping the parameter does not change the curve.
std::vector<double> mitsubishiKnots(const std::vector<double>& knots,
                                    std::vector<std::string>& errors) {
  double first = knots.front();
  double length = knots.back() - first;
  std::vector<double> mapped;
  for (double knot : knots) {
    mapped.push_back(roundToDecimals(1.0 + 98.0 * (knot - first) / length, 4));
  }
  for (std::size_t i = 1; i < knots.size(); ++i) {
    if ((knots[i] != knots[i - 1]) != (mapped[i] != mapped[i - 1])) {
      errors.push_back("G06.2 rule (M80): two knots fall on the same value at 4 decimals in "
                       "0.0001..99.9999");
      break;
    }
  }
  return mapped;
}

// The weights scaled together into 0.0001..99.9999 with 4 decimals (M80);
// scaling every weight alike does not change the curve.
std::vector<double> mitsubishiWeights(const std::vector<double>& weights, bool scalable,
                                      std::vector<std::string>& errors) {
  double largest = *std::max_element(weights.begin(), weights.end());
  double scale =
      scalable && largest > largestMitsubishiValue ? largestMitsubishiValue / largest : 1.0;
  std::vector<double> scaled;
  for (double weight : weights) {
    scaled.push_back(roundToDecimals(weight * scale, 4));
    if (scaled.back() < smallestMitsubishiValue || scaled.back() > largestMitsubishiValue) {
      errors.push_back(fmt::format("G06.2 rule (M80): the weight {} is outside 0.0001..99.9999 "
                                   "at 4 decimals",
                                   weight));
      break;
    }
  }
  return scaled;
}

} // namespace

NurbsBlocks writeNurbsBlocks(const geom::NurbsCurve& curve, const NurbsBlockOptions& options) {
  NurbsBlocks result;
  const std::vector<Eigen::Vector3d>& points = curve.controlPoints();
  std::vector<double> weights =
      curve.weights().empty() ? std::vector<double>(points.size(), 1.0) : curve.weights();
  int order = curve.degree() + 1;
  checkKnotRules(curve.knots().values(), order, points.size(), result.errors);
  if (options.cutterCompensation) {
    result.errors.push_back("G06.2 rule: cutter compensation G41/G42 must be off (G40) in NURBS "
                            "interpolation");
  }
  int decimals = options.coordinateDecimals;
  auto number = [&](double value) { return formatGcodeNumber(value, decimals); };
  Eigen::Vector3d first = points.front() + Eigen::Vector3d(0, 0, options.z);
  bool computedHeight = !options.zCoordinate.empty();
  for (int axis = 0; axis < (computedHeight ? 2 : 3); ++axis) {
    if (number(first[axis]) != number(options.currentPosition[axis])) {
      result.errors.push_back(fmt::format(
          "G06.2 rule: the first control point ({}, {}, {}) must be the current position "
          "({}, {}, {})",
          number(first.x()), number(first.y()), number(first.z()),
          number(options.currentPosition.x()), number(options.currentPosition.y()),
          number(options.currentPosition.z())));
      break;
    }
  }
  bool mitsubishi = options.dialect == NurbsDialect::Mitsubishi;
  bool symbolic = std::any_of(options.weightVariables.begin(), options.weightVariables.end(),
                              [](const std::string& name) { return !name.empty(); });
  if (result.errors.empty()) {
    result.knots = mitsubishi ? mitsubishiKnots(curve.knots().values(), result.errors)
                              : curve.knots().values();
    result.weights = mitsubishi ? mitsubishiWeights(weights, !symbolic, result.errors) : weights;
  }
  if (!result.errors.empty()) {
    return result;
  }
  auto knotWord = [&](std::size_t i) {
    return mitsubishi ? formatGcodeNumber(result.knots[i], 4) : formatParameter(result.knots[i]);
  };
  auto weightWord = [&](std::size_t i) {
    if (i < options.weightVariables.size() && !options.weightVariables[i].empty()) {
      return options.weightVariables[i];
    }
    return mitsubishi ? formatGcodeNumber(result.weights[i], 4)
                      : formatParameter(result.weights[i]);
  };
  if (mitsubishi) {
    result.lines.push_back("G05 P10000");
  }
  auto zWord = [&](const Eigen::Vector3d& point) {
    if (!computedHeight) {
      return number(point.z() + options.z);
    }
    if (point.z() == 0) {
      return options.zCoordinate;
    }
    return fmt::format("[{}{}{}]", options.zOperand, point.z() < 0 ? "-" : "+",
                       number(std::fabs(point.z())));
  };
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d& point = points[i];
    std::string block = fmt::format("K{} X{} Y{} Z{} R{}", knotWord(i), number(point.x()),
                                    number(point.y()), zWord(point), weightWord(i));
    if (i == 0) {
      block = fmt::format("G06.2 P{} {} F{}", order, block,
                          options.feedText.empty() ? number(options.feed) : options.feedText);
    }
    result.lines.push_back(std::move(block));
  }
  for (std::size_t i = points.size(); i < result.knots.size(); ++i) {
    result.lines.push_back("K" + knotWord(i));
  }
  return result;
}

} // namespace cncc::backends
