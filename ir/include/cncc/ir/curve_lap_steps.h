// The uniform steps of a lap cut in steps (CurveSampling::Steps) whose
// counts the lowering leaves to the legalisation (stepsChosenByLegalisation
// in the entry, `?` in the text): each such region takes the fewest uniform
// steps of its parameter whose chords all stay within the entry's amount,
// measured on the lap's curve (its geometry, or its regions interpreted).
// expand-controller-loops writes its loops with them and the interpreter
// runs the lap with them, so the IR before and after the pass cuts alike.
#pragma once

#include "cncc/geom/curve.h"
#include "cncc/ir/curve_table.h"

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>

namespace cncc::ir {

// The points the searches for one lap's counts may ask of its curve (104
// turns of a spiral within 1 um in eight pieces pass it, in about 3 s).
inline constexpr std::size_t maximumStepSearchEvaluations = 50'000'000;

// Whether `steps` uniform steps over [from, to] keep every chord within
// `budget` of the curve (measured, stopping at the first that does not).
bool uniformStepsFit(const geom::Curve& curve, double from, double to, int steps, double budget);

// The fewest uniform steps over [from, to] whose chords all deviate at most
// `budget` from the curve: a count that fits whose count below does not
// (found by doubling, then from the largest deviation as chords shrink
// with the square of the step, then bisection; every count returned has
// been measured); 0 past maximumStepsPerRegion.
int fewestUniformSteps(const geom::Curve& curve, double from, double to, double budget);

// The count a step search over a cut's curve returns (`search`: one of the
// above on a geom::BudgetedCurve), its failures as CurveLapError: past the
// curve's evaluation bound or maximumStepsPerRegion (a count of 0) at the
// cut, a curve that cannot be measured at the curve.
int searchedSteps(const std::function<int()>& search, frontend::SourceSpan cutSpan,
                  frontend::SourceSpan curveSpan);

// Whether the entry leaves a region's count to the legalisation.
bool hasChosenSteps(const CurveTableEntry& entry);

// The entry with every count left to the legalisation measured on `curve`
// (the lap's, in the whole curve's parameter), but an offset's that grow
// with the tool radius (offsetGrowth: curve_lap_offset_steps.h). Throws CurveLapError at the
// cut past maximumStepSearchEvaluations or maximumStepsPerRegion, or where
// the curve cannot be measured.
CurveTableEntry withChosenSteps(const CurveTableEntry& entry, const geom::Curve& curve);

// Where the controller reads a region's parameter step c = (to - from) / N
// with `digits` significant digits as c' > c, its last point lies N (c' - c)
// past the region's end, about that times the curve's speed off its end (a
// region that ends short leaves its last chord along the curve; the last
// region of a closed curve runs on along its start): refused past a quarter
// of the cut's `tolerance`. Throws CurveLapError (LiteralRounding).
void checkStepDrift(const CurveTableEntry& entry, const geom::Curve& curve, int digits,
                    double tolerance);

} // namespace cncc::ir
