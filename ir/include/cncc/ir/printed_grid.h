// Numbers on the printed grid: the coordinates of fitted arcs and NURBS
// control points go where the printed program puts them, so the IR's
// constants are the printed program's numbers.
#pragma once

#include "cncc/geom/curve.h"

#include <Eigen/Core>

#include <utility>

namespace cncc::ir {

// The value a controller reads from `value` printed with the decimals of
// `increment` (10^-n), rounded as the printers round ("%.nf"); the value
// itself when there is no increment.
double onPrintedGrid(double value, double increment);

Eigen::Vector3d onPrintedGrid(const Eigen::Vector3d& point, double increment);

// The number as a controller that keeps `digits` significant digits reads
// it: as the macro printers write it, with at most `digits` digits, the
// whole part's included, and at most `digits` decimals; the number itself
// when `digits` is 0.
double controllerReading(double value, int digits);

// Where `curve` starts and ends, on the printed grid: where the blocks fitted
// to it (SPL spans, a fitted G06.2 block) start and end.
std::pair<Eigen::Vector3d, Eigen::Vector3d> curveEndsOnGrid(const geom::Curve& curve,
                                                            double increment);

} // namespace cncc::ir
