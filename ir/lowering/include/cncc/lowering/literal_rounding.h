// How far the controller's reading of a program's numbers, each rounded to
// the digits it keeps, moves the points of its cuts where the rounding
// reaches them through sin, cos or tan. A rounded angle turns the point
// about the centre it is measured from: 1e9 deg read as 17453293. rad is
// 0.48 rad off, 17 mm on a 38 mm bolt circle, where the same rounding of a
// coordinate would be a fraction of a micrometre.
//
// The estimate is first order: each number's rounding times the derivative
// of the angle with respect to it, the derivative taken at the largest
// magnitude each value can have with the parameters' defaults (a loop's
// variable at the larger of its bounds), and the angle's error times the
// lever that multiplies the sine or cosine on its way to a coordinate. The
// controller's conversion of the angle to degrees counts with the rounding
// of its factor: 180/pi, or where the printers fold a constant into it,
// that constant times 180/pi. The rounding of a curve's parameter (its
// step, the factors it is multiplied by, its conversion to degrees) is not
// counted: the same rounded parameter feeds every coordinate, so it moves
// the point along the curve, not off it.
//
// It does not cover: a curve whose coordinates use different rounded
// frequencies of its parameter (a Lissajous figure); a curve's end passed
// by a parameter that builds up rounded steps; parameter values other than
// the defaults; a divisor smaller than its largest magnitude; the
// steepness of tan near a quarter turn, and of exp, ln, pow and the
// inverse functions; rounding that reaches a point without a periodic
// function (a NURBS span's coefficients are checked where they are
// chosen: PartLowering::spanLiteralsFit).
#pragma once

#include "cncc/ir/ir.h"
#include "cncc/ir/printed_grid.h"

#include <cstdint>
#include <vector>

namespace cncc::ir::lowering {

// controllerReading (printed_grid.h): the number as such a controller reads it.
using ir::controllerReading;

// The largest movement of one cut's feed moves.
struct LiteralRoundingMove {
  // The cut (cut.begin's index).
  std::uint32_t cut = 0;
  // How far the point can move (mm, first order).
  double movement = 0;
  // What rounds most of it: a const or param instruction whose number is
  // rounded, or the sin, cos or tan whose angle the controller converts to
  // degrees with a rounded factor.
  InstructionId source = 0;
};

// For each cut with feed moves that rounding reaches through sin, cos or
// tan, its largest movement, in the order of the cuts' indices.
std::vector<LiteralRoundingMove> trigonometricRoundingMoves(const Function& function, int digits);

} // namespace cncc::ir::lowering
