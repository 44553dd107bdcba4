// `move.polynomial %x, %y, %z, %k3x, %k2x, %k1x, %k3y, %k2y, %k1y, %k3z,
// %k2z, %k1z, %f`: a cubic span (Heidenhain TNC `SPL`) as the IR holds it.
// Per axis the tool follows
//
//   P(t) = K3 t^3 + K2 t^2 + K1 t + E,   t from 1 down to 0,
//
// E the end point (the first three operands): it starts at K3 + K2 + K1 + E,
// which must be where the machine is (within 1 um, as the TNC requires), and
// ends at E, at feed f.
#pragma once

#include "cncc/geom/nurbs_curve.h"
#include "cncc/ir/tool_path.h"

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace cncc::ir {

// The operands of move.polynomial: 3 end coordinates, 9 coefficients, the feed.
inline constexpr std::size_t polynomialMoveOperands = 13;

struct PolynomialMove {
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
  // K3, K2, K1: each a vector of the X, Y and Z coefficients.
  std::array<Eigen::Vector3d, 3> coefficients{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                              Eigen::Vector3d::Zero()};

  Eigen::Vector3d start() const {
    return end + coefficients[0] + coefficients[1] + coefficients[2];
  }
  // Moves the start to `start` by K3 - 2d and K2 + 3d (d the shift): both
  // tangents stay as they are, and no point moves by more than d.
  void startAt(const Eigen::Vector3d& start);
  Eigen::Vector3d pointAt(double t) const;
  // The direction of travel (towards the end) where the span starts and ends.
  Eigen::Vector3d startDirection() const;
  Eigen::Vector3d endDirection() const;
};

// The spans of a non-rational curve of degree 3 or less, one per knot span,
// exactly. Throws geom::GeometryError for a rational curve or a degree over 3.
std::vector<PolynomialMove> polynomialMoves(const geom::NurbsCurve& curve);

// The angle (degrees) the path turns from the end of `before` to the start
// of `after`; 0 where either has no direction.
double polynomialTransitionDegrees(const PolynomialMove& before, const PolynomialMove& after);

// The span of move.polynomial's first 12 operand values.
PolynomialMove polynomialMoveOf(std::span<const double, 12> values);

// The table of a cut's spans (a lap cut as polynomial blocks): each span's
// first 12 operand values of move.polynomial, its end at the pass height 0.
std::vector<double> polynomialMoveTable(const std::vector<PolynomialMove>& spans);

// The spans of a table, or why the table does not hold any (the verifier's
// message).
std::optional<std::vector<PolynomialMove>> readPolynomialMoveTable(std::span<const double> table,
                                                                   std::string* problem = nullptr);

// The feed moves the control makes along `move` from `start`: chords within
// 1e-5 of the cubic, the last at its end, appended to `events`. Throws
// InterpreterError when `start` is more than 1 um from the span's start or a
// value is not finite. The interpreter and the virtual TNC record SPL so.
void polynomialMove(const std::array<double, 3>& start, const PolynomialMove& move, double feed,
                    std::vector<MachineEvent>& events);

} // namespace cncc::ir
