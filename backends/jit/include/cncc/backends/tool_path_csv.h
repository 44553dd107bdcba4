// The `jit` target's output: the tool path as CSV, `x,y,z,feed,rapid`, one
// line per move (rapid = 1 for G00-like moves, their feed 0); an arc as
// feed moves whose chords stay within toolPathCsvArcSagitta of it.
#pragma once

#include "cncc/ir/tool_path.h"

#include <stdexcept>
#include <string>

namespace cncc::backends {

// The decimals a CSV number is printed with, at most.
inline constexpr int toolPathCsvDecimals = 6;
// How far an arc's chords in the CSV stray from it (mm): 0.1 um.
inline constexpr double toolPathCsvArcSagitta = 1e-4;

// Up to 6 decimals, trailing zeros and a bare trailing point trimmed: `25`,
// `0.5`, `-1.25`; never `-0`.
std::string formatCsvNumber(double value);

// The most rows a tool path's CSV may have (about 160 MB of text).
inline constexpr double maximumToolPathCsvRows = 4'000'000;

// A tool path whose CSV would have more than maximumToolPathCsvRows rows.
class ToolPathTooLarge : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// The path as CSV, its arcs as chords within `arcSagitta`; throws
// ToolPathTooLarge, before writing any, past maximumToolPathCsvRows.
std::string writeToolPathCsv(const ir::ToolPath& path, double arcSagitta = toolPathCsvArcSagitta);

} // namespace cncc::backends
