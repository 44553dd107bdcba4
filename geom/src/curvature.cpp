#include "cncc/geom/curvature.h"

#include "curve_sampling.h"
#include "scalar_optimisation.h"

#include <limits>

namespace cncc::geom {

namespace {

constexpr int kInitialSamplesPerPiece = 64;
constexpr double kMaxTurnBetweenSamples = 0.05;

bool isLocalMaximum(const std::vector<double>& values, std::size_t i) {
  bool aboveLeft = i == 0 || values[i] >= values[i - 1];
  bool aboveRight = i + 1 == values.size() || values[i] >= values[i + 1];
  return aboveLeft && aboveRight;
}

} // namespace

CurvatureExtreme minimumRadiusOfCurvature(const Curve& curve) {
  detail::SamplingRule rule;
  rule.initialIntervalsPerPiece = kInitialSamplesPerPiece;
  rule.maxTurn = kMaxTurnBetweenSamples;
  CurvatureExtreme best{curve.domain().t0, -1.0, 0.0};
  auto consider = [&](double t, double k) {
    if (k > best.curvature) {
      best.curvature = k;
      best.parameter = t;
    }
  };
  for (const std::vector<detail::CurveSample>& piece : detail::samplePieces(curve, rule)) {
    std::vector<double> curvature;
    for (const detail::CurveSample& s : piece)
      curvature.push_back(curvatureOf(s.d));
    for (std::size_t i = 0; i < piece.size(); ++i) {
      consider(piece[i].t, curvature[i]);
      if (!isLocalMaximum(curvature, i))
        continue;
      // The peak lies between the neighbouring samples; Brent finds it there.
      double lo = piece[i == 0 ? 0 : i - 1].t;
      double hi = piece[i + 1 == piece.size() ? i : i + 1].t;
      if (!(lo < hi))
        continue;
      auto peak = detail::maximiseBrent([&](double t) { return curve.curvature(t); }, lo, hi);
      consider(peak.t, peak.value);
    }
  }
  best.radius =
      best.curvature > 0.0 ? 1.0 / best.curvature : std::numeric_limits<double>::infinity();
  return best;
}

} // namespace cncc::geom
