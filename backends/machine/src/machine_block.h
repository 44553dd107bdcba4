// Checks of one set-up block of a machine file: its {placeholders}, and
// whether it is a block of the target's dialect (machine_file.h).
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace cncc::backends::machine {

struct BlockProblem {
  std::string code; // "machine-placeholder", "machine-invalid-block", ...
  std::string message;
};

// A problem with the {placeholders} of `pattern`, which may use those
// named in `allowed`.
std::optional<BlockProblem> placeholderProblem(std::string_view pattern,
                                               std::span<const std::string_view> allowed);

// `pattern` with every placeholder replaced by a typical value, so that the
// block can be checked as the printer would write it.
std::string withSampleValues(std::string_view pattern);

// A problem with `block` as a block of `dialect` ("sinumerik" or an ISO
// one) at most `maximumLength` characters long.
std::optional<BlockProblem> blockProblem(std::string_view block, std::string_view dialect,
                                         int maximumLength);

} // namespace cncc::backends::machine
