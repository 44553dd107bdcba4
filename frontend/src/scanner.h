// The lexer's state over one range of a file, read one token at a time:
// lex() collects the tokens into a vector, the parser pulls them as it goes
// (private to the front end; inline so the parser's loop includes it).
#pragma once

#include "cncc/frontend/lexer.h"
#include "spelling_table.h"

#include <array>
#include <charconv>
#include <cstdint>
#include <fmt/format.h>
#include <numbers>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::frontend {

namespace scanning {

// Character classes, one table look-up per byte in the loops below.
enum CharacterClass : std::uint8_t {
  Space = 1,           // ' ', '\t', '\r', '\f', '\v'
  IdentifierStart = 2, // a-z, A-Z, '_'
  Digit = 4,           // 0-9
  IdentifierContinue = IdentifierStart | Digit,
  LineBreak = 8, // '\n'
  SpaceOrLineBreak = Space | LineBreak,
};

inline constexpr std::array<std::uint8_t, 256> characterClasses = [] {
  std::array<std::uint8_t, 256> classes{};
  for (unsigned char c : {' ', '\t', '\r', '\f', '\v'}) {
    classes[c] = Space;
  }
  classes['\n'] = LineBreak;
  for (int c = 'a'; c <= 'z'; ++c) {
    classes[static_cast<std::size_t>(c)] = IdentifierStart;
    classes[static_cast<std::size_t>(c - 'a' + 'A')] = IdentifierStart;
  }
  classes['_'] = IdentifierStart;
  for (int c = '0'; c <= '9'; ++c) {
    classes[static_cast<std::size_t>(c)] = Digit;
  }
  return classes;
}();

inline bool hasClass(char c, std::uint8_t characterClass) {
  return (characterClasses[static_cast<unsigned char>(c)] & characterClass) != 0;
}
inline bool isIdentifierStart(char c) {
  return hasClass(c, IdentifierStart);
}
inline bool isDigit(char c) {
  return hasClass(c, Digit);
}
inline bool isIdentifierContinue(char c) {
  return hasClass(c, IdentifierContinue);
}

struct Keyword {
  std::string_view spelling;
  TokenKind kind;
};

inline constexpr Keyword keywords[] = {
#define CNCC_KEYWORD(identifier, spelling) {spelling, TokenKind::identifier},
#include "cncc/frontend/token_kinds.def"
};

inline constexpr std::size_t longestKeyword = 6;
inline constexpr SpellingTable<longestKeyword> keywordTable = makeSpellingTable<longestKeyword>(
    std::size(keywords), [](std::size_t i) { return keywords[i].spelling; });

// Compared in a loop: a keyword is a few letters, fewer than a call costs.
inline bool isKeyword(std::string_view spelling, std::uint8_t candidate) {
  if (candidate == 0) {
    return false;
  }
  std::string_view keyword = keywords[candidate - 1].spelling;
  for (std::size_t i = 1; i < spelling.size(); ++i) {
    if (spelling[i] != keyword[i]) {
      return false;
    }
  }
  return true; // the length and first letter chose the candidate
}

inline TokenKind keywordOrIdentifier(std::string_view spelling) {
  const SpellingCandidates* candidates = spellingCandidates(keywordTable, spelling);
  if (candidates == nullptr) {
    return TokenKind::Identifier;
  }
  if (isKeyword(spelling, candidates->first)) {
    return keywords[candidates->first - 1].kind;
  }
  if (isKeyword(spelling, candidates->second)) {
    return keywords[candidates->second - 1].kind;
  }
  return TokenKind::Identifier;
}

// What a byte starts as a punctuator: its one-byte token (Error: none) and
// the two-byte one when the next byte is `second` ("==", "..", "&&").
struct PunctuatorStart {
  TokenKind single = TokenKind::Error;
  char second = '\0';
  TokenKind pair = TokenKind::Error;
};

inline constexpr std::array<PunctuatorStart, 256> punctuatorStarts = [] {
  struct Punctuator {
    std::string_view spelling;
    TokenKind kind;
  };
  constexpr Punctuator punctuators[] = {
#define CNCC_PUNCTUATOR(identifier, spelling) {spelling, TokenKind::identifier},
#include "cncc/frontend/token_kinds.def"
  };
  std::array<PunctuatorStart, 256> starts{};
  for (const Punctuator& punctuator : punctuators) {
    PunctuatorStart& start = starts[static_cast<unsigned char>(punctuator.spelling[0])];
    if (punctuator.spelling.size() == 1) {
      start.single = punctuator.kind;
    } else {
      start.second = punctuator.spelling[1];
      start.pair = punctuator.kind;
    }
  }
  return starts;
}();

// Exact decimal to double when the digits fit a double's mantissa and the
// power of ten is exact (both operands exact, so the one division rounds
// correctly, as std::from_chars does); nullopt sends the rest to from_chars.
inline std::optional<double> fastDecimal(std::string_view digits) {
  static constexpr double powersOfTen[] = {1e0, 1e1, 1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                           1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};
  std::uint64_t mantissa = 0;
  int significant = 0;
  int fractionDigits = 0;
  bool inFraction = false;
  for (char c : digits) {
    if (c == '.') {
      inFraction = true;
      continue;
    }
    if (!isDigit(c)) {
      return std::nullopt; // an exponent
    }
    if (mantissa != 0 || c != '0') {
      ++significant;
    }
    mantissa = mantissa * 10 + static_cast<std::uint64_t>(c - '0');
    fractionDigits += inFraction ? 1 : 0;
  }
  if (significant > 15 || fractionDigits > 15) {
    return std::nullopt;
  }
  return static_cast<double>(mantissa) / powersOfTen[fractionDigits];
}

} // namespace scanning

