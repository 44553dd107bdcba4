#pragma once

// Replacing a planar curve by tangent-continuous circular arcs (biarcs) and lines,
// for G2/G3 output.

#include "cncc/geom/composite_curve.h"
#include "cncc/geom/curve.h"
#include "cncc/geom/line_arc_curves.h"

#include <Eigen/Core>

#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace cncc::geom {

enum class ArcSegmentKind { Line, Arc };

/// One G1 (line) or G2/G3 (arc) move in the plane z = start.z() (G17).
struct ArcSegment {
  ArcSegmentKind kind = ArcSegmentKind::Line;
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
  /// Arcs only: centre (the printer writes I J = centre - start), radius, turning
  /// direction and signed sweep (rad, positive counter-clockwise, |sweep| <= pi).
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  double radius = 0.0;
  ArcDirection direction = ArcDirection::CounterClockwise;
  double sweep = 0.0;

  double length() const;
  /// The move as a curve (LineCurve or ArcCurve).
  std::shared_ptr<const Curve> curve() const;
};

struct ArcFitOptions {
  /// Largest allowed distance between the arcs and the curve (mm), > 0.
  double tolerance = 0.01;
  /// Arcs of a larger radius are lines (a controller reads centre offsets only
  /// within its number range); the fit keeps the tolerance with them.
  double largestRadius = std::numeric_limits<double>::infinity();
};

struct ArcFit {
  std::vector<ArcSegment> segments;
  /// Both directed deviations between path() and the curve (measureCurveDeviation at
  /// 1e-3 of the tolerance).
  double deviation = 0.0;

  std::size_t arcCount() const;
  std::size_t lineCount() const;
  /// The segments joined into one curve, for measurement and simulation.
  CompositeCurve path() const;
};

/// Why the curve cannot be replaced by arcs in the XY plane (it leaves the plane
/// z = const), or nothing.
std::optional<std::string> findArcFittingProblem(const Curve& curve);

/// Tangent-continuous arcs and lines within the tolerance of a curve in a plane
/// z = const, each arc at most 180 degrees.
///
/// Greedy farthest reach by biarcs: from the current point, with the curve's tangent
/// there, the next point is the farthest curve point (doubling, then bisection) to
/// which a biarc (two arcs meeting tangentially, starting and ending with the curve's
/// tangents) stays within the tolerance of the curve between the two points; the
/// biarc's free parameter (the ratio of its two tangent legs) is first taken equal,
/// and searched (golden section on its logarithm) where equal legs do not fit. Both
/// directed distances are measured against the curve itself, not against chords. The
/// path is tangent-continuous except at corners of the curve (breakpoints where its
/// tangent jumps), where it turns as the curve does; breakpoints where the curvature
/// jumps (joins of lines and arcs) end a biarc too, so lines and arcs of the curve
/// come out as themselves. Arcs flatter than 1e-9 mm of
/// sagitta become lines; consecutive lines on one line and arcs on one circle are
/// merged while an arc stays within 180 degrees. Throws GeometryError for a
/// tolerance <= 0 or a curve findArcFittingProblem rejects.
ArcFit fitArcs(const Curve& curve, const ArcFitOptions& options = {});

} // namespace cncc::geom
