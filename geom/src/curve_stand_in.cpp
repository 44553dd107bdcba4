#include "cncc/geom/curve_stand_in.h"

#include <array>
#include <utility>
#include <vector>

namespace cncc::geom {

namespace {

class StandInCurve : public PiecewisePolynomialCurve {
public:
  StandInCurve(std::vector<PolynomialSpan> spans, std::vector<double> breakpoints)
      : PiecewisePolynomialCurve(std::move(spans)), breakpoints_(std::move(breakpoints)) {}
  std::vector<double> breakpoints() const override { return breakpoints_; }

private:
  std::vector<double> breakpoints_;
};

PolynomialSpan quinticSpan(const Curve& curve, double t0, double t1) {
  CurveDerivatives a = curve.derivatives(t0);
  CurveDerivatives b = curve.derivatives(t1);
  double h = t1 - t0;
  Eigen::Vector3d p = b.point - a.point;
  Eigen::Vector3d v0 = a.first * h, v1 = b.first * h;
  Eigen::Vector3d s0 = a.second * h * h, s1 = b.second * h * h;
  std::array<Eigen::Vector3d, 6> c = {
      a.point,
      v0,
      0.5 * s0,
      10 * p - 6 * v0 - 4 * v1 - 1.5 * s0 + 0.5 * s1,
      -15 * p + 8 * v0 + 7 * v1 + 1.5 * s0 - s1,
      6 * p - 3 * v0 - 3 * v1 - 0.5 * s0 + 0.5 * s1,
  };
  PolynomialSpan span;
  span.t0 = t0;
  span.t1 = t1;
  for (std::size_t k = 0; k < c.size(); ++k) {
    span.coefficients.push_back({c[k].x(), c[k].y(), c[k].z(), k == 0 ? 1.0 : 0.0});
  }
  return span;
}

} // namespace

std::optional<CurveStandIn> standInFor(const Curve& curve, double error) {
  constexpr int kInitialSteps = 32;
  constexpr int kMaximumSteps = 1 << 14;
  std::vector<double> breakpoints = curve.breakpoints();
  std::vector<PolynomialSpan> spans;
  for (std::size_t piece = 0; piece + 1 < breakpoints.size(); ++piece) {
    double a = breakpoints[piece];
    double b = breakpoints[piece + 1];
    for (int steps = kInitialSteps;; steps *= 2) {
      if (steps > kMaximumSteps) {
        return std::nullopt;
      }
      std::vector<PolynomialSpan> pieceSpans;
      bool close = true;
      for (int i = 0; i < steps && close; ++i) {
        double t0 = a + (b - a) * i / steps;
        double t1 = i + 1 == steps ? b : a + (b - a) * (i + 1) / steps;
        pieceSpans.push_back(quinticSpan(curve, t0, t1));
        for (double u : {0.25, 0.5, 0.75}) {
          double t = t0 + (t1 - t0) * u;
          close = close && (pieceSpans.back().pointAt(u) - curve.point(t)).norm() <= error;
        }
      }
      if (close) {
        spans.insert(spans.end(), pieceSpans.begin(), pieceSpans.end());
        break;
      }
    }
  }
  return CurveStandIn{std::make_unique<StandInCurve>(std::move(spans), std::move(breakpoints)),
                      error};
}

} // namespace cncc::geom
