#include "cncc/frontend/lexer.h"

#include <charconv>
#include <fmt/format.h>
#include <numbers>

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

namespace {

bool isIdentifierStart(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
bool isDigit(char c) {
  return c >= '0' && c <= '9';
}
bool isIdentifierContinue(char c) {
  return isIdentifierStart(c) || isDigit(c);
}

struct Keyword {
  std::string_view spelling;
  TokenKind kind;
};

constexpr Keyword keywords[] = {
#define CNCC_KEYWORD(identifier, spelling) {spelling, TokenKind::identifier},
#include "cncc/frontend/token_kinds.def"
};

class Lexer {
public:
  Lexer(const SourceManager& sources, FileId file, DiagnosticEngine& diagnostics,
        std::vector<SourceSpan>* comments)
      : file_(file), text_(sources.file(file).text()), diagnostics_(diagnostics),
        comments_(comments) {}

  std::vector<Token> run() {
    std::vector<Token> tokens;
    while (true) {
      bool startsLine = skipSpaceAndComments();
      Token token = next();
      token.startsLine = startsLine || tokens.empty();
      bool done = token.kind == TokenKind::EndOfFile;
      tokens.push_back(std::move(token));
      if (done) {
        return tokens;
      }
    }
  }

private:
  char peek(std::size_t ahead = 0) const {
    return position_ + ahead < text_.size() ? text_[position_ + ahead] : '\0';
  }
  bool atEnd() const { return position_ >= text_.size(); }
  SourceSpan spanFrom(std::size_t begin) const {
    return {file_, static_cast<std::uint32_t>(begin), static_cast<std::uint32_t>(position_)};
  }

  // Returns true when a line break was crossed.
  bool skipSpaceAndComments() {
    bool crossedLine = false;
    while (!atEnd()) {
      char c = peek();
      if (c == '\n') {
        crossedLine = true;
        ++position_;
      } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
        ++position_;
      } else if (c == '/' && peek(1) == '/') {
        std::size_t begin = position_;
        while (!atEnd() && peek() != '\n') {
          ++position_;
        }
        recordComment(begin);
      } else if (c == '/' && peek(1) == '*') {
        crossedLine |= skipBlockComment();
      } else {
        break;
      }
    }
    return crossedLine;
  }

  bool skipBlockComment() {
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
          {file_, static_cast<std::uint32_t>(begin), static_cast<std::uint32_t>(begin + 2)},
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

  Token make(TokenKind kind, std::size_t begin) {
    Token token;
    token.kind = kind;
    token.span = spanFrom(begin);
    return token;
  }

  Token next() {
    std::size_t begin = position_;
    if (atEnd()) {
      return make(TokenKind::EndOfFile, begin);
    }
    char c = peek();
    if (isIdentifierStart(c)) {
      return identifier();
    }
    if (isDigit(c) || (c == '.' && isDigit(peek(1)))) {
      return number();
    }
    if (c == '"') {
      return string();
    }
    return punctuator();
  }

  Token identifier() {
    std::size_t begin = position_;
    while (isIdentifierContinue(peek())) {
      ++position_;
    }
    std::string_view spelling = text_.substr(begin, position_ - begin);
    TokenKind kind = TokenKind::Identifier;
    for (const Keyword& keyword : keywords) {
      if (keyword.spelling == spelling) {
        kind = keyword.kind;
      }
    }
    Token token = make(kind, begin);
    token.text = std::string(spelling);
    return token;
  }

  void skipDigits() {
    while (isDigit(peek())) {
      ++position_;
    }
  }

  Token number() {
    std::size_t begin = position_;
    skipDigits();
    // "1..5" is a range, not "1." followed by ".5".
    if (peek() == '.' && peek(1) != '.') {
      ++position_;
      skipDigits();
    }
    bool malformed = false;
    if ((peek() == 'e' || peek() == 'E') &&
        (isDigit(peek(1)) || ((peek(1) == '+' || peek(1) == '-') && isDigit(peek(2))))) {
      position_ += isDigit(peek(1)) ? 1 : 2;
      skipDigits();
    } else if ((peek() == 'e' || peek() == 'E') && !isIdentifierContinue(peek(1))) {
      // "2e" or "2e+" with no exponent digits.
      ++position_;
      if (peek() == '+' || peek() == '-') {
        ++position_;
      }
      malformed = true;
    }
    std::string_view digits = text_.substr(begin, position_ - begin);
    Token token = make(TokenKind::Number, begin);
    if (malformed) {
      diagnostics_.report(DiagnosticKind::MalformedNumber, token.span,
                          fmt::format("exponent of '{}' has no digits", digits));
      token.kind = TokenKind::Error;
      return token;
    }
    auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), token.number);
    if (error != std::errc() || end != digits.data() + digits.size()) {
      diagnostics_.report(DiagnosticKind::MalformedNumber, token.span,
                          fmt::format("number '{}' is out of range", digits));
      token.kind = TokenKind::Error;
      return token;
    }
    if (isIdentifierStart(peek())) {
      applyUnitSuffix(token);
    }
    return token;
  }

