// A polar or parametric curve's expressions evaluated at all its samples of
// `t` at once (private to the front end): each node of the tree is visited
// once for the 17 samples instead of once per sample, and what does not
// depend on `t` is computed once. It follows the number fast path
// (number_evaluation.cpp) node for node, with the same arithmetic, so it
// succeeds exactly when the fast path would succeed at every sample, and
// counts the steps that path would count.
#pragma once

#include "evaluator.h"

#include <cstddef>
#include <optional>
#include <span>

namespace cncc::frontend {

// The samples of a curve's parameter: t = low + (high - low) * i / 16 for
// i = 0 .. 16.
inline constexpr int curveSampleIntervals = 16;

struct CurveSamples {
  const Declaration* parameter = nullptr; // the curve's `t`
  double low = 0;
  double high = 0;
  std::span<const Expr* const> expressions; // null entries are skipped
};

// The steps the number fast path would spend evaluating every expression
// (each one the curve gives) at every sample, with `t` bound innermost
// over `bindings`, at fn call depth `callDepth`. Nullopt when some sample
// is not a finite number or needs what the fast path leaves to the ordinary
// evaluation (which reports); then the samples must be evaluated one by
// one. Reads the program and the bindings only.
std::optional<std::size_t> fastPathSampleSteps(const SemaContext& context, std::size_t callDepth,
                                               const Bindings& bindings,
                                               const CurveSamples& samples);

} // namespace cncc::frontend
