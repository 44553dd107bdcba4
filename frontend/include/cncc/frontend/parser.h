// The recursive-descent parser: tokens to a Module.
//
// Errors never stop it. After the first error in a statement or item it is
// "panicking": later errors are suppressed until it resynchronises at the
// next statement or item boundary, so one typo gives one message. What could
// not be parsed becomes an Error node; everything else is kept.
#pragma once

#include "cncc/frontend/ast.h"
#include "cncc/frontend/diagnostics.h"
#include "cncc/frontend/lexer.h"

#include <vector>

namespace cncc::frontend {

// Deeper nesting than this is an error rather than a stack overflow.
inline constexpr int maximumNestingDepth = 200;
// Likewise for a chain of binary operators such as 1 + 1 + ... + 1.
inline constexpr int maximumChainLength = 2000;

Module parse(std::vector<Token> tokens, FileId file, DiagnosticEngine& diagnostics);

// Lexes and parses one file of `sources`.
Module parseFile(const SourceManager& sources, FileId file, DiagnosticEngine& diagnostics);

// Parses only the bytes [begin, end) of the file as if they were the whole
// file (see lexRange). parseFile() is parseFileRange() of [0, size).
Module parseFileRange(const SourceManager& sources, FileId file, std::uint32_t begin,
                      std::uint32_t end, DiagnosticEngine& diagnostics);

} // namespace cncc::frontend
