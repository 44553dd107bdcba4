#include "curve_sampling.h"

#include "vector_math.h"

#include <algorithm>

namespace cncc::geom::detail {

namespace {

constexpr int kMaxDepth = 40;

class AdaptiveSampler {
public:
  AdaptiveSampler(const Curve& curve, const SamplingRule& rule) : curve_(curve), rule_(rule) {}

  // Appends samples strictly after `a` up to and including `b`.
  void refine(const CurveSample& a, const CurveSample& b, int depth,
              std::vector<CurveSample>& out) const {
    double middle = 0.5 * (a.t + b.t);
    CurveSample m{middle, curve_.derivatives(middle)};
    if (depth >= kMaxDepth || !(a.t < middle && middle < b.t) || acceptable(a, m, b)) {
      out.push_back(m);
      out.push_back(b);
      return;
    }
    refine(a, m, depth + 1, out);
    refine(m, b, depth + 1, out);
  }

private:
  bool acceptable(const CurveSample& a, const CurveSample& m, const CurveSample& b) const {
    if (angleBetween(a.d.first, m.d.first) > rule_.maxTurn ||
        angleBetween(m.d.first, b.d.first) > rule_.maxTurn)
      return false;
    double chord = (b.d.point - a.d.point).norm();
    double sagitta = std::max(distanceToSegment(m.d.point, a.d.point, b.d.point),
                              chord * angleBetween(a.d.first, b.d.first) / 8.0);
    return sagitta <= rule_.maxSagitta;
  }

  const Curve& curve_;
  const SamplingRule& rule_;
};

} // namespace

std::vector<std::vector<CurveSample>> samplePieces(const Curve& curve, const SamplingRule& rule) {
  AdaptiveSampler sampler(curve, rule);
  std::vector<double> cuts = curve.breakpoints();
  std::vector<std::vector<CurveSample>> pieces;
  int n = std::max(1, rule.initialIntervalsPerPiece);
  for (std::size_t piece = 0; piece + 1 < cuts.size(); ++piece) {
    double a = cuts[piece], b = cuts[piece + 1];
    std::vector<CurveSample> samples{{a, curve.derivatives(a)}};
    for (int i = 1; i <= n; ++i) {
      double t = i == n ? b : a + (b - a) * i / n;
      CurveSample next{t, curve.derivatives(t)};
      CurveSample previous = samples.back();
      sampler.refine(previous, next, 0, samples);
    }
    pieces.push_back(std::move(samples));
  }
  return pieces;
}

std::vector<CurveSample> sampleCurve(const Curve& curve, const SamplingRule& rule) {
  std::vector<CurveSample> all;
  for (std::vector<CurveSample>& piece : samplePieces(curve, rule)) {
    auto first = piece.begin();
    if (!all.empty())
      ++first; // the breakpoint is already there as the previous piece's end
    all.insert(all.end(), first, piece.end());
  }
  return all;
}

} // namespace cncc::geom::detail
