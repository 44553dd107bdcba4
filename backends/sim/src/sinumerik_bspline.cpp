// The dense sampling of the curves the virtual Sinumerik cuts.
#include "cncc/backends/sinumerik_controller.h"

#include "sinumerik_sampling.h"

#include <algorithm>
#include <cmath>

namespace cncc::backends::sinumerik {

geom::CurveSamples sampleDensely(const geom::Curve& curve, double tolerance) {
  constexpr int kProbes = 32;
  constexpr double kMargin = 2.0;
  geom::CurveSamples samples;
  std::vector<double> breakpoints = curve.breakpoints();
  samples.parameters.push_back(breakpoints.front());
  for (std::size_t piece = 0; piece + 1 < breakpoints.size(); ++piece) {
    double t0 = breakpoints[piece];
    double t1 = breakpoints[piece + 1];
    double bend = 0;
    for (int i = 0; i <= kProbes; ++i) {
      double t = t0 + (t1 - t0) * i / kProbes;
      bend = std::max(bend, curve.secondDerivative(std::min(t, t1)).norm());
    }
    double step = bend > 0 ? std::sqrt(8.0 * tolerance / (kMargin * bend)) : (t1 - t0);
    double count = std::clamp(std::ceil((t1 - t0) / step), 1.0, 1e7);
    auto steps = static_cast<std::size_t>(count);
    for (std::size_t i = 1; i <= steps; ++i) {
      samples.parameters.push_back(i == steps ? t1 : t0 + (t1 - t0) * double(i) / double(steps));
    }
  }
  for (double t : samples.parameters) {
    samples.points.push_back(curve.point(t));
  }
  return samples;
}

} // namespace cncc::backends::sinumerik
