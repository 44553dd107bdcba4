// The lexer: source text to tokens. Errors are reported and lexing goes on,
// so the parser always sees a complete token stream ending in EndOfFile.
#pragma once

#include "cncc/frontend/diagnostics.h"
#include "cncc/frontend/source_manager.h"

#include <string>
#include <string_view>
#include <vector>

namespace cncc::frontend {

enum class TokenKind {
#define CNCC_TOKEN(identifier, spelling) identifier,
#include "cncc/frontend/token_kinds.def"
};

// How a unit suffix scales a number ("2.5mm", "45deg"): to millimetres and
// radians.
enum class UnitSuffix { None, Millimetre, Inch, Degree, Radian };

struct Token {
  TokenKind kind = TokenKind::EndOfFile;
  SourceSpan span;
  // Number: the value with its unit applied; String: the unescaped text is in
  // `text`; Identifier and keywords: `text` is the spelling.
  double number = 0;
  UnitSuffix unit = UnitSuffix::None;
  std::string text;
  // The first token on its line (used for error recovery).
  bool startsLine = false;
};

std::string_view tokenSpelling(TokenKind kind);
std::string_view unitSuffixSpelling(UnitSuffix unit);

// Lexes one file. Comments are skipped; they are kept (as spans) in
// `comments` when asked, for the formatter.
std::vector<Token> lex(const SourceManager& sources, FileId file, DiagnosticEngine& diagnostics,
                       std::vector<SourceSpan>* comments = nullptr);

} // namespace cncc::frontend
