// Running parts at compile time (private to the front end): each part's body
// with its parameters at their defaults (or -D values), the way the machine
// will run it, checking what only values show (part_evaluation.cpp).
#pragma once

#include "evaluator.h"

#include <vector>

namespace cncc::frontend {

// Every constant of every module, before any part uses one (so that parts
// on two threads only read them).
void evaluateConstants(Evaluator& evaluator);

// One checked part of the main module. `assigned`, when given, collects the
// declarations whose values are set (to undo them).
void evaluatePart(Evaluator& evaluator, const PartItem& part,
                  std::vector<const Declaration*>* assigned = nullptr);

} // namespace cncc::frontend
