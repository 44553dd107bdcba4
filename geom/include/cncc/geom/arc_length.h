#pragma once

#include "cncc/geom/curve.h"

#include <cstddef>
#include <vector>

namespace cncc::geom {

/// Default absolute tolerance (mm) on arc lengths.
inline constexpr double kArcLengthTolerance = 1e-10;

/// Length of the curve between parameters ta <= tb by adaptive Gauss-Legendre
/// quadrature of |C'(t)| (10 nodes; an interval is split until it and its two halves
/// agree within its share of `tolerance`), integrating each smooth piece between
/// breakpoints separately.
double arcLength(const Curve& curve, double ta, double tb, double tolerance = kArcLengthTolerance);
double arcLength(const Curve& curve, double tolerance = kArcLengthTolerance);

/// Cumulative arc length s(t) over the whole curve, and its inverse t(s).
/// Built once by the adaptive quadrature; lookups reuse its accepted intervals.
/// Keeps a reference to the curve, which must outlive the table.
class ArcLengthTable {
public:
  explicit ArcLengthTable(const Curve& curve, double tolerance = kArcLengthTolerance);
  explicit ArcLengthTable(const Curve&& curve, double tolerance = kArcLengthTolerance) = delete;

  double totalLength() const { return cumulative_.back(); }
  /// s(t), arc length from t0 to t.
  double lengthAt(double t) const;
  /// t with s(t) = s (s clamped to [0, totalLength]): Newton's method on
  /// s(t) - s with s'(t) = |C'(t)|, safeguarded by bisection in the interval that
  /// holds s. Accurate to about the quadrature tolerance in length.
  double parameterAt(double s) const;

private:
  double lengthWithin(std::size_t interval, double t) const;

  const Curve& curve_;
  std::vector<double> starts_;     // parameter where each accepted interval starts, then t1
  std::vector<double> cumulative_; // arc length at each entry of starts_
};

/// `count` >= 2 parameters equally spaced in arc length from t0 to t1 inclusive.
std::vector<double> equalArcLengthParameters(const Curve& curve, std::size_t count);

} // namespace cncc::geom
