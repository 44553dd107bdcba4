// The IR's stable text form, for --emit=ir, --print-after and golden tests,
// and its parser (print, parse, print again gives the same text).
#pragma once

#include "cncc/ir/ir.h"

#include <optional>
#include <string>
#include <string_view>

namespace cncc::ir {

// Values are renumbered in print order, so equal functions print equally.
std::string printFunction(const Function& function);

struct ParseError {
  int line = 0;
  std::string message;
};

// The word of a curve table entry's sampling in the text ("chords",
// "samples", "spacing"), and back; nullopt for another word.
std::string_view curveSamplingName(CurveSampling sampling);
std::optional<CurveSampling> curveSamplingNamed(std::string_view name);

// Parses the text printFunction writes; nullopt and `error` on bad input.
std::optional<Function> parseFunction(std::string_view text, ParseError& error);

} // namespace cncc::ir
