// `move.nurbs @t, %z, %f, %w0, .. %wn`: NURBS interpolation (Fanuc and
// Mitsubishi G06.2) as the IR holds it. Table t is the curve's block data:
//
//   [order, knot 0 .. knot n+order-1, x0, y0, z0, .. xn-1, yn-1, zn-1]
//
// one weight operand per control point (a part parameter stays an SSA value,
// so an edit at the machine reaches the curve), z added to every control
// point (the pass height), f the feed. The move starts where the machine is,
// which must be the first control point, as the controllers require.
#pragma once

#include "cncc/geom/nurbs_curve.h"
#include "cncc/ir/tool_path.h"

#include <Eigen/Core>

#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace cncc::ir {

struct NurbsBlockData {
  int order = 0;
  std::vector<double> knots;
  std::vector<Eigen::Vector3d> points;
};

// The table of a curve's block data.
std::vector<double> nurbsMoveTable(const geom::NurbsCurve& curve);

// The block data of a table for `weights` weights, or why the table does not
// hold it (the verifier's message).
std::optional<NurbsBlockData> readNurbsMoveTable(std::span<const double> table, std::size_t weights,
                                                 std::string* problem = nullptr);

// The curve the move follows: the block data raised by z, with the weights.
// Throws InterpreterError for block data no NURBS has (a weight <= 0...).
geom::NurbsCurve nurbsMoveCurve(const NurbsBlockData& data, double z,
                                std::span<const double> weights);

// The feed moves a controller's NURBS interpolation makes from `start`, in
// chords within 1e-5 of the curve (or 1e-7 of its size, if larger), the
// last at the curve's end, appended to `events`. Throws InterpreterError,
// as a controller alarms, when `start` is not the first control point. The
// interpreter and the JIT both record NURBS moves so.
void nurbsMove(const std::array<double, 3>& start, std::span<const double> table, double z,
               double feed, std::span<const double> weights, std::vector<MachineEvent>& events);

} // namespace cncc::ir
