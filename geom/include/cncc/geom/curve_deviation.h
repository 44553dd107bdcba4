#pragma once

#include "cncc/geom/curve.h"
#include "cncc/geom/deviation.h"

namespace cncc::geom {

/// Where the largest distance from one curve to another occurs.
struct CurveDistanceWitness {
  double distance = 0.0;
  /// Parameter on the curve measured from.
  double parameter = 0.0;
  /// Parameter of the closest point on the other curve.
  double targetParameter = 0.0;
};

/// Largest distance from the points of `from` with parameter in [a, b] to the curve
/// behind `target`. `from` is sampled at `samples` equal parameter steps and every
/// sampled local maximum of at least half the largest sample is refined by Brent's
/// method, so the value is one actually attained (a lower bound that is exact unless a
/// peak is narrower than the sampling). Approximations built by the fitting routines
/// have a handful of error lobes per span, so 32 samples per span find them all.
CurveDistanceWitness largestDistanceToCurve(const Curve& from, double a, double b,
                                            const CurveProximity& target, int samples = 32);

/// Both directed deviations between an approximating curve and the curve it replaces.
struct CurveDeviationReport {
  /// max over points of the approximation of the distance to the curve.
  CurveDistanceWitness approximationToCurve;
  /// max over points of the curve of the distance to the approximation.
  CurveDistanceWitness curveToApproximation;

  /// The Hausdorff distance, the larger of the two.
  double maxDeviation() const;
};

/// Both directed deviations between two curves (their Hausdorff distance). Each curve
/// is sampled curvature-adaptively (as measureDeviation samples its curve, at least 32
/// samples per smooth piece) and every sampled local maximum is refined, with closest
/// points found by CurveProximity at options.accuracy; the result is accurate to about
/// options.accuracy.
CurveDeviationReport measureCurveDeviation(const Curve& approximation, const Curve& curve,
                                           const DeviationOptions& options = {});
/// The same with `curveProximity`, of `curve` at options.accuracy, built by the caller
/// (a fit that measures many approximations of one curve builds it once). The curve's
/// own samples and points are asked first, before the approximation is sampled: a
/// BudgetedCurve is asked the same points in all, and one past its budget throws
/// before the work on the approximation is done.
CurveDeviationReport measureCurveDeviation(const Curve& approximation, const Curve& curve,
                                           const CurveProximity& curveProximity,
                                           const DeviationOptions& options);

} // namespace cncc::geom
