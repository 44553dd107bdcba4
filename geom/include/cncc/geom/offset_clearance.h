#pragma once

#include "cncc/geom/curve.h"
#include "cncc/geom/deviation.h"

#include <Eigen/Core>

#include <limits>
#include <optional>

namespace cncc::geom {

/// Where a curve bends tightest on one side: parameter, point and the radius of
/// curvature there (infinity when it never bends to that side).
struct CurvatureExtreme {
  double t = 0.0;
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double radius = std::numeric_limits<double>::infinity();
};

/// The tightest bends of a curve as a tool offset by d (as OffsetCurve) sees them:
/// concave where the tool is on the inside of the bend (the centre of curvature on the
/// tool's side: the tool gouges where the radius is below |d|), convex where it is on
/// the outside. Sampled per smooth piece (at least 64 samples a piece, 4096 in all)
/// and every local extreme refined by golden-section search. d != 0.
struct OffsetClearance {
  CurvatureExtreme concave;
  CurvatureExtreme convex;
};
OffsetClearance offsetClearance(const Curve& curve, double distance);

/// Where the offset curve crosses itself (a closed contour whose offset loops, a
/// narrow neck two tool radii wide): the first crossing along the curve of two
/// non-adjacent chords of the offset sampled at `samples` parameters per smooth piece
/// (and the breakpoints; a curve of more than 1024 pieces at 4096 equal parameter
/// steps instead) and wherever the offset turns by more than 0.1 rad between them,
/// nullopt when none. The chords are kept in a grid, so that only chords sharing a
/// cell are tested against each other. Past 2,000,000 points asked of the offset for
/// the turns, or 20,000,000 tested pairs (a curve running over itself many times), it
/// throws EvaluationBudgetExceeded.
std::optional<Eigen::Vector3d> offsetSelfCrossing(const Curve& offset, int samplesPerPiece = 256);

/// Where a tool of `radius` whose centre runs on `offset` comes nearer than its radius
/// less `slack` to `base`, the curve it runs beside: the open end of a path run into
/// its own start, a loop or a crossing of the offset. The tool centre at the parameter
/// `t` of the offset, the nearest point of the base and its distance.
struct ClearanceViolation {
  double t = 0.0;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Vector3d nearest = Eigen::Vector3d::Zero();
  double distance = 0.0;
};

/// The tool centre nearest to the base curve of those the check measures, if one is
/// nearer than `radius - slack`: the offset's breakpoints and ends, and between them
/// steps of half the radius along it (at most 20,000 in all, further apart on a
/// longer curve), each measured against `part`, the base's samples within slack / 4
/// (a bounding-box tree: the work grows with the centres times the logarithm of the
/// samples) and, where near, its exact closest point. Distances are in 3D (a helix's
/// turns are a pitch apart). `radius` and `slack` > 0.
std::optional<ClearanceViolation> offsetClearanceViolation(const Curve& offset,
                                                           const CurveProximity& part,
                                                           double radius, double slack);
/// The same against `base` sampled here (wrap it in a BudgetedCurve to bound that).
std::optional<ClearanceViolation> offsetClearanceViolation(const Curve& offset, const Curve& base,
                                                           double radius, double slack);

} // namespace cncc::geom