class Scanner {
public:
  // Lexes the bytes [begin, end) of the file as if they were all of it: the
  // text ends at `end`, offsets stay those of the file.
  Scanner(const SourceManager& sources, FileId file, std::uint32_t begin, std::uint32_t end,
          DiagnosticEngine& diagnostics, std::vector<SourceSpan>* comments)
      : fileId_(file), file_(sources.file(file)), text_(file_.text().substr(0, end)),
        diagnostics_(diagnostics), comments_(comments), position_(begin) {}

  // The next token; after the last one, EndOfFile at the end of the range
  // (every call). Lexer diagnostics are reported as their tokens are read.
  // Scanned into a fresh local token, so that a field a kind does not use
  // keeps its default, and stores to it cannot alias the scanner's members,
  // which then stay in registers.
  Token read() {
    Token scanned;
    scanned.startsLine = skipSpaceAndComments();
    next(scanned);
    return scanned;
  }
  void read(Token& token) { token = read(); }

  // The bytes left to read, for sizing a vector of the tokens.
  std::size_t remaining() const { return text_.size() - position_; }

private:
  char peek(std::size_t ahead = 0) const {
    return position_ + ahead < text_.size() ? text_[position_ + ahead] : '\0';
  }
  bool atEnd() const { return position_ >= text_.size(); }
  SourceSpan spanFrom(std::size_t begin) const {
    return {fileId_, static_cast<std::uint32_t>(begin), static_cast<std::uint32_t>(position_)};
  }

  // Returns true when a line break was crossed or this is the first token.
  bool skipSpaceAndComments() {
    bool crossedLine = first_;
    first_ = false;
    const std::size_t size = text_.size();
    const char* text = text_.data();
    std::size_t position = position_;
    while (position < size) {
      // Spaces and line breaks one class look-up each, the usual case.
      std::uint8_t characterClass =
          scanning::characterClasses[static_cast<unsigned char>(text[position])];
      if ((characterClass & scanning::SpaceOrLineBreak) != 0) {
        crossedLine |= (characterClass & scanning::LineBreak) != 0;
        ++position;
        continue;
      }
      if (text[position] != '/' || position + 1 == size) {
        break;
      }
      char following = text[position + 1];
      if (following == '/') {
        std::size_t lineEnd = text_.find('\n', position);
        position_ = lineEnd == std::string_view::npos ? size : lineEnd;
        recordComment(position);
      } else if (following == '*') {
        position_ = position;
        crossedLine |= skipBlockComment();
      } else {
        break;
      }
      position = position_;
    }
    position_ = position;
    return crossedLine;
  }

  [[gnu::noinline]] bool skipBlockComment() {
    std::size_t begin = position_;
    bool crossedLine = false;
    position_ += 2;
    while (!atEnd() && !(peek() == '*' && peek(1) == '/')) {
      crossedLine |= peek() == '\n';
      ++position_;
    }
    if (atEnd()) {
      diagnostics_.report(
          DiagnosticKind::UnterminatedComment,
          {fileId_, static_cast<std::uint32_t>(begin), static_cast<std::uint32_t>(begin + 2)},
          "block comment is not closed; expected '*/' before the end of the file");
    } else {
      position_ += 2;
    }
    recordComment(begin);
    return crossedLine;
  }

  void recordComment(std::size_t begin) {
    if (comments_ != nullptr) {
      comments_->push_back(spanFrom(begin));
    }
  }

  void make(Token& token, TokenKind kind, std::size_t begin) {
    token.kind = kind;
    token.span = spanFrom(begin);
  }

  void makeNumber(Token& token, std::size_t begin, double value) {
    make(token, TokenKind::Number, begin);
    token.number = value;
  }

