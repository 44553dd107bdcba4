// Sampling the curves the virtual Sinumerik cuts: chords within a sagitta.
#pragma once

#include "cncc/geom/curve.h"
#include "cncc/geom/discretisation.h"

namespace cncc::backends::sinumerik {

// Equal parameter steps on each smooth piece, short enough that a chord
// sags at most `tolerance`: over a step h the sagitta is at most
// h^2 max|C''| / 8, the maximum taken over 33 samples with a margin.
geom::CurveSamples sampleDensely(const geom::Curve& curve, double tolerance);

} // namespace cncc::backends::sinumerik
