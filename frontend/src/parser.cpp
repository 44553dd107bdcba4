#include "cncc/frontend/parser.h"

#include "node_arena.h"
#include "scanner.h"

#include <algorithm>
#include <array>
#include <deque>
#include <fmt/format.h>
#include <iterator>
#include <limits>
#include <optional>

namespace cncc::frontend {

namespace {

bool isStatementWord(const Token& token) {
  if (token.kind != TokenKind::Identifier) {
    return false;
  }
  std::string_view word = token.text;
  return word == "units" || word == "tool" || word == "feed" || word == "spindle" ||
         word == "safe" || word == "origin" || word == "coolant";
}

// The extended work offsets `G54.1 P1` .. `G54.1 P300`.
constexpr int maximumExtendedOffset = 300;

// 54 .. 59 for `G54` .. `G59`, else 0.
int workOffsetGroup(std::string_view word) {
  if (word.size() != 3 || word[0] != 'G' || word[1] != '5' || word[2] < '4' || word[2] > '9') {
    return 0;
  }
  return 50 + (word[2] - '0');
}

// Whether `token` is the `.1` of `G54.1` (the lexer reads `G54.1` as the name
// G54 and the number .1).
bool isPointOne(const Token& token) {
  return token.kind == TokenKind::Number && token.unit == UnitSuffix::None && token.number == 0.1 &&
         token.span.end - token.span.begin == 2;
}

// n of the word `Pn` (one to four digits), or -1 when the word is not one.
int extendedOffsetNumber(std::string_view word) {
  if (word.size() < 2 || word.size() > 5 || word[0] != 'P') {
    return -1;
  }
  int number = 0;
  for (char digit : word.substr(1)) {
    if (digit < '0' || digit > '9') {
      return -1;
    }
    number = number * 10 + (digit - '0');
  }
  return number;
}

std::optional<CoolantMode> coolantModeNamed(std::string_view word) {
  for (CoolantMode mode :
       {CoolantMode::Flood, CoolantMode::Mist, CoolantMode::Through, CoolantMode::Off}) {
    if (coolantModeSpelling(mode) == word) {
      return mode;
    }
  }
  return std::nullopt;
}

bool isModifierName(std::string_view word) {
  const std::vector<std::string>& names = cutModifierNames();
  return std::find(names.begin(), names.end(), word) != names.end();
}

bool isItemKeyword(TokenKind kind) {
  return kind == TokenKind::KwPart || kind == TokenKind::KwFn || kind == TokenKind::KwConst ||
         kind == TokenKind::KwImport;
}

bool isStatementKeyword(TokenKind kind) {
  return kind == TokenKind::KwLet || kind == TokenKind::KwCurve || kind == TokenKind::KwFor ||
         kind == TokenKind::KwIf;
}

std::string describe(const Token& token) {
  switch (token.kind) {
  case TokenKind::Identifier:
    return fmt::format("'{}'", token.text);
  case TokenKind::Number:
  case TokenKind::String:
  case TokenKind::EndOfFile:
  case TokenKind::Error:
    return std::string(tokenSpelling(token.kind));
  default:
    return fmt::format("'{}'", tokenSpelling(token.kind));
  }
}

// Where the parser's tokens come from: read from the file as the parser goes
// (parseFile), so the tokens of a whole file are never all in memory...
class ScannerSource {
public:
  ScannerSource(const SourceManager& sources, FileId file, std::uint32_t begin, std::uint32_t end,
                DiagnosticEngine& diagnostics)
      : scanner_(sources, file, begin, end, diagnostics, nullptr) {}
  void read(Token& token) { scanner_.read(token); }

private:
  Scanner scanner_;
};

// ... or from a vector lexed before (parse), ending in EndOfFile.
class VectorSource {
public:
  explicit VectorSource(std::vector<Token> tokens) : tokens_(std::move(tokens)) {}
  void read(Token& token) {
    token = tokens_[next_ < tokens_.size() ? next_ : tokens_.size() - 1];
    ++next_;
  }

private:
  std::vector<Token> tokens_;
  std::size_t next_ = 0;
};

template <typename Source> class Parser {
public:
  Parser(Source source, FileId file, DiagnosticEngine& diagnostics)
      : source_(std::move(source)), file_(file), diagnostics_(diagnostics) {}

  Module parseModule() {
    Module module;
    module.file = file_;
    module.arenas.push_back(itemArena_);
    module.arenas.push_back(partBodyArena_);
    while (!check(TokenKind::EndOfFile)) {
      panicking_ = false;
      std::size_t before = position_;
      module.items.push_back(parseItem());
      if (panicking_ || position_ == before) {
        synchroniseItem();
      }
    }
    reportPending();
    return module;
  }

private:
  // Guards against stack exhaustion on absurd nesting.
  struct DepthGuard {
    explicit DepthGuard(int& depth) : depth(depth) { ++depth; }
    ~DepthGuard() { --depth; }
    int& depth;
  };

  // ---------------------------------------------------------------- tokens
  // The tokens are read in batches into a window of the last few: the parser
  // looks one token ahead and back at the previous one. A token returned by
  // advance() stays valid for `windowSize - batchSize - 1` more.
  static constexpr std::size_t windowSize = 64;
  static constexpr std::size_t batchSize = 32;

  [[gnu::always_inline]] const Token& peek(std::size_t ahead = 0) {
    std::size_t index = position_ + ahead;
    if (index < read_) [[likely]] {
      return window_[index % windowSize];
    }
    return readUpTo(index);
  }
  // Out of line: peek() is the parser's most frequent call.
  [[gnu::noinline]] const Token& readUpTo(std::size_t index) {
    while (read_ <= index && read_ <= endOfFile_) {
      std::size_t batchEnd = read_ + batchSize;
      while (read_ < batchEnd) {
        Token& token = window_[read_ % windowSize];
        source_.read(token);
        if (token.kind == TokenKind::EndOfFile) {
          endOfFile_ = read_++;
          break;
        }
        ++read_;
      }
    }
    // Past the end, every token is the EndOfFile.
    return window_[std::min(index, endOfFile_) % windowSize];
  }
  [[gnu::always_inline]] bool check(TokenKind kind) { return peek().kind == kind; }
  bool checkWord(std::string_view word) {
    return check(TokenKind::Identifier) && peek().text == word;
  }
  [[gnu::always_inline]] const Token& advance() {
    const Token& token = peek();
    if (token.kind != TokenKind::EndOfFile) {
      ++position_;
    }
    return token;
  }
  bool match(TokenKind kind) {
    if (!check(kind)) {
      return false;
    }
    advance();
    return true;
  }
  SourceSpan previousSpan() {
    return position_ == 0 ? peek().span : window_[(position_ - 1) % windowSize].span;
  }
  SourceSpan spanFrom(SourceSpan begin) { return begin.to(previousSpan()); }

  // ---------------------------------------------------------------- errors
  Diagnostic* error(DiagnosticKind kind, SourceSpan span, std::string message) {
    if (panicking_) {
      return nullptr;
    }
    panicking_ = true;
    // Lexer errors were already reported; do not pile a parse error on them.
    if (check(TokenKind::Error) && span == peek().span) {
      return nullptr;
    }
    return report(kind, span, std::move(message));
  }

  // The parser's diagnostics are kept until the end, so that all of the
  // lexer's reach the engine first (and its error limit) as when the whole
  // file was lexed before parsing.
  Diagnostic* report(DiagnosticKind kind, SourceSpan span, std::string message) {
    return &pending_.emplace_back(
        Diagnostic{kind, diagnosticSeverity(kind), span, std::move(message), {}});
  }
  static void addNote(Diagnostic* diagnostic, SourceSpan span, std::string message) {
    if (diagnostic != nullptr) {
      diagnostic->notes.push_back({span, std::move(message)});
    }
  }
  void reportPending() {
    for (Diagnostic& pending : pending_) {
      Diagnostic* reported =
          diagnostics_.report(pending.kind, pending.span, std::move(pending.message));
      for (DiagnosticNote& note : pending.notes) {
        diagnostics_.addNote(reported, note.span, std::move(note.message));
      }
    }
    pending_.clear();
  }

  Diagnostic* errorAtCurrent(DiagnosticKind kind, std::string_view expected) {
    return error(kind, peek().span,
                 fmt::format("expected {}, found {}", expected, describe(peek())));
  }

  bool expect(TokenKind kind, std::string_view context) {
    if (match(kind)) {
      return true;
    }
    errorAtCurrent(DiagnosticKind::ExpectedToken,
                   fmt::format("'{}' {}", tokenSpelling(kind), context));
    return false;
  }

  // Expects the closing token of a pair, pointing back at the opening one.
  bool expectClosing(TokenKind kind, SourceSpan opening, std::string_view context) {
    if (match(kind)) {
      return true;
    }
    Diagnostic* diagnostic = errorAtCurrent(DiagnosticKind::ExpectedToken,
                                            fmt::format("'{}' {}", tokenSpelling(kind), context));
    addNote(diagnostic, opening, "to match this");
    return false;
  }

  std::string_view expectIdentifier(std::string_view what, SourceSpan& span) {
    span = peek().span;
    if (check(TokenKind::Identifier)) {
      return advance().text;
    }
    if (peek().kind >= TokenKind::KwPart && peek().kind <= TokenKind::KwFalse) {
      error(DiagnosticKind::ExpectedIdentifier, peek().span,
            fmt::format("expected {}, found keyword '{}', which cannot be used as a name", what,
                        tokenSpelling(peek().kind)));
      advance();
      return {};
    }
    errorAtCurrent(DiagnosticKind::ExpectedIdentifier, what);
    return {};
  }

  void synchroniseItem() {
    while (!check(TokenKind::EndOfFile)) {
      if (peek().startsLine && isItemKeyword(peek().kind)) {
        return;
      }
      advance();
    }
  }

  // Skips to the next statement on a later line, or to a '}' or ';'.
  void synchroniseStatement(int braceDepth = 0) {
    while (!check(TokenKind::EndOfFile)) {
      const Token& token = peek();
      if (braceDepth == 0 && token.kind == TokenKind::RightBrace) {
        return;
      }
      if (braceDepth == 0 && token.kind == TokenKind::Semicolon) {
        advance();
        return;
      }
      if (braceDepth == 0 && token.startsLine &&
          (isStatementKeyword(token.kind) || isStatementWord(token) || isItemKeyword(token.kind))) {
        return;
      }
      if (token.kind == TokenKind::LeftBrace) {
        ++braceDepth;
      } else if (token.kind == TokenKind::RightBrace) {
        --braceDepth;
      }
      advance();
    }
  }

  // Skips to just past the '}' that closes a '{' already consumed.
  void skipPastMatchingBrace() {
    int depth = 1;
    while (!check(TokenKind::EndOfFile) && depth > 0) {
      depth += check(TokenKind::LeftBrace) ? 1 : check(TokenKind::RightBrace) ? -1 : 0;
      advance();
    }
  }

  // ---------------------------------------------------------------- items
  ItemPtr parseItem() {
    SourceSpan begin = peek().span;
    switch (peek().kind) {
    case TokenKind::KwImport:
      return parseImport();
    case TokenKind::KwConst:
      return parseConst();
    case TokenKind::KwFn:
      return parseFn();
    case TokenKind::KwPart:
      return parsePart();
    default:
      break;
    }
    std::string hint;
    if (isStatementKeyword(peek().kind) || isStatementWord(peek())) {
      hint = "; statements such as this belong inside a 'part { ... }'";
    }
    error(DiagnosticKind::ExpectedItem, peek().span,
          fmt::format("expected 'part', 'fn', 'const' or 'import', found {}{}", describe(peek()),
                      hint));
    advance();
    return arena_->make<ErrorItem>(begin);
  }

  // import "std/curves"
  ItemPtr parseImport() {
    SourceSpan begin = advance().span;
    if (!check(TokenKind::String)) {
      errorAtCurrent(DiagnosticKind::ExpectedToken, "a module path in quotes after 'import'");
      return arena_->make<ErrorItem>(spanFrom(begin));
    }
    const Token& path = advance();
    return arena_->make<ImportItem>(spanFrom(begin), path.text, path.span);
  }

  // const name = expr
  ItemPtr parseConst() {
    SourceSpan begin = advance().span;
    SourceSpan nameSpan;
    std::string_view name = expectIdentifier("a constant name after 'const'", nameSpan);
    ExprPtr value;
    if (!name.empty() && expect(TokenKind::Equal, "after the constant's name")) {
      value = parseExpression();
    } else {
      value = arena_->make<ErrorExpr>(peek().span);
    }
    return arena_->make<ConstItem>(spanFrom(begin), name, nameSpan, std::move(value));
  }

  // fn name(a, b) = expr
  ItemPtr parseFn() {
    SourceSpan begin = advance().span;
    SourceSpan nameSpan;
    std::string_view name = expectIdentifier("a function name after 'fn'", nameSpan);
    NodeList<Parameter> parameters;
    if (!name.empty()) {
      parameters = parseParameters("function");
    }
    ExprPtr body;
    if (!panicking_ && expect(TokenKind::Equal, "before the function's body")) {
      body = parseExpression();
    } else {
      body = arena_->make<ErrorExpr>(peek().span);
    }
    return arena_->make<FnItem>(spanFrom(begin), name, nameSpan, std::move(parameters),
                                std::move(body));
  }

  // part name(p = 1, q = 2) { ... }
  ItemPtr parsePart() {
    SourceSpan begin = advance().span;
    SourceSpan nameSpan;
    std::string_view name = expectIdentifier("a part name after 'part'", nameSpan);
    NodeList<Parameter> parameters;
    if (!name.empty() && check(TokenKind::LeftParen)) {
      parameters = parseParameters("part");
    }
    Block body;
    if (!panicking_ && check(TokenKind::LeftBrace)) {
      arena_ = partBodyArena_.get();
      body = parseBlock();
      arena_ = itemArena_.get();
    } else {
      errorAtCurrent(DiagnosticKind::ExpectedToken, "'{' to begin the part's body");
      body.span = peek().span;
    }
    return arena_->make<PartItem>(spanFrom(begin), name, nameSpan, std::move(parameters),
                                  std::move(body));
  }

  // ( [name [= default] {, name [= default]}] )
  NodeList<Parameter> parseParameters(std::string_view owner) {
    SourceSpan opening = peek().span;
    // Formatted only when missing: the message is rarely needed.
    if (!check(TokenKind::LeftParen)) {
      expect(TokenKind::LeftParen, fmt::format("to begin the {}'s parameters", owner));
      return {};
    }
    advance();
    std::size_t first = parameterStack_.size();
    while (!check(TokenKind::RightParen) && !check(TokenKind::EndOfFile) && !panicking_) {
      Parameter parameter;
      parameter.name = expectIdentifier("a parameter name", parameter.nameSpan);
      if (panicking_) {
        break;
      }
      if (match(TokenKind::Equal)) {
        parameter.defaultValue = parseExpression();
      }
      parameterStack_.push_back(std::move(parameter));
      if (!match(TokenKind::Comma)) {
        break;
      }
    }
    if (!panicking_) {
      expectClosing(TokenKind::RightParen, opening, "to close the parameter list");
    }
    if (panicking_) {
      // The list ends at a syntax error: a parameter whose default was not
      // read has an erroneous one, not a missing one the checker would
      // report before the syntax error (`part p(depth 3)`).
      for (std::size_t i = first; i < parameterStack_.size(); ++i) {
        if (!parameterStack_[i].defaultValue) {
          parameterStack_[i].defaultValue = arena_->make<ErrorExpr>(parameterStack_[i].nameSpan);
        }
      }
    }
    return arena_->takeList(parameterStack_, first);
  }

  // ---------------------------------------------------------------- statements
  Block parseBlock() {
    Block block;
    DepthGuard guard(depth_);
    SourceSpan opening = advance().span; // '{'
    if (depth_ > maximumNestingDepth) {
      error(DiagnosticKind::NestingTooDeep, opening,
            fmt::format("blocks nested more than {} levels deep", maximumNestingDepth));
      skipPastMatchingBrace();
      block.span = spanFrom(opening);
      return block;
    }
    std::size_t first = statementStack_.size();
    while (!check(TokenKind::RightBrace) && !check(TokenKind::EndOfFile)) {
      if (peek().startsLine && isItemKeyword(peek().kind)) {
        break; // a missing '}': let the item loop take over
      }
      panicking_ = false;
      std::size_t before = position_;
      StmtPtr statement = parseStatement();
      statementStack_.push_back(std::move(statement));
      if (panicking_ || position_ == before) {
        synchroniseStatement();
      }
      if (position_ == before) {
        // A statement word that cannot start a statement (`tool = 1`): step
        // past it and skip the rest, so the one typo gives one message.
        advance();
        synchroniseStatement();
      }
    }
    block.statements = arena_->takeList(statementStack_, first);
    panicking_ = false;
    if (!check(TokenKind::RightBrace)) {
      Diagnostic* diagnostic =
          error(DiagnosticKind::ExpectedToken, peek().span,
                fmt::format("expected '}}' to close the block, found {}", describe(peek())));
      addNote(diagnostic, opening, "the block begins here");
      block.span = spanFrom(opening);
      return block;
    }
    advance();
    block.span = spanFrom(opening);
    return block;
  }

  StmtPtr parseStatement() {
    SourceSpan begin = peek().span;
    switch (peek().kind) {
    case TokenKind::KwLet:
      return parseLet();
    case TokenKind::KwCurve:
      return parseCut();
    case TokenKind::KwFor:
      return parseFor();
    case TokenKind::KwIf:
      return parseIf();
    case TokenKind::Semicolon:
      advance();
      return arena_->make<ErrorStmt>(begin);
    default:
      break;
    }
    if (isStatementWord(peek()) && peek(1).kind != TokenKind::Equal) {
      return parseSettingStatement();
    }
    std::string hint;
    if (check(TokenKind::Identifier) && peek(1).kind == TokenKind::Equal) {
      hint = fmt::format("; to name a value write 'let {} = ...'", peek().text);
    }
    error(DiagnosticKind::ExpectedStatement, peek().span,
          fmt::format("expected a statement (units, tool, feed, spindle, safe, origin, coolant, "
                      "let, curve, for, if), found {}{}",
                      describe(peek()), hint));
    return arena_->make<ErrorStmt>(begin);
  }

  StmtPtr parseSettingStatement() {
    const Token& word = advance();
    SourceSpan begin = word.span;
    std::string_view text = word.text;
    if (text == "units") {
      SourceSpan unitSpan = peek().span;
      if (!check(TokenKind::Identifier)) {
        errorAtCurrent(DiagnosticKind::ExpectedIdentifier, "'mm' or 'inch' after 'units'");
        return arena_->make<ErrorStmt>(spanFrom(begin));
      }
      std::string_view unit = advance().text;
      if (unit != "mm" && unit != "inch") {
        error(DiagnosticKind::UnknownUnits, unitSpan,
              fmt::format("unknown units '{}'; expected 'mm' or 'inch'", unit));
      }
      return arena_->make<UnitsStmt>(spanFrom(begin), unit, unitSpan);
    }
    if (text == "tool") {
      ExprPtr number = parseExpression();
      NodeList<Argument> settings =
          parseSettings({"diameter", "length", "radius", "spindle", "feed"});
      return arena_->make<ToolStmt>(spanFrom(begin), std::move(number), std::move(settings));
    }
    if (text == "origin") {
      return parseOrigin(begin);
    }
    if (text == "coolant") {
      return parseCoolant(begin);
    }
    if (text == "safe") {
      NodeList<Argument> settings = parseSettings({"z"});
      if (settings.empty() && !panicking_) {
        errorAtCurrent(DiagnosticKind::ExpectedToken, "'z=' after 'safe'");
      }
      return arena_->make<SafeStmt>(spanFrom(begin), std::move(settings));
    }
    StmtKind kind = text == "feed" ? StmtKind::Feed : StmtKind::Spindle;
    ExprPtr value = parseExpression();
    return arena_->make<ValueStmt>(kind, spanFrom(begin), std::move(value));
  }

  // The words of `origin` and `coolant` are on the statement's line.
  bool onStatementLine() { return !peek().startsLine && !check(TokenKind::EndOfFile); }

  // origin G54 .. G59 | origin G54.1 P<n>, all on one line. `G54.1` is the
  // name G54 and the number .1 written together; a space separates `P<n>`
  // from it (the lexer would read `.1P3` as a number with a unit).
  StmtPtr parseOrigin(SourceSpan begin) {
    if (!onStatementLine() || !check(TokenKind::Identifier)) {
      reportMissingWord(begin, "origin", "a work offset", "G54 .. G59, or G54.1 P1 .. P300");
      return arena_->make<ErrorStmt>(spanFrom(begin));
    }
    const Token word = advance(); // copied: the window moves on
    SourceSpan offsetSpan = word.span;
    bool extended = false;
    bool joined = false; // a number, '.' or bad token right after the name
    if (peek().span.begin == word.span.end &&
        (check(TokenKind::Number) || check(TokenKind::Dot) || check(TokenKind::Error))) {
      joined = true;
      if (check(TokenKind::Error)) {
        panicking_ = true; // the lexer has reported it (`G54.1P3`)
        advance();
        return arena_->make<ErrorStmt>(spanFrom(begin));
      }
      extended = word.text == "G54" && isPointOne(peek());
      offsetSpan = word.span.to(advance().span);
    }
    int group = workOffsetGroup(word.text);
    if (group == 0 || (joined && !extended)) {
      reportInvalidOffset(word.text, offsetSpan, joined);
      return arena_->make<ErrorStmt>(spanFrom(begin));
    }
    if (!extended) {
      return arena_->make<OriginStmt>(spanFrom(begin), group, 0, offsetSpan, SourceSpan{});
    }
    return parseExtendedOffset(begin, offsetSpan);
  }

  // The `P<n>` after `origin G54.1`.
  StmtPtr parseExtendedOffset(SourceSpan begin, SourceSpan offsetSpan) {
    int number =
        onStatementLine() && check(TokenKind::Identifier) ? extendedOffsetNumber(peek().text) : -1;
    if (number < 0) {
      if (onStatementLine()) {
        errorAtCurrent(DiagnosticKind::ExpectedToken,
                       "the extended offset P1 .. P300 after 'G54.1' (one word, such as P1)");
      } else {
        error(DiagnosticKind::ExpectedToken, offsetSpan,
              "'G54.1' needs the extended offset after it on its line: P1 .. P300, such as "
              "'G54.1 P1'");
      }
      return arena_->make<ErrorStmt>(spanFrom(begin));
    }
    SourceSpan numberSpan = advance().span;
    if (number < 1 || number > maximumExtendedOffset) {
      // The statement is read to its end: the next one parses as usual.
      report(DiagnosticKind::RegisterOutOfRange, numberSpan,
             fmt::format("there is no extended work offset P{}; G54.1 takes P1 .. P{}", number,
                         maximumExtendedOffset));
      return arena_->make<ErrorStmt>(spanFrom(begin));
    }
    return arena_->make<OriginStmt>(spanFrom(begin), 54, number, offsetSpan, numberSpan);
  }

  void reportInvalidOffset(std::string_view word, SourceSpan span, bool joined) {
    std::string what = joined ? std::string("this") : fmt::format("'{}'", word);
    std::string hint;
    if (!word.empty() && word[0] == 'g') {
      hint = " (written in capitals)";
    }
    error(DiagnosticKind::InvalidChoice, span,
          fmt::format("{} is not a work offset; 'origin' takes G54 .. G59, or G54.1 P1 .. P{}{}",
                      what, maximumExtendedOffset, hint));
  }

  // coolant flood | mist | through | off, on one line.
  StmtPtr parseCoolant(SourceSpan begin) {
    if (!onStatementLine() || !check(TokenKind::Identifier)) {
      reportMissingWord(begin, "coolant", "a coolant mode", "flood, mist, through or off");
      return arena_->make<ErrorStmt>(spanFrom(begin));
    }
    const Token& word = advance();
    std::optional<CoolantMode> mode = coolantModeNamed(word.text);
    if (!mode) {
      report(DiagnosticKind::InvalidChoice, word.span,
             fmt::format("'{}' is not a coolant mode; expected flood, mist, through or off{}",
                         word.text, word.text == "on" ? " (flood or mist turns it on)" : ""));
      return arena_->make<ErrorStmt>(spanFrom(begin));
    }
    return arena_->make<CoolantStmt>(spanFrom(begin), *mode, word.span);
  }

  // `origin` or `coolant` without its word: at the next token when it is on
  // the line, else at the statement's word (not at what the next line holds).
  void reportMissingWord(SourceSpan statementWord, std::string_view statement,
                         std::string_view expected, std::string_view choices) {
    if (onStatementLine()) {
      errorAtCurrent(DiagnosticKind::ExpectedIdentifier,
                     fmt::format("{} after '{}' ({})", expected, statement, choices));
      return;
    }
    error(DiagnosticKind::ExpectedIdentifier, statementWord,
          fmt::format("'{}' needs {} after it on its line: {}", statement, expected, choices));
  }

  // { name = expr } while the next tokens read `identifier =`. A setting on a
  // later line must be one of `knownNames`; anything else starts a new
  // statement (so `x = 3` on the next line is not taken for a setting).
  NodeList<Argument> parseSettings(std::initializer_list<std::string_view> knownNames) {
    std::size_t first = argumentStack_.size();
    while (!panicking_ && check(TokenKind::Identifier) && peek(1).kind == TokenKind::Equal &&
           continuesStatement(knownNames)) {
      Argument setting;
      setting.nameSpan = peek().span;
      setting.name = advance().text;
      advance(); // '='
      setting.value = parseExpression();
      argumentStack_.push_back(std::move(setting));
    }
    return arena_->takeList(argumentStack_, first);
  }

  bool continuesStatement(std::initializer_list<std::string_view> knownNames) {
    if (!peek().startsLine) {
      return true;
    }
    for (std::string_view name : knownNames) {
      if (peek().text == name) {
        return true;
      }
    }
    return false;
  }

  StmtPtr parseLet() {
    SourceSpan begin = advance().span;
    SourceSpan nameSpan;
    std::string_view name = expectIdentifier("a name after 'let'", nameSpan);
    ExprPtr value;
    if (!name.empty() && expect(TokenKind::Equal, "after the name in 'let'")) {
      value = parseExpression();
    } else {
      value = arena_->make<ErrorExpr>(peek().span);
    }
    return arena_->make<LetStmt>(spanFrom(begin), name, nameSpan, std::move(value));
  }

  // curve <expr> { word | word = expr }
  StmtPtr parseCut() {
    SourceSpan begin = advance().span;
    ExprPtr curve = parseExpression();
    std::size_t first = modifierStack_.size();
    while (!panicking_ && check(TokenKind::Identifier)) {
      bool assigned = peek(1).kind == TokenKind::Equal;
      // A word on the same line is a modifier (`sweep`, `tolerance=0.01`); on
      // a later line only a known `modifier=value` continues the cut.
      if (peek().startsLine && !(assigned && isModifierName(peek().text))) {
        break;
      }
      if (!assigned && isStatementWord(peek())) {
        break;
      }
      Modifier modifier;
      modifier.nameSpan = peek().span;
      modifier.name = advance().text;
      if (assigned) {
        advance();
        modifier.value = parseExpression();
      }
      modifierStack_.push_back(std::move(modifier));
    }
    return arena_->make<CutStmt>(spanFrom(begin), std::move(curve),
                                 arena_->takeList(modifierStack_, first));
  }

  // for i in a .. b { ... }
  StmtPtr parseFor() {
    SourceSpan begin = advance().span;
    SourceSpan variableSpan;
    std::string_view variable = expectIdentifier("a loop variable after 'for'", variableSpan);
    ExprPtr range;
    Block body;
    if (!panicking_ && expect(TokenKind::KwIn, "after the loop variable")) {
      range = parseExpression();
    } else {
      range = arena_->make<ErrorExpr>(peek().span);
    }
    if (!panicking_ && check(TokenKind::LeftBrace)) {
      body = parseBlock();
    } else {
      errorAtCurrent(DiagnosticKind::ExpectedToken, "'{' to begin the loop's body");
      body.span = peek().span;
    }
    return arena_->make<ForStmt>(spanFrom(begin), variable, variableSpan, std::move(range),
                                 std::move(body));
  }

  // if cond { ... } [else if ... | else { ... }]
  StmtPtr parseIf() {
    SourceSpan begin = advance().span;
    ExprPtr condition = parseExpression();
    Block thenBlock;
    Block elseBlock;
    bool hasElse = false;
    if (panicking_ || !check(TokenKind::LeftBrace)) {
      errorAtCurrent(DiagnosticKind::ExpectedToken, "'{' after the condition of 'if'");
      thenBlock.span = peek().span;
      return arena_->make<IfStmt>(spanFrom(begin), std::move(condition), std::move(thenBlock),
                                  std::move(elseBlock), false);
    }
    thenBlock = parseBlock();
    if (match(TokenKind::KwElse)) {
      hasElse = true;
      if (check(TokenKind::KwIf)) {
        SourceSpan elseBegin = peek().span;
        StmtPtr elseIf = parseIf();
        statementStack_.push_back(std::move(elseIf));
        elseBlock.statements = arena_->takeList(statementStack_, statementStack_.size() - 1);
        elseBlock.span = spanFrom(elseBegin);
      } else if (check(TokenKind::LeftBrace)) {
        elseBlock = parseBlock();
      } else {
        errorAtCurrent(DiagnosticKind::ExpectedToken, "'{' or 'if' after 'else'");
        elseBlock.span = peek().span;
      }
    }
    return arena_->make<IfStmt>(spanFrom(begin), std::move(condition), std::move(thenBlock),
                                std::move(elseBlock), hasElse);
  }

  // ---------------------------------------------------------------- expressions
  ExprPtr parseExpression() {
    DepthGuard guard(depth_);
    if (depth_ > maximumNestingDepth) {
      error(DiagnosticKind::NestingTooDeep, peek().span,
            fmt::format("expression nested more than {} levels deep", maximumNestingDepth));
      return arena_->make<ErrorExpr>(peek().span);
    }
    if (check(TokenKind::KwIf)) {
      return parseIfElse();
    }
    if (ExprPtr leaf = parseLeaf()) {
      return leaf;
    }
    return parseRange();
  }

  // Whether `kind` after an operand continues the expression: an operator,
  // '..', or what follows a name in a call, an index or a member.
  static bool continuesOperand(TokenKind kind) {
    BinaryOperator op{};
    return binaryLevel(kind, op) >= 0 || kind == TokenKind::Caret || kind == TokenKind::DotDot ||
           kind == TokenKind::LeftParen || kind == TokenKind::LeftBracket || kind == TokenKind::Dot;
  }

  // A number or a name that is a whole expression, such as an argument, a
  // list element or a setting: what parseRange() would return, without
  // descending through every level of operators for it. Null for anything
  // else.
  ExprPtr parseLeaf() {
    if (continuesOperand(peek(1).kind)) {
      return nullptr;
    }
    const Token& token = peek();
    if (token.kind == TokenKind::Number) {
      advance();
      return arena_->make<NumberExpr>(token.span, token.number, token.unit);
    }
    if (token.kind == TokenKind::Identifier) {
      advance();
      return arena_->make<NameExpr>(token.span, token.text);
    }
    return nullptr;
  }

  // if c then a else b
  ExprPtr parseIfElse() {
    SourceSpan begin = advance().span;
    ExprPtr condition = parseExpression();
    ExprPtr thenValue;
    ExprPtr elseValue;
    if (!panicking_ && expect(TokenKind::KwThen, "after the condition of an 'if' expression")) {
      thenValue = parseExpression();
    }
    if (!panicking_ && expect(TokenKind::KwElse, "in an 'if' expression (it needs both values)")) {
      elseValue = parseExpression();
    }
    if (!thenValue) {
      thenValue = arena_->make<ErrorExpr>(peek().span);
    }
    if (!elseValue) {
      elseValue = arena_->make<ErrorExpr>(peek().span);
    }
    return arena_->make<IfElseExpr>(spanFrom(begin), std::move(condition), std::move(thenValue),
                                    std::move(elseValue));
  }

  ExprPtr parseRange() {
    ExprPtr low = parseOr();
    if (!check(TokenKind::DotDot)) {
      return low;
    }
    advance();
    ExprPtr high = parseOr();
    SourceSpan span = low->span.to(high->span);
    return arena_->make<RangeExpr>(span, std::move(low), std::move(high));
  }

  // Binary operators by precedence level: 0 is '||', then '&&', the
  // comparisons, '+' and '-', and 4 is '*', '/' and '%'. -1: not one.
  static int binaryLevel(TokenKind kind, BinaryOperator& op) {
    switch (kind) {
    case TokenKind::PipePipe:
      op = BinaryOperator::Or;
      return 0;
    case TokenKind::AmpAmp:
      op = BinaryOperator::And;
      return 1;
    case TokenKind::EqualEqual:
      op = BinaryOperator::Equal;
      return 2;
    case TokenKind::BangEqual:
      op = BinaryOperator::NotEqual;
      return 2;
    case TokenKind::Less:
      op = BinaryOperator::Less;
      return 2;
    case TokenKind::LessEqual:
      op = BinaryOperator::LessEqual;
      return 2;
    case TokenKind::Greater:
      op = BinaryOperator::Greater;
      return 2;
    case TokenKind::GreaterEqual:
      op = BinaryOperator::GreaterEqual;
      return 2;
    case TokenKind::Plus:
      op = BinaryOperator::Add;
      return 3;
    case TokenKind::Minus:
      op = BinaryOperator::Subtract;
      return 3;
    case TokenKind::Star:
      op = BinaryOperator::Multiply;
      return 4;
    case TokenKind::Slash:
      op = BinaryOperator::Divide;
      return 4;
    case TokenKind::Percent:
      op = BinaryOperator::Remainder;
      return 4;
    default:
      return -1;
    }
  }
  static constexpr int deepestBinaryLevel = 4;

  ExprPtr parseOr() { return parseBinary(0); }

  // The operators of `level` and tighter, each level left associative: the
  // operand is parsed once, then each level from the tightest out takes the
  // operators of its own kind, parsing its right operands one level tighter.
  ExprPtr parseBinary(int level) {
    ExprPtr left = parseUnary();
    for (int current = deepestBinaryLevel; current >= level; --current) {
      BinaryOperator op{};
      // The levels down to the next token's take none of it: skipped. Once
      // the token is not an operator of this level or a looser one, no
      // level below takes it either.
      int next = binaryLevel(peek().kind, op);
      if (panicking_ || next < level || next > current) {
        return left;
      }
      current = next;
      // Every operator deepens the (left-leaning) tree that later phases walk
      // recursively, so a chain is bounded like nesting is.
      int chainLength = 0;
      while (!panicking_ && binaryLevel(peek().kind, op) == current) {
        if (++chainLength > maximumChainLength) {
          error(DiagnosticKind::NestingTooDeep, peek().span,
                fmt::format("more than {} operators in a row; split the expression with 'let'",
                            maximumChainLength));
          return left;
        }
        SourceSpan operatorSpan = advance().span;
        ExprPtr right = current == deepestBinaryLevel ? parseUnary() : parseBinary(current + 1);
        SourceSpan span = left->span.to(right->span);
        left = arena_->make<BinaryExpr>(span, op, operatorSpan, std::move(left), std::move(right));
      }
    }
    return left;
  }

  ExprPtr parseUnary() {
    if (check(TokenKind::Minus) || check(TokenKind::Bang)) {
      DepthGuard guard(depth_);
      if (depth_ > maximumNestingDepth) {
        error(DiagnosticKind::NestingTooDeep, peek().span,
              fmt::format("expression nested more than {} levels deep", maximumNestingDepth));
        return arena_->make<ErrorExpr>(peek().span);
      }
      SourceSpan begin = peek().span;
      UnaryOperator op =
          advance().kind == TokenKind::Minus ? UnaryOperator::Negate : UnaryOperator::Not;
      ExprPtr operand = parseUnary();
      SourceSpan span = begin.to(operand->span);
      return arena_->make<UnaryExpr>(span, op, std::move(operand));
    }
    return parsePower();
  }

  // a ^ b is right associative and binds tighter than unary minus on its
  // left: -2^2 is -(2^2), 2^-1 is 2^(-1).
  ExprPtr parsePower() {
    ExprPtr base = parsePostfix();
    if (panicking_ || !check(TokenKind::Caret)) {
      return base;
    }
    DepthGuard guard(depth_); // 2^2^2^... nests to the right
    if (depth_ > maximumNestingDepth) {
      error(DiagnosticKind::NestingTooDeep, peek().span,
            fmt::format("expression nested more than {} levels deep", maximumNestingDepth));
      return base;
    }
    SourceSpan operatorSpan = advance().span;
    ExprPtr exponent = parseUnary();
    SourceSpan span = base->span.to(exponent->span);
    return arena_->make<BinaryExpr>(span, BinaryOperator::Power, operatorSpan, std::move(base),
                                    std::move(exponent));
  }

  ExprPtr parsePostfix() {
    ExprPtr expression = parsePrimary();
    while (!panicking_) {
      if (check(TokenKind::LeftBracket)) {
        SourceSpan opening = advance().span;
        ExprPtr index = parseExpression();
        expectClosing(TokenKind::RightBracket, opening, "to close the index");
        SourceSpan span = spanFrom(expression->span);
        expression = arena_->make<IndexExpr>(span, std::move(expression), std::move(index));
      } else if (check(TokenKind::Dot)) {
        advance();
        SourceSpan memberSpan;
        std::string_view member =
            expectIdentifier("a member name (x, y or z) after '.'", memberSpan);
        SourceSpan span = spanFrom(expression->span);
        expression = arena_->make<MemberExpr>(span, std::move(expression), member, memberSpan);
      } else {
        return expression;
      }
    }
    return expression;
  }

  ExprPtr parsePrimary() {
    const Token& token = peek();
    switch (token.kind) {
    case TokenKind::Number:
      advance();
      return arena_->make<NumberExpr>(token.span, token.number, token.unit);
    case TokenKind::String:
      advance();
      return arena_->make<StringExpr>(token.span, token.text);
    case TokenKind::KwTrue:
    case TokenKind::KwFalse:
      advance();
      return arena_->make<BoolExpr>(token.span, token.kind == TokenKind::KwTrue);
    case TokenKind::Identifier:
      return parseNameOrCall();
    case TokenKind::LeftParen:
      return parseParenthesisOrPoint();
    case TokenKind::LeftBracket:
      return parseList();
    default:
      break;
    }
    errorAtCurrent(DiagnosticKind::ExpectedExpression, "an expression");
    SourceSpan span = token.span;
    // Consume a stray token inside an expression, but never a token that can
    // end the statement or close a bracket.
    if (token.kind == TokenKind::Error || token.kind == TokenKind::Star ||
        token.kind == TokenKind::Slash || token.kind == TokenKind::Caret ||
        token.kind == TokenKind::Percent || token.kind == TokenKind::Equal) {
      advance();
    }
    return arena_->make<ErrorExpr>(span);
  }

  ExprPtr parseNameOrCall() {
    // Copied: the arguments read more tokens than the window keeps.
    const Token name = advance();
    if (!check(TokenKind::LeftParen)) {
      return arena_->make<NameExpr>(name.span, name.text);
    }
    SourceSpan opening = advance().span;
    std::size_t first = argumentStack_.size();
    bool sawNamed = false;
    while (!check(TokenKind::RightParen) && !check(TokenKind::EndOfFile) && !panicking_) {
      Argument argument;
      if (check(TokenKind::Identifier) && peek(1).kind == TokenKind::Equal) {
        argument.nameSpan = peek().span;
        argument.name = advance().text;
        advance();
        sawNamed = true;
      } else if (sawNamed) {
        // Not a syntax error: the parser stays in step.
        report(DiagnosticKind::PositionalAfterNamed, peek().span,
               "a positional argument cannot follow a named one");
      }
      argument.value = parseExpression();
      argumentStack_.push_back(std::move(argument));
      if (panicking_ && check(TokenKind::Comma) && !argumentStack_.back().name.empty()) {
        // `order=,`: the value is missing, reported; the arguments after the
        // comma are read, so that none is called missing or unused.
        panicking_ = false;
      }
      if (!match(TokenKind::Comma)) {
        break;
      }
    }
    NodeList<Argument> arguments = arena_->takeList(argumentStack_, first);
    if (!panicking_ && !match(TokenKind::RightParen)) {
      // Formatted only here: the message is rarely needed.
      expectClosing(TokenKind::RightParen, opening,
                    fmt::format("to close the arguments of '{}'", name.text));
    }
    auto call =
        arena_->make<CallExpr>(spanFrom(name.span), name.text, name.span, std::move(arguments));
    call->argumentsCutShort = panicking_;
    return call;
  }

  // (e) is grouping; (x, y) and (x, y, z) are points.
  ExprPtr parseParenthesisOrPoint() {
    SourceSpan opening = advance().span;
    std::size_t first = expressionStack_.size();
    ExprPtr component = parseExpression();
    expressionStack_.push_back(std::move(component));
    while (!panicking_ && match(TokenKind::Comma)) {
      component = parseExpression();
      expressionStack_.push_back(std::move(component));
    }
    std::size_t count = expressionStack_.size() - first;
    if (!panicking_) {
      expectClosing(TokenKind::RightParen, opening,
                    count == 1 ? "to close the parenthesis" : "to close the point");
    }
    SourceSpan span = spanFrom(opening);
    if (count == 1) {
      ExprPtr grouped = std::move(expressionStack_.back());
      expressionStack_.pop_back();
      return grouped;
    }
    if (count > 3) {
      error(DiagnosticKind::PointComponents, span,
            fmt::format("a point has 2 or 3 components (x, y[, z]), this one has {}", count));
    }
    return arena_->make<PointExpr>(span, arena_->takeList(expressionStack_, first));
  }

  ExprPtr parseList() {
    SourceSpan opening = advance().span;
    std::size_t first = expressionStack_.size();
    while (!check(TokenKind::RightBracket) && !check(TokenKind::EndOfFile) && !panicking_) {
      ExprPtr element = parseExpression();
      expressionStack_.push_back(std::move(element));
      if (!match(TokenKind::Comma)) {
        break;
      }
    }
    NodeList<ExprPtr> elements = arena_->takeList(expressionStack_, first);
    if (!panicking_) {
      expectClosing(TokenKind::RightBracket, opening, "to close the list");
    }
    return arena_->make<ListExpr>(spanFrom(opening), std::move(elements));
  }

  Source source_;
  std::array<Token, windowSize> window_;
  std::size_t read_ = 0; // tokens read into the window so far
  std::size_t endOfFile_ = std::numeric_limits<std::size_t>::max(); // its index once read
  std::deque<Diagnostic> pending_;
  // The children of the lists being parsed, innermost last (node_arena.h).
  std::vector<ExprPtr> expressionStack_;
  std::vector<Argument> argumentStack_;
  std::vector<StmtPtr> statementStack_;
  std::vector<Parameter> parameterStack_;
  std::vector<Modifier> modifierStack_;

  // The file-level items (constants, functions, the parts' headers) apart
  // from the parts' bodies: checking the items, which parts use, reads one
  // compact run of memory instead of nodes scattered among the parts'.
  std::shared_ptr<NodeArena> itemArena_ = std::make_shared<NodeArena>();
  std::shared_ptr<NodeArena> partBodyArena_ = std::make_shared<NodeArena>();
  NodeArena* arena_ = itemArena_.get(); // where nodes are made now
  FileId file_;
  DiagnosticEngine& diagnostics_;
  std::size_t position_ = 0;
  bool panicking_ = false;
  int depth_ = 0;
};

} // namespace

Module parse(std::vector<Token> tokens, FileId file, DiagnosticEngine& diagnostics) {
  return Parser<VectorSource>(VectorSource(std::move(tokens)), file, diagnostics).parseModule();
}

Module parseFile(const SourceManager& sources, FileId file, DiagnosticEngine& diagnostics) {
  auto size = static_cast<std::uint32_t>(sources.file(file).text().size());
  return parseFileRange(sources, file, 0, size, diagnostics);
}

Module parseFileRange(const SourceManager& sources, FileId file, std::uint32_t begin,
                      std::uint32_t end, DiagnosticEngine& diagnostics) {
  ScannerSource source(sources, file, begin, end, diagnostics);
  return Parser<ScannerSource>(std::move(source), file, diagnostics).parseModule();
}

void appendModule(Module& into, Module&& from) {
  for (std::shared_ptr<NodeArena>& arena : from.arenas) {
    into.arenas.push_back(std::move(arena));
  }
  from.arenas.clear();
  into.items.reserve(into.items.size() + from.items.size());
  for (ItemPtr& item : from.items) {
    into.items.push_back(std::move(item));
  }
  from.items.clear();
}

} // namespace cncc::frontend