  void next(Token& token) {
    std::size_t begin = position_;
    if (begin >= text_.size()) {
      make(token, TokenKind::EndOfFile, begin);
      return;
    }
    char c = text_[begin];
    std::uint8_t characterClass = scanning::characterClasses[static_cast<unsigned char>(c)];
    if ((characterClass & scanning::IdentifierStart) != 0) {
      identifier(token);
    } else if ((characterClass & scanning::Digit) != 0 ||
               (c == '.' && scanning::isDigit(peek(1)))) {
      number(token);
    } else if (c == '"') {
      string(token);
    } else {
      punctuator(token);
    }
  }

  void skipIdentifierCharacters() {
    const std::size_t size = text_.size();
    while (position_ < size && scanning::isIdentifierContinue(text_[position_])) {
      ++position_;
    }
  }

  void identifier(Token& token) {
    const std::size_t begin = position_;
    const std::size_t size = text_.size();
    const char* text = text_.data();
    std::size_t position = begin + 1;
    while (position < size && scanning::isIdentifierContinue(text[position])) {
      ++position;
    }
    position_ = position;
    std::string_view spelling(text + begin, position - begin);
    make(token, scanning::keywordOrIdentifier(spelling), begin);
    token.text = spelling;
  }

  void skipDigits() {
    const std::size_t size = text_.size();
    while (position_ < size && scanning::isDigit(text_[position_])) {
      ++position_;
    }
  }

  // Digits with an optional fraction and unit, the usual number, are
  // converted as they are read; the rest (an exponent, many digits) take the
  // general path below.
  void number(Token& token) {
    static constexpr double powersOfTen[] = {1e0, 1e1, 1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                             1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15};
    const std::size_t begin = position_;
    const std::size_t size = text_.size();
    const char* text = text_.data();
    std::size_t position = begin;
    std::uint64_t mantissa = 0;
    auto digits = [&] {
      while (position < size && scanning::isDigit(text[position])) {
        mantissa = mantissa * 10 + static_cast<std::uint64_t>(text[position] - '0');
        ++position;
      }
    };
    digits();
    std::size_t integerDigits = position - begin;
    std::size_t fractionBegin = position;
    // "1..5" is a range, not "1." followed by ".5".
    if (position < size && text[position] == '.' &&
        !(position + 1 < size && text[position + 1] == '.')) {
      ++position;
      fractionBegin = position;
      digits();
    }
    std::size_t fractionDigits = position - fractionBegin;
    char following = position < size ? text[position] : '\0';
    // At most 15 digits keep the mantissa and the power of ten exact; longer
    // ones (leading zeros too) are left to the general path, which converts
    // the same way when they allow it.
    if (following == 'e' || following == 'E' || integerDigits + fractionDigits > 15) {
      generalNumber(token);
      return;
    }
    position_ = position;
    makeNumber(token, begin, static_cast<double>(mantissa) / powersOfTen[fractionDigits]);
    if (scanning::isIdentifierStart(following)) {
      applyUnitSuffix(token);
    }
  }

  [[gnu::noinline]] void generalNumber(Token& token) {
    std::size_t begin = position_;
    skipDigits();
    // "1..5" is a range, not "1." followed by ".5".
    if (peek() == '.' && peek(1) != '.') {
      ++position_;
      skipDigits();
    }
    bool malformed = false;
    if ((peek() == 'e' || peek() == 'E') &&
        (scanning::isDigit(peek(1)) ||
         ((peek(1) == '+' || peek(1) == '-') && scanning::isDigit(peek(2))))) {
      position_ += scanning::isDigit(peek(1)) ? 1 : 2;
      skipDigits();
    } else if ((peek() == 'e' || peek() == 'E') && !scanning::isIdentifierContinue(peek(1))) {
      // "2e" or "2e+" with no exponent digits.
      ++position_;
      if (peek() == '+' || peek() == '-') {
        ++position_;
      }
      malformed = true;
    }
    std::string_view digits = text_.substr(begin, position_ - begin);
    make(token, TokenKind::Number, begin);
    if (malformed) {
      diagnostics_.report(DiagnosticKind::MalformedNumber, token.span,
                          fmt::format("exponent of '{}' has no digits", digits));
      token.kind = TokenKind::Error;
      return;
    }
    if (std::optional<double> value = scanning::fastDecimal(digits)) {
      token.number = *value;
    } else {
      auto [end, error] =
          std::from_chars(digits.data(), digits.data() + digits.size(), token.number);
      if (error != std::errc() || end != digits.data() + digits.size()) {
        diagnostics_.report(DiagnosticKind::MalformedNumber, token.span,
                            fmt::format("number '{}' is out of range", digits));
        token.kind = TokenKind::Error;
        return;
      }
    }
    if (scanning::isIdentifierStart(peek())) {
      applyUnitSuffix(token);
    }
  }

