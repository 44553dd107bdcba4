// The function's cut table as IR text: a `cut @n ...` line per cut, after
// the curve table, that printer.cpp writes and parser.cpp reads. The cut's
// curves (what verify measures against, what plots draw) and its source
// span are not text: a cut read back has none.
#pragma once

#include "cncc/ir/cut_geometry.h"

#include <string>
#include <string_view>

namespace cncc::ir {

// `  cut @n tolerance T [method M] [arcs native|fitted] [beside R]
// [blocks "how the spline blocks were found"]`
std::string cutEntryText(std::size_t index, const CutGeometry& cut);

// Reads the line of cut `index` (trimmed); throws text::Failure.
CutGeometry readCutEntry(std::string_view line, std::size_t index);

} // namespace cncc::ir
