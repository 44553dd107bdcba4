// `move.spline @t, %z, %f`: Sinumerik spline interpolation (BSPLINE,
// CSPLINE, ASPLINE) as the IR holds it. Table t is the blocks' data:
//
//   [kind, degree, start, end, n, x1, y1, z1, .. xn, yn, zn, (B only:) w1 .. wn, l1 .. ln]
//
// kind 0 BSPLINE, 1 CSPLINE, 2 ASPLINE; degree SD (2 or 3; 3 for the
// interpolating splines); start and end the transitions of a C or A spline
// (geom::SplineEndCondition: 0 auto, 1 natural, 2 tangent); n points after
// the start, which is where the machine is: a B spline's control points
// with their weights PW and knot intervals PL, a C or A spline's knots.
// z is added to every point (the pass height), f is the feed. The curve is
// the one geom's models say the controller builds (controller_bspline.h,
// interpolating_splines.h): a tangent start follows the feed move before
// the spline, a tangent end the last chord (the lowering retracts straight
// up after a spline).
#pragma once

#include "cncc/geom/curve.h"
#include "cncc/geom/interpolating_splines.h"
#include "cncc/ir/spline_blocks_kind.h"
#include "cncc/ir/tool_path.h"

#include <Eigen/Core>

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace cncc::ir {

struct SplineBlockData {
  SplineKind kind = SplineKind::BSpline;
  int degree = 3;
  geom::SplineEndCondition start = geom::SplineEndCondition::Natural;
  geom::SplineEndCondition end = geom::SplineEndCondition::Natural;
  std::vector<Eigen::Vector3d> points;
  std::vector<double> weights;   // BSpline: PW per point
  std::vector<double> intervals; // BSpline: PL per point
};

std::vector<double> splineMoveTable(const SplineBlockData& data);

// The block data of a table, or why the table does not hold any (the
// verifier's message).
std::optional<SplineBlockData> readSplineMoveTable(std::span<const double> table,
                                                   std::string* problem = nullptr);

// The curve the controller cuts from `start` (where the machine is), the
// points raised by z, a tangent start along `arrival` (the XY direction of
// the feed move before it, if any). Throws InterpreterError when the
// points make no spline.
std::shared_ptr<const geom::Curve> splineMoveCurve(const SplineBlockData& data,
                                                   const Eigen::Vector3d& start, double z,
                                                   const std::optional<Eigen::Vector3d>& arrival);

// The feed moves the controller's spline makes from where the last move in
// `events` ended, in chords within 1e-5 of the curve (or 1e-7 of its size,
// if larger), the last at its end, appended to `events`; each is marked
// with `table` (MachineEvent::splineTable), the first as the move's start.
// The interpreter and the JIT both record spline moves so.
void splineMove(std::uint32_t table, std::span<const double> data, double z, double feed,
                std::vector<MachineEvent>& events);

} // namespace cncc::ir
