// Numbers on the printed grid: the coordinates of fitted arcs and NURBS
// control points go where the printed program puts them, so the IR's
// constants are the printed program's numbers.
#pragma once

#include <Eigen/Core>

namespace cncc::ir {

// The value a controller reads from `value` printed with the decimals of
// `increment` (10^-n), rounded as the printers round ("%.nf"); the value
// itself when there is no increment.
double onPrintedGrid(double value, double increment);

Eigen::Vector3d onPrintedGrid(const Eigen::Vector3d& point, double increment);

} // namespace cncc::ir
