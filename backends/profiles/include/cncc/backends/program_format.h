// The printed program as the machine wants it written (MachineSetup): `N`
// line numbers on its blocks, with the targets of macro jumps renumbered
// with them, and comments kept or dropped, in capitals or as written.
#pragma once

#include "cncc/backends/machine_setup.h"

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::backends {

struct FormattedProgram {
  std::vector<std::string> lines;
  // For each line, the index of the printed line it comes from (dropped
  // comment lines leave gaps).
  std::vector<std::size_t> printedLine;
};

// `lines` as the setup's dialect prints them: a macro jump target is a lone
// `N<label>` block and its jumps end in `GOTO <label>`. Problems (a jump
// target whose number repeats once the numbers wrap) go to `errors`.
FormattedProgram formatProgram(std::vector<std::string> lines, const MachineSetup& setup,
                               std::vector<std::string>& errors);

} // namespace cncc::backends
