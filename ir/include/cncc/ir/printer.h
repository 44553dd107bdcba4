// The IR's stable text form, for --emit=ir, --print-after and golden tests,
// and its parser (print, parse, print again gives the same text).
#pragma once

#include "cncc/ir/ir.h"

#include <optional>
#include <string>

namespace cncc::ir {

// Values are renumbered in print order, so equal functions print equally.
std::string printFunction(const Function& function);

struct ParseError {
  int line = 0;
  std::string message;
};

// Parses the text printFunction writes; nullopt and `error` on bad input.
std::optional<Function> parseFunction(std::string_view text, ParseError& error);

} // namespace cncc::ir
