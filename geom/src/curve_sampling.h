#pragma once

// Curvature-adaptive sampling of a curve (internal): the dense samples that curvature
// search and deviation measurement start from.

#include "cncc/geom/curve.h"

#include <functional>
#include <limits>
#include <vector>

namespace cncc::geom::detail {

struct CurveSample {
  double t;
  CurveDerivatives d;
};

struct SamplingRule {
  /// Uniform intervals each smooth piece starts with.
  int initialIntervalsPerPiece = 16;
  /// Largest tangent turn (rad) between neighbouring samples.
  double maxTurn = 0.1;
  /// Largest estimated distance between the curve and the chord of neighbouring samples.
  double maxSagitta = std::numeric_limits<double>::infinity();
};

using SampleVisitor = std::function<void(const CurveSample&)>;

/// Samples of each smooth piece of the curve, piece by piece (a breakpoint ends one
/// piece and starts the next). An interval is halved until the tangent turns at most
/// maxTurn over each half and the arc's sagitta (from the mid point's distance to the
/// chord and from chord * turn / 8) is at most maxSagitta.
std::vector<std::vector<CurveSample>> samplePieces(const Curve& curve, const SamplingRule& rule);

/// The same samples as one increasing sequence (breakpoints once).
std::vector<CurveSample> sampleCurve(const Curve& curve, const SamplingRule& rule);
/// The same samples, each handed to `visit` in turn instead of kept.
void visitSamples(const Curve& curve, const SamplingRule& rule, const SampleVisitor& visit);

} // namespace cncc::geom::detail
