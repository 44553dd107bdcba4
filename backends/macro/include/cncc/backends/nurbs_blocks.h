// NURBS interpolation blocks for method=nurbs on Fanuc (G06.2) and
// Mitsubishi M70/M80/M800 (G05 P10000, then G06.2), as TARGETS.md gives the
// manuals' rules:
//
//   G06.2 P<order> K<knot> X.. Y.. Z.. R<weight> F<feed>  the first control point
//   K<knot> X.. Y.. Z.. R<weight>                          one block per further point
//   K<knot>                                                the remaining `order` knots
//
// The number of knots is the number of control points plus the order, the
// first and the last `order` knots are equal (clamped ends), no interior knot
// is repeated more than `order` times, the first control point is where the
// machine already is, and cutter compensation (G41/G42) is off. On M80 every
// weight and knot is printed with at most 4 decimals within 0.0001..99.9999:
// the weights are scaled together and the knots mapped affinely (neither
// changes the curve), a knot vector that cannot be mapped without merging
// knots is refused. A rule the curve breaks is an error naming the rule.
#pragma once

#include "cncc/backends/controller_profile.h"
#include "cncc/geom/nurbs_curve.h"

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace cncc::backends {

enum class NurbsDialect { Fanuc, Mitsubishi };

struct NurbsBlockOptions {
  NurbsDialect dialect = NurbsDialect::Fanuc;
  int coordinateDecimals = 3; // IS-B, millimetres
  // The pass height added to the curve's own z: a number, or where the
  // program computes it its coordinate text (`#4`) and its text as an
  // operand, for `Z[#4+1.5]` above a control point's own z.
  double z = 0;
  std::string zCoordinate;
  std::string zOperand;
  double feed = 0;
  std::string feedText; // printed after F instead of `feed` when not empty (`#9`)
  // Where the machine is when the first block runs (must be the first
  // control point, at the pass height; in X and Y where that is computed).
  Eigen::Vector3d currentPosition = Eigen::Vector3d::Zero();
  bool cutterCompensation = false; // G41/G42 in effect
  // Per control point, a variable that holds its weight (`#3`), or empty for
  // the number; a variable weight is printed as `R#3` as the syntax allows.
  std::vector<std::string> weightVariables;
};

struct NurbsBlocks {
  std::vector<std::string> lines;  // empty when errors is not
  std::vector<std::string> errors; // each names the G06.2 rule it breaks
  // The printed knots and weights (after the M80 mapping), for checking.
  std::vector<double> knots;
  std::vector<double> weights;
};

NurbsBlocks writeNurbsBlocks(const geom::NurbsCurve& curve, const NurbsBlockOptions& options);

} // namespace cncc::backends
