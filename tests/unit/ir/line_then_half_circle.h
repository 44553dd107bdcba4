// A test curve of two pieces: a line from (0, 0) to (10, 0), then a half
// circle of radius r about (10, r) to (10, 2r), in the parameter of a
// composite curve (the line's 0 .. 10, then the circle's angle 0 .. pi).
#pragma once

#include "cncc/geom/composite_curve.h"
#include "cncc/geom/function_curve.h"
#include "cncc/geom/line_arc_curves.h"

#include <cmath>
#include <memory>
#include <numbers>

namespace cncc::ir::test_support {

inline std::shared_ptr<const geom::Curve> lineThenHalfCircleGeometry(double r) {
  auto line =
      std::make_shared<geom::LineCurve>(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(10, 0, 0));
  auto half = std::make_shared<geom::FunctionCurve>(geom::FunctionCurve::fromCoordinates(
      {0, std::numbers::pi}, [r](double s) { return 10 + r * std::sin(s); },
      [r](double s) { return r - r * std::cos(s); }));
  return std::make_shared<geom::CompositeCurve>(
      std::vector<std::shared_ptr<const geom::Curve>>{line, half});
}

} // namespace cncc::ir::test_support
