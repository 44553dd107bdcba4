// How a target wants its parts lowered: what it interpolates natively
// (arcs, NURBS blocks, splines), whether curve loops run on the controller,
// and the machine's limits the lowering checks. The lowering library
// (cncc/lowering/lowering.h) reads it; a backend says what it wants.
#pragma once

#include "cncc/ir/spline_blocks_kind.h"

#include <limits>
#include <string>
#include <vector>

namespace cncc::ir {

struct LoweringOptions {
  // Whether the lowering writes each lap along a curve out for the target
  // (runCurveLegalisation: bound-controller-steps, write-curve-blocks,
  // fit-arcs, expand-controller-loops, expand-curve-laps) or leaves it a
  // curve.lap: the
  // target-neutral IR, which `--emit=ir` shows before the target's passes.
  bool expandCurveLaps = true;
  // Whether the target interpolates splines (method=cspline, aspline,
  // bspline, nurbs) itself. Without it such a cut is cut as straight feed
  // moves within its tolerance, with a spline-as-chords warning.
  bool splineInterpolation = false;
  // Whether a spline method= cut as chords is reported (spline-as-chords,
  // by the lowering or choose-curve-blocks): not by verify's reference,
  // whose target's own compile has said so.
  bool reportSplineAsChords = true;
  // The curve blocks the target prints, which the cut table says
  // (CutGeometry::printedBlocks) and choose-curve-blocks makes of the laps
  // of a method= spline cut. Fanuc/Mitsubishi G06.2: method=nurbs as one
  // move.nurbs per pass.
  bool nurbsBlocks = false;
  // Heidenhain SPL: a spline-method cut (cspline, aspline, bspline, nurbs)
  // as move.polynomial cubic spans.
  bool polynomialBlocks = false;
  // Sinumerik: a method=bspline, nurbs, cspline or aspline cut in a plane
  // z = constant as move.spline blocks fitted once, on the printed grid,
  // their ends as `splineEnds` says.
  bool splineBlocks = false;
  SplineEnds splineEnds = SplineEnds::Automatic;
  // Whether a cut that wants arcs (arcs=true, or arcsOnEveryCut without
  // arcs=false) asks its laps for arcs fitted on the printed grid, which
  // fit-arcs writes as move.arc ops (arc_cuts.cpp): every target prints
  // them; verify's reference of chords does without.
  bool fittedArcs = true;
  bool arcsOnEveryCut = false; // --arcs
  // Controller-side targets (macro programs): each cut becomes loops the
  // controller runs over uniform parameter steps, a pass loop over the sweep
  // and no constant tables; what depends on part parameters (step counts
  // included) is computed on the controller. See controller_cuts.cpp.
  bool controllerLoops = false;
  // A `for` whose bounds read parameters lowered as the loop a controller
  // runs, and an `if` whose condition does as its branches, on a target
  // whose host computes the program too (the IR is then the same for every
  // target; the legalisation unroll-host-control writes them out). Without
  // it or controllerLoops, the lowering writes the loop out itself, each
  // trip's cut with the curve the front end evaluates for that trip, and
  // lowers the branch taken: the references that measure a program (verify,
  // --stats and the tests), which tell each trip's cut apart.
  bool keepLoops = false;
  // The significant digits of the constants the controller reads (0: the
  // target folds every number on the host). A NURBS span evaluated on the
  // controller from power-basis coefficients whose rounding to these digits
  // would move its points by more than a quarter of the tolerance (a weight
  // of 1e9: coefficients of 1e10 that cancel) is an error at the cut. The
  // constant terms of sin, cos and tan's angles are taken modulo a turn,
  // and a number whose rounding still moves a cut's points through one of
  // them by more than a quarter of its tolerance (1e9 deg shared between
  // bolt holes) is an error at its statement (cncc/lowering/literal_rounding.h).
  int literalSignificantDigits = 0;
  // The controller's least input increment (mm or inch; 0: none). Its
  // rounding of every executed coordinate, half an increment per axis, is
  // taken from the tolerance before the chord error is chosen.
  double coordinateIncrement = 0;
  // How deep the controller nests loops (0: no limit). A `for` run on the
  // controller that would nest deeper is unrolled instead.
  int maximumLoopNesting = 0;
  // What the machine's set-up has: `origin G54.1 Pn` up to this n (0: no
  // extended work offsets), and a code for through-spindle coolant.
  int maximumExtendedWorkOffset = 0;
  bool throughSpindleCoolant = false;
  // The target prints the controller's cutter radius compensation (G41/G42
  // D.., G40) for `comp=controller`; `targetName` names it in the error
  // where it does not.
  bool cutterCompensation = false;
  // Corners of less than this (radians) between compensated moves the
  // controller runs as tangent: it goes straight on from the offset end of
  // one move, off the exact offset by up to r (1 - cos) (LinuxCNC: 0.05).
  double compensationTangentAngle = 0;
  // The controller meets the offsets of a convex corner at their crossing
  // unless told otherwise (Fanuc, Mitsubishi): a `corner.arc` (G39) at each
  // convex corner of a compensated curve makes it go round on an arc of the
  // radius, as the exact offset does.
  bool compensationCornerArcs = false;
  // ... after a line only (Mitsubishi writes G39 on the move block, and on
  // an arc block its I J would be the arc's): after an arc the offsets meet.
  bool cornerArcsAfterLinesOnly = false;
  std::string targetName;
  // The machine's largest feed (mm/min, whatever the part's units) and
  // spindle speed (rpm); 0: no limit. A constant beyond it is an error at
  // the statement that sets it.
  double maximumFeed = 0;
  double maximumSpindleSpeed = 0;
  // The largest coordinate, radius or feed (mm, mm/min) the target's
  // programs can write; a tenth of it in inches. A cut whose curve, depth or
  // feed at the values compiled with goes beyond it is a coordinate-range
  // error.
  double largestNumber = std::numeric_limits<double>::infinity();
  // The largest coordinate or arc centre offset the target prints, in the
  // part's units, where its printed decimals leave less than largestNumber
  // within its reader's significant digits (gcode: 9999.9999); a curve
  // beyond it is a coordinate-range error, a fitted arc of a larger radius
  // is cut as lines. Feeds keep largestNumber.
  double largestCoordinate = std::numeric_limits<double>::infinity();
  // The passes (passes.h, by name) that make the optimised IR what the
  // target's printer takes, run in order after the optimiser (at -O0 too):
  // fold-finite for the macro programs. The lowering does not run them;
  // whoever optimises does (the driver after its optimiser).
  std::vector<std::string> passesBeforePrinting;
};

} // namespace cncc::ir
