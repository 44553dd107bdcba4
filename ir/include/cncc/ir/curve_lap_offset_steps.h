// The counts of a lap beside a curve whose tool radius the program reads
// (CurveTableEntry::offsetGrowth): a region left to the legalisation takes
// N(r) = N0 sqrt(1 + q r) uniform steps at the tool radius r. A chord over
// a parameter step h deviates from the offset by about h^2 s'^2 |k (1 - d k)|
// / 8 (s' the speed, k the signed curvature, d the tool-centre distance), at
// most h^2 (s'^2 |k| + r s'^2 k^2) / 8, so N(r)^2 = N0^2 + Q r: N0 the
// fewest steps on the drawn curve, Q from the largest s'^2 k^2 over the
// region, and q = Q / N0^2. Both are measured on the regions themselves (the
// drawn curve is their points at d = 0, the exact offset at d = side r),
// and Q is raised until N(r) fits the exact offset at radii around the
// compiled one. expand-controller-loops writes N(r) as the program's
// arithmetic on the distance the lap reads; the interpreter computes it the
// same way.
#pragma once

#include "cncc/ir/curve_lap.h"
#include "cncc/ir/ir.h"

#include <cstddef>
#include <vector>

namespace cncc::ir {

// The points the measurements of one lap's offset counts may ask of its
// regions.
inline constexpr std::size_t maximumOffsetStepEvaluations = 10'000'000;

// N0 and q of one region (0 and 0 for a region with a count of its own).
struct OffsetRegionGrowth {
  double drawnSteps = 0;
  double growth = 0;
};

// N0 and q of each region of `lap` whose count is left to the legalisation
// in an entry with offsetGrowth, measured as the program was compiled:
// what the regions read from outside the lap but the distance at the
// parameters' defaults (so the counts the interpreter runs are the printed
// program's, whatever the parameters). Throws CurveLapError: at the cut past
// maximumOffsetStepEvaluations or maximumStepsPerRegion at the compiled
// radius, or where the growth cannot be bounded; at the curve where it
// cannot be measured.
std::vector<OffsetRegionGrowth> measureOffsetGrowth(const Function& function,
                                                    const Instruction& lap);

// The count at the tool-centre distance `distance`, as the program computes
// it: ROUND[N0 * SQRT[1 + q * r] + 0.5] with r = side * distance.
double offsetStepsAt(const OffsetRegionGrowth& region, const OffsetStepGrowth& growth,
                     double distance);

} // namespace cncc::ir
