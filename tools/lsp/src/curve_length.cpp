#include "curve_length.h"

#include "cncc/geom/arc_length.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/geom/nurbs_curve.h"

#include <cmath>

namespace cncc::lsp {

namespace {

using frontend::CurveKind;
using frontend::CurveValue;

// Hovers need a few digits, not the kernel's default 1e-10 mm.
constexpr double hoverTolerance = 1e-6;

std::optional<double> splineLength(const CurveValue& curve) {
  std::vector<Eigen::Vector3d> points;
  for (const auto& point : curve.points) {
    points.emplace_back(point[0], point[1], point[2]);
  }
  std::vector<double> weights = curve.weights;
  if (weights.empty()) {
    weights.assign(points.size(), 1.0);
  }
  if (geom::NurbsCurve::findProblem(curve.knots, curve.degree, points, weights)) {
    return std::nullopt;
  }
  geom::NurbsCurve nurbs(geom::KnotVector(curve.knots, curve.degree), std::move(points),
                         std::move(weights));
  return geom::arcLength(nurbs, hoverTolerance);
}

std::optional<double> lengthOf(const CurveValue& curve) {
  switch (curve.kind) {
  case CurveKind::Nurbs:
    return splineLength(curve);
  case CurveKind::Line:
    return std::hypot(curve.to[0] - curve.from[0], curve.to[1] - curve.from[1],
                      curve.to[2] - curve.from[2]);
  case CurveKind::Arc:
    return std::abs(curve.arcRadius * (curve.endAngle - curve.startAngle));
  case CurveKind::Path: {
    double total = 0;
    for (const auto& piece : curve.pieces) {
      std::optional<double> length = piece ? lengthOf(*piece) : std::nullopt;
      if (!length) {
        return std::nullopt;
      }
      total += *length;
    }
    return total;
  }
  case CurveKind::Translate:
  case CurveKind::Rotate:
  case CurveKind::Scale: {
    if (curve.pieces.empty() || !curve.pieces.front()) {
      return std::nullopt;
    }
    std::optional<double> length = lengthOf(*curve.pieces.front());
    double factor = curve.kind == CurveKind::Scale ? std::abs(curve.factor) : 1.0;
    return length ? std::optional(*length * factor) : std::nullopt;
  }
  case CurveKind::Polar:
  case CurveKind::Param:
    return std::nullopt;
  }
  return std::nullopt;
}

} // namespace

std::optional<double> curveLength(const CurveValue& curve) {
  try {
    return lengthOf(curve);
  } catch (const geom::GeometryError&) {
    return std::nullopt; // the front end reports invalid curves itself
  }
}

} // namespace cncc::lsp