  [[gnu::noinline]] void applyUnitSuffix(Token& token) {
    std::size_t suffixBegin = position_;
    skipIdentifierCharacters();
    std::string_view suffix = text_.substr(suffixBegin, position_ - suffixBegin);
    token.span = spanFrom(token.span.begin);
    if (suffix == "mm") {
      token.unit = UnitSuffix::Millimetre;
    } else if (suffix == "in") {
      token.unit = UnitSuffix::Inch;
      token.number *= 25.4;
    } else if (suffix == "deg") {
      token.unit = UnitSuffix::Degree;
      token.number *= std::numbers::pi / 180.0;
    } else if (suffix == "rad") {
      token.unit = UnitSuffix::Radian;
    } else {
      diagnostics_.report(DiagnosticKind::UnknownUnitSuffix, spanFrom(suffixBegin),
                          fmt::format("unknown unit '{}' after a number; expected mm, in, deg "
                                      "or rad (or a space before a name)",
                                      suffix));
      token.kind = TokenKind::Error;
    }
  }

  [[gnu::noinline]] void string(Token& token) {
    std::size_t begin = position_;
    ++position_;
    std::string value;
    bool escaped = false;
    bool invalid = false; // the parser must not act on a string with an error
    while (!atEnd() && peek() != '"' && peek() != '\n') {
      if (peek() == '\\') {
        char escapedCharacter = peek(1);
        if (!escaped) {
          // The text so far had no escape: copy it once.
          value.assign(text_.substr(begin + 1, position_ - begin - 1));
          escaped = true;
        }
        if (escapedCharacter == '"' || escapedCharacter == '\\') {
          value.push_back(escapedCharacter);
          position_ += 2;
          continue;
        }
        std::size_t escapeBegin = position_;
        position_ += (escapedCharacter == '\0' || escapedCharacter == '\n') ? 1 : 2;
        invalid = true;
        diagnostics_.report(DiagnosticKind::InvalidEscape, spanFrom(escapeBegin),
                            "invalid escape in string; only '\\\"' and '\\\\' are allowed");
        continue;
      }
      if (escaped) {
        value.push_back(peek());
      }
      ++position_;
    }
    if (peek() != '"') {
      make(token, TokenKind::String, begin);
      diagnostics_.report(DiagnosticKind::UnterminatedString, token.span,
                          "string is not closed; expected '\"' before the end of the line");
      token.kind = TokenKind::Error;
      return;
    }
    std::size_t contentEnd = position_;
    ++position_;
    make(token, invalid ? TokenKind::Error : TokenKind::String, begin);
    if (invalid) {
      return;
    }
    if (escaped) {
      token.text = file_.keepUnescaped(static_cast<std::uint32_t>(begin), std::move(value));
    } else {
      token.text = text_.substr(begin + 1, contentEnd - begin - 1);
    }
  }

  // One table look-up: the punctuators are a byte or two.
  void punctuator(Token& token) {
    std::size_t begin = position_;
    const scanning::PunctuatorStart& start =
        scanning::punctuatorStarts[static_cast<unsigned char>(text_[begin])];
    if (start.second != '\0' && peek(1) == start.second) {
      position_ += 2;
      make(token, start.pair, begin);
      return;
    }
    if (start.single != TokenKind::Error) {
      position_ += 1;
      make(token, start.single, begin);
      return;
    }
    unexpectedCharacters(token);
  }

  static bool startsToken(char c) {
    return scanning::isIdentifierContinue(c) || c == '"' || c == ' ' || c == '\t' || c == '\n' ||
           c == '\r' || std::string_view("()[]{},;.+-*/%^=!<>").find(c) != std::string_view::npos;
  }

  // A run of characters that start no token is one error, not one per byte.
  [[gnu::noinline]] void unexpectedCharacters(Token& token) {
    std::size_t begin = position_;
    ++position_;
    while (!atEnd() && !startsToken(peek())) {
      ++position_;
    }
    make(token, TokenKind::Error, begin);
    std::string_view run = text_.substr(begin, position_ - begin);
    std::string message;
    if (run == "&") {
      message = "unexpected character '&'; did you mean '&&'?";
    } else if (run == "|") {
      message = "unexpected character '|'; did you mean '||'?";
    } else if (static_cast<unsigned char>(run[0]) >= 0x80) {
      message = "unexpected non-ASCII character; CDL source is ASCII outside strings and comments";
    } else {
      unsigned char first = static_cast<unsigned char>(run[0]);
      message = first >= 0x20 && first < 0x7f
                    ? fmt::format("unexpected character '{}'", run.substr(0, 1))
                    : fmt::format("unexpected control character 0x{:02x}", first);
    }
    diagnostics_.report(DiagnosticKind::UnexpectedCharacter, token.span, std::move(message));
  }

  FileId fileId_;
  const SourceFile& file_;
  std::string_view text_;
  DiagnosticEngine& diagnostics_;
  std::vector<SourceSpan>* comments_;
  std::size_t position_ = 0;
  bool first_ = true;
};

} // namespace cncc::frontend
