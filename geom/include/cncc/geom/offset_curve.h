#pragma once

#include "cncc/geom/curve.h"
#include "cncc/geom/geometry_error.h"

#include <Eigen/Core>

#include <memory>
#include <optional>
#include <vector>

namespace cncc::geom {

/// Signed curvature in XY, (x'y'' - y'x'') / |C'|^3: positive where the curve turns
/// left (counter-clockwise); zero where the curve is singular (C' = 0).
double signedCurvatureOf(const CurveDerivatives& d);

/// The angle in XY a path turns where `before` ends and `after` starts, from the one's
/// end tangent to the other's start tangent (counter-clockwise positive, within ±pi).
double cornerTurn(const Curve& before, const Curve& after);

/// The left unit normal in XY of a tangent direction: the tangent turned a quarter
/// turn counter-clockwise, z = 0.
Eigen::Vector3d leftNormalOf(const Eigen::Vector3d& tangent);

/// The exact offset O(t) = C(t) + d N(t) of a smooth curve, N the left unit normal in
/// XY in the direction of travel: d > 0 to the left of the curve, d < 0 to the right
/// (a tool of radius r on side=left is d = r, on side=right d = -r). z is the base
/// curve's. In the base curve's parameter:
///   O'  = C' (1 - d k)            (k the signed curvature; O' is parallel to C')
///   O'' from fourth-order differences of O' within the base's smooth pieces.
/// Where d k >= 1 the offset has a cusp or a loop: the tool cannot follow (see
/// offset_clearance.h).
class OffsetCurve : public Curve {
public:
  OffsetCurve(std::shared_ptr<const Curve> base, double distance);

  const Curve& base() const { return *base_; }
  double distance() const { return distance_; }

  ParameterRange domain() const override { return base_->domain(); }
  Eigen::Vector3d point(double t) const override;
  Eigen::Vector3d derivative(double t) const override;
  Eigen::Vector3d secondDerivative(double t) const override;
  CurveDerivatives derivatives(double t) const override;
  std::vector<double> breakpoints() const override { return breakpoints_; }

private:
  // The smooth piece of the base holding t (the later one at a breakpoint).
  ParameterRange smoothPieceAt(double t) const;

  std::shared_ptr<const Curve> base_;
  double distance_;
  std::vector<double> breakpoints_;
};

/// Thrown where an offset cannot be built as asked: `place` is where, on the base
/// curve, and `radius` the radius found there (a concave corner has radius 0).
class OffsetError : public GeometryError {
public:
  OffsetError(const std::string& message, const Eigen::Vector3d& place, double radius)
      : GeometryError(message), place(place), radius(radius) {}
  Eigen::Vector3d place;
  double radius;
};

/// The offset at signed distance d (as OffsetCurve) of a curve made of pieces, each
/// smooth, joined end to start: a LineCurve stays a line and an ArcCurve an arc of
/// radius R - d (counter-clockwise) or R + d (clockwise); other pieces become
/// OffsetCurves. Offsets that meet as closely as their pieces do (within 1e-7 mm
/// more: a tangent join, even across the pieces' own small gap) are joined as they
/// are. Where two pieces meet at a corner on the side away from the offset
/// (convex) an arc of radius |d| about the corner joins their offsets; at a corner on
/// the offset's side (concave) both offsets are cut back to where they cross (a line
/// or an arc stays one). A path whose end meets its start is joined there too.
/// Throws OffsetError where two offsets at a concave corner do not cross within their
/// pieces (radius 0) and where an arc's offset radius would not be positive (the
/// arc's radius); GeometryError for d = 0 or no pieces. One piece gives its offset
/// alone; several a CompositeCurve.
std::shared_ptr<const Curve> offsetOfPieces(const std::vector<std::shared_ptr<const Curve>>& pieces,
                                            double distance);

/// The offset of pieces as offsetOfPieces builds it, and where each of its parts
/// (piecesOf(*curve), in order) comes from: the index of the drawn piece it lies
/// beside (cut back at a concave corner), or nullopt for the arc about a convex
/// corner, which follows the piece ending there (the arc where a closed path
/// closes comes last).
struct PiecesOffset {
  std::shared_ptr<const Curve> curve;
  std::vector<std::optional<std::size_t>> partOrigins;
};
PiecesOffset offsetOfPiecesWithOrigins(const std::vector<std::shared_ptr<const Curve>>& pieces,
                                       double distance);

} // namespace cncc::geom
