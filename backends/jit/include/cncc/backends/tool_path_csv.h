// The `jit` target's output: the tool path as CSV, `x,y,z,feed,rapid`, one
// line per move (rapid = 1 for G00-like moves, their feed 0); an arc as
// feed moves whose chords stay within toolPathCsvArcSagitta of it.
#pragma once

#include "cncc/ir/tool_path.h"

#include <string>

namespace cncc::backends {

// The decimals a CSV number is printed with, at most.
inline constexpr int toolPathCsvDecimals = 6;
// How far an arc's chords in the CSV stray from it (mm): 0.1 um.
inline constexpr double toolPathCsvArcSagitta = 1e-4;

// Up to 6 decimals, trailing zeros and a bare trailing point trimmed: `25`,
// `0.5`, `-1.25`; never `-0`.
std::string formatCsvNumber(double value);

std::string writeToolPathCsv(const ir::ToolPath& path);

} // namespace cncc::backends
