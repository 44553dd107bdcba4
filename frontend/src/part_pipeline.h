// The parts of the main module, each checked and then run at once (private
// to the front end): running a part reads the syntax tree its check has
// just read, while it is still in the cache, and a large file's parts go
// through both steps on two threads with one start and one join.
#pragma once

#include "checker.h"
#include "evaluator.h"

namespace cncc::frontend {

// After checker.checkItems() and the evaluation of the constants. The
// outcome (diagnostics in their order, declarations, values) is the one of
// doing each part's two steps in order on one thread.
void checkAndEvaluateParts(SemaContext& context, Checker& checker, Evaluator& evaluator);

} // namespace cncc::frontend
