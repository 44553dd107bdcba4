// The lexer: source text to tokens. Errors are reported and lexing goes on,
// so the parser always sees a complete token stream ending in EndOfFile.
#pragma once

#include "cncc/frontend/diagnostics.h"
#include "cncc/frontend/source_manager.h"

#include <string>
#include <string_view>
#include <vector>

namespace cncc::frontend {

enum class TokenKind : std::uint8_t {
#define CNCC_TOKEN(identifier, spelling) identifier,
#include "cncc/frontend/token_kinds.def"
};

// How a unit suffix scales a number ("2.5mm", "45deg"): to millimetres and
// radians.
enum class UnitSuffix : std::uint8_t { None, Millimetre, Inch, Degree, Radian };

struct Token {
  TokenKind kind = TokenKind::EndOfFile;
  UnitSuffix unit = UnitSuffix::None;
  // The first token on its line (used for error recovery).
  bool startsLine = false;
  SourceSpan span;
  // Number: the value with its unit applied.
  double number = 0;
  // Identifier and keywords: the spelling; String: the unescaped text. A view
  // into the source file, which the SourceManager keeps for as long as it
  // lives (a string with escapes views its unescaped copy kept by the file).
  std::string_view text;
};

std::string_view tokenSpelling(TokenKind kind);
std::string_view unitSuffixSpelling(UnitSuffix unit);

// Lexes one file. Comments are skipped; they are kept (as spans) in
// `comments` when asked, for the formatter.
std::vector<Token> lex(const SourceManager& sources, FileId file, DiagnosticEngine& diagnostics,
                       std::vector<SourceSpan>* comments = nullptr);
// Lexes the bytes [begin, end) of one file as if they were the whole file:
// spans keep the file's offsets, the first token starts a line and
// EndOfFile is at `end`. lex() is lexRange() of [0, size).
std::vector<Token> lexRange(const SourceManager& sources, FileId file, std::uint32_t begin,
                            std::uint32_t end, DiagnosticEngine& diagnostics,
                            std::vector<SourceSpan>* comments = nullptr);

} // namespace cncc::frontend
