// The language features, one function per request or notification the
// server answers, each in its own file. They read an Analysis (or the
// document's text) and return the JSON the protocol expects as the result.
#pragma once

#include "cncc/lsp/analysis.h"
#include "cncc/lsp/json_rpc.h"

#include <string>
#include <vector>

namespace cncc::lsp {

// diagnostics.cpp: `textDocument/publishDiagnostics` params. Diagnostics in
// an imported file are shown on the import that brings it in.
Json publishDiagnosticsParams(const Analysis& analysis, long long version);

// hover.cpp: `textDocument/hover`; null where there is nothing to say.
Json hover(const Analysis& analysis, Position position);

// definition.cpp: `textDocument/definition`; a Location or null.
Json definition(const Analysis& analysis, Position position);

// completion.cpp: `textDocument/completion`; a CompletionList.
struct CompletionOptions {
  bool snippets = false;       // the client expands `${1:name}` snippets
  std::string stdlibDirectory; // where `import "std/..."` modules are
};
Json completion(const Analysis& analysis, Position position, const CompletionOptions& options);

// document_symbols.cpp: `textDocument/documentSymbol`; DocumentSymbol[].
Json documentSymbols(const Analysis& analysis);

// formatting.cpp: `textDocument/formatting`; TextEdit[] (empty when the
// text is already formatted or has syntax errors).
Json formatting(const std::string& uri, const std::string& text);

// semantic_tokens.cpp: the legend (for the capabilities) and
// `textDocument/semanticTokens/full`.
Json semanticTokensLegend();
Json semanticTokens(const Analysis& analysis);

} // namespace cncc::lsp
