#pragma once

#include "cncc/geom/curve.h"

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
/// narrow neck two tool radii wide): the first crossing of two non-adjacent chords of
/// the offset sampled at `samples` parameters per smooth piece (and the breakpoints),
/// nullopt when none. The chords' work grows with the square of their number, so
/// they are capped at 4096 (a curve of more than 1024 pieces is sampled at equal
/// parameter steps instead).
std::optional<Eigen::Vector3d> offsetSelfCrossing(const Curve& offset, int samplesPerPiece = 256);

} // namespace cncc::geom
