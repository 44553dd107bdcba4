#pragma once

#include "cncc/geom/curve.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/geom/segment_tree.h"

#include <Eigen/Core>

#include <cstddef>
#include <limits>
#include <memory>
#include <vector>

namespace cncc::geom {

/// Where a largest distance between a polyline and a curve occurs.
struct DeviationWitness {
  double distance = 0.0;
  Eigen::Vector3d polylinePoint = Eigen::Vector3d::Zero();
  Eigen::Vector3d curvePoint = Eigen::Vector3d::Zero();
  double curveParameter = 0.0;
  /// Polyline segment holding polylinePoint (segment i joins vertices i and i + 1).
  std::size_t segment = 0;
};

/// Both directed distances between a polyline P and a curve C.
struct DeviationReport {
  /// max over points p of P of the distance from p to C: how far the executed path
  /// strays from the curve.
  DeviationWitness polylineToCurve;
  /// max over points c of C of the distance from c to P: how far the curve is from
  /// being covered by the path (catches a path that stops short or cuts corners).
  DeviationWitness curveToPolyline;

  /// The Hausdorff distance, the larger of the two.
  double maxDeviation() const;
  const DeviationWitness& worst() const;
};

struct DeviationOptions {
  /// Absolute accuracy (mm). The curve is sampled so that the polyline through its
  /// samples stays within `accuracy` of it, polyline segments are sampled at the
  /// spacing at which the tightest bend of the curve sags by `accuracy`, and the
  /// sampled local maxima are refined (Brent's method on the distance), largest
  /// first, until the next one's sample is within `accuracy` of the largest refined.
  /// A reported distance is therefore one actually attained, exact to rounding
  /// (~1e-13 mm); it falls short of the largest by a few times `accuracy` at most
  /// (a skipped peak, or one narrower than the sampling).
  /// Work grows like length / sqrt(accuracy * smallest radius of curvature).
  double accuracy = 1e-7;
  /// The most polyline and curve-sample segments the closest-point queries may
  /// measure in all (the work of a measurement, which grows with the length of
  /// the polyline times, for points far from the curve, the curve's samples);
  /// past it measureDeviation throws MeasurementTooLarge.
  double maximumWork = std::numeric_limits<double>::infinity();
};

/// Thrown by measureDeviation past DeviationOptions::maximumWork.
class MeasurementTooLarge : public GeometryError {
public:
  explicit MeasurementTooLarge(double limit);
  double limit;
};

/// Closest points on a curve, from a dense polyline through curve samples (chosen so
/// it stays within `accuracy` of the curve) and a bounding-box tree over it, then
/// refinement of the curve parameter by Newton's method (Brent's method when Newton
/// does not converge). Keeps a reference to the curve, which must outlive it.
class CurveProximity {
public:
  CurveProximity(const Curve& curve, double accuracy);
  CurveProximity(const Curve&& curve, double accuracy) = delete; // would dangle
  ~CurveProximity();
  CurveProximity(const CurveProximity&) = delete;
  CurveProximity& operator=(const CurveProximity&) = delete;

  struct ClosestPoint {
    double distance;
    double parameter;
    Eigen::Vector3d point;
  };
  ClosestPoint closestPoint(const Eigen::Vector3d& p) const;
  /// closestPoint(p), the same to the bit, its search of the samples bounded
  /// from the start by sample segment `hint` (SegmentTree::nearest(p, hint)),
  /// and the segment found left in `hint`: for points along a curve.
  ClosestPoint closestPoint(const Eigen::Vector3d& p, std::size_t& hint) const;
  /// The distance from p to the polyline through the samples, within `accuracy` of
  /// its distance to the curve, without evaluating the curve.
  double sampledDistance(const Eigen::Vector3d& p) const;
  /// The same, searched from sample segment `hint` first (SegmentTree::nearestDistance),
  /// for queries along a path.
  double sampledDistance(const Eigen::Vector3d& p, std::size_t& hint) const;

  const std::vector<double>& sampleParameters() const { return parameters_; }
  /// Segments of the curve's samples the queries have measured so far.
  std::size_t segmentsMeasured() const;
  const std::vector<Eigen::Vector3d>& samplePoints() const;
  /// Smallest radius of curvature seen at the samples (for choosing step sizes).
  double smallestSampledRadius() const { return smallestRadius_; }
  /// The smallest radius of curvature at the samples of sample segments
  /// `first` .. `last` (either order) and of the segment beside each: the
  /// tightest bend near points whose nearest samples are there.
  double smallestRadiusBetween(std::size_t first, std::size_t last) const;

private:
  struct Index;
  // The curve's point nearest p, from the samples' segment nearest it.
  ClosestPoint closestPointNear(const Eigen::Vector3d& p, const SegmentTree::Nearest& near) const;

  const Curve& curve_;
  std::vector<double> parameters_;
  std::vector<double> radii_;      // of curvature, at each sample
  std::vector<double> blockRadii_; // the smallest of each block of radiusBlock samples
  double smallestRadius_;
  std::unique_ptr<Index> index_;
};

/// Both directed deviations between `polyline` (at least one vertex) and `curve`.
DeviationReport measureDeviation(const std::vector<Eigen::Vector3d>& polyline, const Curve& curve,
                                 const DeviationOptions& options = {});

} // namespace cncc::geom
