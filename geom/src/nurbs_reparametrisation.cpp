#include "cncc/geom/nurbs_reparametrisation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace cncc::geom {

namespace {

// y of x on [0, 1].
double inverseMap(double lambda, double x) {
  double denominator = lambda * (1 - x) + x;
  return denominator > 0 ? x / denominator : x;
}

// The weights of the reparametrised curve, first weight 1, and its knots.
struct Mapped {
  std::vector<double> knots;
  std::vector<double> weights;
};

Mapped mapped(const NurbsCurve& curve, double lambda) {
  ParameterRange domain = curve.domain();
  double length = domain.length();
  Mapped out;
  std::vector<double> unit; // the new knots on [0, 1]
  for (double knot : curve.knots().values()) {
    double x = std::clamp((knot - domain.t0) / length, 0.0, 1.0);
    double y = knot <= domain.t0 ? 0.0 : (knot >= domain.t1 ? 1.0 : inverseMap(lambda, x));
    unit.push_back(y);
    out.knots.push_back(knot <= domain.t0 || knot >= domain.t1 ? knot : domain.t0 + length * y);
  }
  int p = curve.degree();
  const std::vector<double>& weights = curve.weights();
  for (std::size_t i = 0; i < weights.size(); ++i) {
    double factor = 1;
    for (int j = 1; j <= p; ++j) {
      double y = unit[i + std::size_t(j)];
      factor *= (1 - y) + lambda * y;
    }
    out.weights.push_back(weights[i] * factor);
  }
  double first = out.weights.front();
  for (double& weight : out.weights) {
    weight /= first;
  }
  return out;
}

// Positive when every weight fits the range, then larger the larger the
// smallest weight is (a weight printed in fixed steps keeps more of its
// digits); a weight beyond the highest costs a thousand times more.
double margin(const std::vector<double>& weights, WeightRange range) {
  constexpr double kBeyondHighest = 1000;
  double worst = std::numeric_limits<double>::infinity();
  for (double weight : weights) {
    worst = std::min({worst, kBeyondHighest * std::log(range.highest / weight),
                      std::log(weight / range.lowest)});
  }
  return worst;
}

} // namespace

NurbsCurve reparametrised(const NurbsCurve& curve, double lambda) {
  Mapped out = mapped(curve, lambda);
  return NurbsCurve(KnotVector(std::move(out.knots), curve.degree()), curve.controlPoints(),
                    std::move(out.weights));
}

double reparametrisedParameter(const NurbsCurve& curve, double lambda, double t) {
  ParameterRange domain = curve.domain();
  double x = std::clamp((t - domain.t0) / domain.length(), 0.0, 1.0);
  return domain.t0 + domain.length() * inverseMap(lambda, x);
}

std::optional<FittingWeights> weightsWithin(const NurbsCurve& curve, WeightRange range) {
  auto score = [&](double logLambda) {
    return margin(mapped(curve, std::exp(logLambda)).weights, range);
  };
  if (score(0) >= 0) {
    Mapped scaled = mapped(curve, 1);
    return FittingWeights{NurbsCurve(curve.knots(), curve.controlPoints(), scaled.weights), 1};
  }
  // A scan of log lambda, then golden sections about the best.
  constexpr double kReach = 12; // lambda from e^-12 to e^12
  constexpr int kSteps = 240;
  double step = 2 * kReach / kSteps;
  double best = 0;
  double bestScore = score(0);
  for (int k = 0; k <= kSteps; ++k) {
    double at = -kReach + step * k;
    if (double s = score(at); s > bestScore) {
      best = at;
      bestScore = s;
    }
  }
  double low = best - step, high = best + step;
  const double golden = (std::sqrt(5.0) - 1) / 2;
  for (int k = 0; k < 60; ++k) {
    double a = high - golden * (high - low), b = low + golden * (high - low);
    if (score(a) > score(b)) {
      high = b;
    } else {
      low = a;
    }
  }
  double lambdaLog = score((low + high) / 2) > bestScore ? (low + high) / 2 : best;
  if (!(score(lambdaLog) >= 0)) {
    return std::nullopt;
  }
  return FittingWeights{reparametrised(curve, std::exp(lambdaLog)), std::exp(lambdaLog)};
}

} // namespace cncc::geom
