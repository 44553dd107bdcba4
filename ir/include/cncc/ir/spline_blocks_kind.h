// Which Sinumerik spline blocks a cut is printed as, and how an A or C
// spline begins and ends: what the lowering asks (LoweringOptions), the
// curve table keeps for the fit (CurveTableEntry::splineFit) and a
// move.spline's table holds.
#pragma once

namespace cncc::ir {

enum class SplineKind { BSpline = 0, CSpline = 1, ASpline = 2 };

// How A and C spline blocks begin and end (--spline-ends).
enum class SplineEnds {
  // A tangent start where the block before the spline moves in XY (the
  // last chord of a ramp), a natural one after a vertical plunge; a natural end.
  Automatic,
  Natural, // BNAT ENAT
  Auto,    // BAUTO EAUTO
};

} // namespace cncc::ir
