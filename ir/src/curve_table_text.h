// The function's curve table as IR text: printer.cpp writes each entry as
// a `curve @c ... { ... }` block before the body, parser.cpp reads it back.
// The entry's geometry, fitted arcs and source spans are not text.
#pragma once

#include "cncc/ir/curve_table.h"

#include <span>
#include <string>
#include <string_view>

namespace cncc::ir {

// `  curve @c chords 0.005 over from .. to {`, a `piece` line per piece, a
// line for each of the entry's other settings, `  }`. Chosen parameters an
// earlier entry of `curves` shares (a ramp's, which spline blocks after it
// go through) are `chosen as @e`.
std::string curveEntryText(std::span<const CurveTableEntry> curves, std::size_t index);

// Reading an entry back, a line at a time (each trimmed): its header (the
// entry `index` of the table), then each line to its `}`, for which
// readCurveEntryLine returns true. Both throw text::Failure.
// `earlier`: the entries read before, which `chosen as @e` may name.
CurveTableEntry readCurveEntryHeader(std::string_view line, std::size_t index);
bool readCurveEntryLine(std::string_view line, CurveTableEntry& entry,
                        std::span<const CurveTableEntry> earlier);

} // namespace cncc::ir
