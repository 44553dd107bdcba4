// Plain ISO G-code: the tool path the IR produced on the host, as G00/G01
// and G02/G03 blocks with modal coordinates.
#pragma once

#include "cncc/backends/line_spans.h"
#include "cncc/backends/machine_setup.h"
#include "cncc/ir/tool_path.h"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::backends {

struct GcodeOptions {
  int programNumber = 1;  // O<number>
  std::string sourceName; // for the header comment, e.g. "s_profile.cdl"
  std::string partName;   // for the header comment
  bool inches = false;    // G20 instead of G21
  int decimals = 4;       // the most decimals a number is printed with
  MachineSetup setup = builtinMachineSetup("gcode");
};

// `10.`, `0.5`, `-1.25`: at most `decimals` decimals, no trailing zeros, always
// a decimal point, never `-0.`.
std::string formatGcodeNumber(double value, int decimals);

// A comment's text for `( ... )`: printable, without parentheses (the
// machine's comment case is applied to the whole program, program_format.h).
std::string gcodeCommentText(std::string_view text);

// The program number that an output file name gives: `O1234` (any directory,
// any extension) gives 1234; nothing else gives one.
std::optional<int> programNumberFromFileName(std::string_view path);

std::string writeGcode(const ir::ToolPath& path, const GcodeOptions& options);

struct GcodeProgram {
  std::string text;
  // Where each line of `text` was printed from.
  LineOrigins lineOrigins;
};
// The same program, with where each line comes from.
GcodeProgram writeGcodeProgram(const ir::ToolPath& path, const GcodeOptions& options);

} // namespace cncc::backends