  void applyUnitSuffix(Token& token) {
    std::size_t suffixBegin = position_;
    while (isIdentifierContinue(peek())) {
      ++position_;
    }
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

  Token string() {
    std::size_t begin = position_;
    ++position_;
    std::string value;
    bool invalid = false; // the parser must not act on a string with an error
    while (!atEnd() && peek() != '"' && peek() != '\n') {
      if (peek() == '\\') {
        char escaped = peek(1);
        if (escaped == '"' || escaped == '\\') {
          value.push_back(escaped);
          position_ += 2;
          continue;
        }
        std::size_t escapeBegin = position_;
        position_ += (escaped == '\0' || escaped == '\n') ? 1 : 2;
        invalid = true;
        diagnostics_.report(DiagnosticKind::InvalidEscape, spanFrom(escapeBegin),
                            "invalid escape in string; only '\\\"' and '\\\\' are allowed");
        continue;
      }
      value.push_back(peek());
      ++position_;
    }
    if (peek() != '"') {
      Token token = make(TokenKind::String, begin);
      diagnostics_.report(DiagnosticKind::UnterminatedString, token.span,
                          "string is not closed; expected '\"' before the end of the line");
      token.kind = TokenKind::Error;
      return token;
    }
    ++position_;
    Token token = make(invalid ? TokenKind::Error : TokenKind::String, begin);
    token.text = std::move(value);
    return token;
  }

  Token punctuator() {
    std::size_t begin = position_;
    char c = peek();
    char following = peek(1);
    auto two = [&](TokenKind kind) {
      position_ += 2;
      return make(kind, begin);
    };
    auto one = [&](TokenKind kind) {
      position_ += 1;
      return make(kind, begin);
    };
    switch (c) {
    case '(':
      return one(TokenKind::LeftParen);
    case ')':
      return one(TokenKind::RightParen);
    case '[':
      return one(TokenKind::LeftBracket);
    case ']':
      return one(TokenKind::RightBracket);
    case '{':
      return one(TokenKind::LeftBrace);
    case '}':
      return one(TokenKind::RightBrace);
    case ',':
      return one(TokenKind::Comma);
    case ';':
      return one(TokenKind::Semicolon);
    case '.':
      return following == '.' ? two(TokenKind::DotDot) : one(TokenKind::Dot);
    case '+':
      return one(TokenKind::Plus);
    case '-':
      return one(TokenKind::Minus);
    case '*':
      return one(TokenKind::Star);
    case '/':
      return one(TokenKind::Slash);
    case '%':
      return one(TokenKind::Percent);
    case '^':
      return one(TokenKind::Caret);
    case '=':
      return following == '=' ? two(TokenKind::EqualEqual) : one(TokenKind::Equal);
    case '!':
      return following == '=' ? two(TokenKind::BangEqual) : one(TokenKind::Bang);
    case '<':
      return following == '=' ? two(TokenKind::LessEqual) : one(TokenKind::Less);
    case '>':
      return following == '=' ? two(TokenKind::GreaterEqual) : one(TokenKind::Greater);
    case '&':
      if (following == '&') {
        return two(TokenKind::AmpAmp);
      }
      break;
    case '|':
      if (following == '|') {
        return two(TokenKind::PipePipe);
      }
      break;
    default:
      break;
    }
    return unexpectedCharacters();
  }

  static bool startsToken(char c) {
    return isIdentifierContinue(c) || c == '"' || c == ' ' || c == '\t' || c == '\n' || c == '\r' ||
           std::string_view("()[]{},;.+-*/%^=!<>").find(c) != std::string_view::npos;
  }

  // A run of characters that start no token is one error, not one per byte.
  Token unexpectedCharacters() {
    std::size_t begin = position_;
    ++position_;
    while (!atEnd() && !startsToken(peek())) {
      ++position_;
    }
    Token token = make(TokenKind::Error, begin);
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
    return token;
  }

  FileId file_;
  std::string_view text_;
  DiagnosticEngine& diagnostics_;
  std::vector<SourceSpan>* comments_;
  std::size_t position_ = 0;
};

} // namespace

std::vector<Token> lex(const SourceManager& sources, FileId file, DiagnosticEngine& diagnostics,
                       std::vector<SourceSpan>* comments) {
  return Lexer(sources, file, diagnostics, comments).run();
}

} // namespace cncc::frontend
