// The formatter: a file's syntax tree and comments to its canonical text,
// for `cncc fmt` and the language server.
//
// The layout is a function of the tree and the comments alone, so
// formatting is idempotent, and the output parses to the same tree (its
// spans aside): the formatter only moves whitespace, comments stay where
// they were relative to the code, and parentheses appear exactly where
// precedence needs them. Canonical layout:
//
//  - two spaces of indentation per block; lines of at most 100 columns
//    where a line can break (inside brackets, after `=` of a `fn`, before
//    a `name=value` setting or modifier, after a binary operator);
//  - one item or statement per line; at most one blank line is kept where
//    the source had one, and a `part` always has one around it;
//  - `*`, `/`, `%` and `^` without spaces, every other binary operator and
//    `..` with a space each side: `a + b*t`, `(x - 8)/2`, `0 .. 2*pi`;
//  - `name=value` for call arguments, statement settings and modifiers,
//    but ` = ` for every named argument of a call where one value has a
//    spaced operator: `polar(r = a + b*t, t = 0 .. 2*pi)`; and
//    `name = default` for parameters;
//  - a comment at the end of a line stays at the end of its line; one on a
//    line of its own stays on a line of its own, indented like the code.
//
// A file with syntax errors is not formatted: its diagnostics are reported
// and nothing is returned.
#pragma once

#include "cncc/frontend/diagnostics.h"
#include "cncc/frontend/source_manager.h"

#include <optional>
#include <string>

namespace cncc::frontend {

struct FormatOptions {
  int lineWidth = 100;
  int indentWidth = 2;
};

// The canonical text of `file`, or nullopt when lexing or parsing it
// reported an error (the diagnostics say why).
std::optional<std::string> formatFile(const SourceManager& sources, FileId file,
                                      DiagnosticEngine& diagnostics,
                                      const FormatOptions& options = {});

} // namespace cncc::frontend
