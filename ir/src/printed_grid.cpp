#include "cncc/ir/printed_grid.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace cncc::ir {

double onPrintedGrid(double value, double increment) {
  if (!(increment > 0) || !std::isfinite(value)) {
    return value;
  }
  auto decimals = static_cast<int>(std::lround(-std::log10(increment)));
  if (decimals < 0 || decimals > 12 ||
      std::fabs(std::pow(10.0, -decimals) - increment) > 1e-9 * increment) {
    return std::round(value / increment) * increment; // not a power of ten
  }
  // The decimal text, as printed, read back: halves round as the printers
  // round them (the binary value decides), not as value / increment would.
  return std::stod(fmt::format("{:.{}f}", value, decimals));
}

double controllerReading(double value, int digits) {
  double magnitude = std::abs(value);
  if (!std::isfinite(value) || digits <= 0) {
    return value;
  }
  int wholeDigits = magnitude < 1 ? 0 : static_cast<int>(std::floor(std::log10(magnitude))) + 1;
  double scale = std::pow(10.0, std::max(0, digits - wholeDigits));
  return std::nearbyint(value * scale) / scale;
}

Eigen::Vector3d onPrintedGrid(const Eigen::Vector3d& point, double increment) {
  return {onPrintedGrid(point.x(), increment), onPrintedGrid(point.y(), increment),
          onPrintedGrid(point.z(), increment)};
}

std::pair<Eigen::Vector3d, Eigen::Vector3d> curveEndsOnGrid(const geom::Curve& curve,
                                                            double increment) {
  geom::ParameterRange domain = curve.domain();
  return {onPrintedGrid(curve.point(domain.t0), increment),
          onPrintedGrid(curve.point(domain.t1), increment)};
}

} // namespace cncc::ir
