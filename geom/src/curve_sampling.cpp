#include "curve_sampling.h"

#include "vector_math.h"

#include <algorithm>
#include <functional>

namespace cncc::geom::detail {

namespace {

constexpr int kMaxDepth = 40;

class AdaptiveSampler {
public:
  AdaptiveSampler(const Curve& curve, const SamplingRule& rule) : curve_(curve), rule_(rule) {}

  // Visits samples strictly after `a` up to and including `b`, in order.
  void refine(const CurveSample& a, const CurveSample& b, int depth,
              const SampleVisitor& visit) const {
    double middle = 0.5 * (a.t + b.t);
    CurveSample m{middle, curve_.derivatives(middle)};
    if (depth >= kMaxDepth || !(a.t < middle && middle < b.t) || acceptable(a, m, b)) {
      visit(m);
      visit(b);
      return;
    }
    refine(a, m, depth + 1, visit);
    refine(m, b, depth + 1, visit);
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

void visitPieceSamples(const Curve& curve, const SamplingRule& rule,
                       const std::function<void(std::size_t)>& startPiece,
                       const SampleVisitor& visit) {
  AdaptiveSampler sampler(curve, rule);
  std::vector<double> cuts = curve.breakpoints();
  int n = std::max(1, rule.initialIntervalsPerPiece);
  for (std::size_t piece = 0; piece + 1 < cuts.size(); ++piece) {
    double a = cuts[piece], b = cuts[piece + 1];
    CurveSample previous{a, curve.derivatives(a)};
    startPiece(piece);
    visit(previous);
    for (int i = 1; i <= n; ++i) {
      double t = i == n ? b : a + (b - a) * i / n;
      CurveSample next{t, curve.derivatives(t)};
      sampler.refine(previous, next, 0, visit);
      previous = next;
    }
  }
}

std::vector<std::vector<CurveSample>> samplePieces(const Curve& curve, const SamplingRule& rule) {
  std::vector<std::vector<CurveSample>> pieces;
  visitPieceSamples(
      curve, rule, [&](std::size_t) { pieces.emplace_back(); },
      [&](const CurveSample& sample) { pieces.back().push_back(sample); });
  return pieces;
}

void visitSamples(const Curve& curve, const SamplingRule& rule, const SampleVisitor& visit) {
  // A breakpoint once: as the end of the piece before it.
  bool pieceStart = false;
  visitPieceSamples(
      curve, rule, [&](std::size_t piece) { pieceStart = piece > 0; },
      [&](const CurveSample& sample) {
        if (!pieceStart)
          visit(sample);
        pieceStart = false;
      });
}

std::vector<CurveSample> sampleCurve(const Curve& curve, const SamplingRule& rule) {
  std::vector<CurveSample> all;
  visitSamples(curve, rule, [&](const CurveSample& sample) { all.push_back(sample); });
  return all;
}

} // namespace cncc::geom::detail
