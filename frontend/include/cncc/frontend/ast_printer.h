// Text dumps of the token stream and of the syntax tree, for `--emit=tokens`
// and `--emit=ast`. Both are golden-test formats: stable, one item per line.
//
// Tokens, one per line:
//   3:9 Number '2.5mm' value=2.5 unit=mm
//   3:15 String '"a\"b"' value="a\"b"
//
// The tree, indented two spaces per level, one node per line: the node's
// kind, its `line:col`, what it holds, its type once the semantic checker has
// set one (`: num`) and, for names, what they resolve to:
//   Name 9:42 depth : num -> part-parameter depth at 2:13
#pragma once

#include "cncc/frontend/ast.h"
#include "cncc/frontend/lexer.h"
#include "cncc/frontend/source_manager.h"

#include <string>
#include <string_view>
#include <vector>

namespace cncc::frontend {

// The identifier of a token kind as written in token_kinds.def ("KwPart").
std::string_view tokenKindName(TokenKind kind);

std::string dumpTokens(const std::vector<Token>& tokens, const SourceManager& sources);

std::string dumpAst(const Module& module, const SourceManager& sources);

} // namespace cncc::frontend
