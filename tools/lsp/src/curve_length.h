// Curve lengths for hovers, from the geometry kernel.
#pragma once

#include "cncc/frontend/value.h"

#include <optional>

namespace cncc::lsp {

// The arc length of a compile-time curve value. Nullopt for curves given by
// expressions in `t` (polar, param, and paths or transforms holding one):
// evaluating those needs the front end's evaluator, which is private to it.
std::optional<double> curveLength(const frontend::CurveValue& curve);

} // namespace cncc::lsp
