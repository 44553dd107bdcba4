#include "cncc/frontend/lexer.h"

#include "scanner.h"

#include <array>
#include <charconv>
#include <cstdint>
#include <fmt/format.h>
#include <numbers>
#include <optional>

namespace cncc::frontend {

std::string_view tokenSpelling(TokenKind kind) {
  switch (kind) {
#define CNCC_TOKEN(identifier, spelling)                                                           \
  case TokenKind::identifier:                                                                      \
    return spelling;
#include "cncc/frontend/token_kinds.def"
  }
  return "token";
}

std::string_view unitSuffixSpelling(UnitSuffix unit) {
  switch (unit) {
  case UnitSuffix::None:
    return "";
  case UnitSuffix::Millimetre:
    return "mm";
  case UnitSuffix::Inch:
    return "in";
  case UnitSuffix::Degree:
    return "deg";
  case UnitSuffix::Radian:
    return "rad";
  }
  return "";
}

std::vector<Token> lex(const SourceManager& sources, FileId file, DiagnosticEngine& diagnostics,
                       std::vector<SourceSpan>* comments) {
  auto size = static_cast<std::uint32_t>(sources.file(file).text().size());
  return lexRange(sources, file, 0, size, diagnostics, comments);
}

std::vector<Token> lexRange(const SourceManager& sources, FileId file, std::uint32_t begin,
                            std::uint32_t end, DiagnosticEngine& diagnostics,
                            std::vector<SourceSpan>* comments) {
  Scanner scanner(sources, file, begin, end, diagnostics, comments);
  std::vector<Token> tokens;
  // Dense sources hold about one token per 3 bytes.
  tokens.reserve(scanner.remaining() / 2 + 16);
  do {
    tokens.push_back(scanner.read());
  } while (tokens.back().kind != TokenKind::EndOfFile);
  return tokens;
}

} // namespace cncc::frontend
