// Semantic tokens: every token and comment of the document classified for
// highlighting, names by what they resolve to (a parameter, a function, a
// constant...), in the protocol's relative encoding.
#include "cncc/frontend/lexer.h"
#include "cncc/lsp/features.h"

#include <algorithm>
#include <unordered_map>

namespace cncc::lsp {

namespace {

using namespace frontend;

// Indexes into the legend's token types and modifier bits.
enum class TokenType {
  Keyword,
  Number,
  String,
  Comment,
  Operator,
  Function,
  Parameter,
  Variable,
  Class,
  Property,
  EnumMember
};
namespace TokenModifier {
constexpr unsigned Declaration = 1;
constexpr unsigned Readonly = 2;
constexpr unsigned DefaultLibrary = 4;
} // namespace TokenModifier

struct Classified {
  std::uint32_t begin;
  std::uint32_t end;
  TokenType type;
  unsigned modifiers;
};

std::optional<std::pair<TokenType, unsigned>> classifyDeclaration(const Reference& reference) {
  const frontend::Declaration& declaration = *reference.declaration;
  unsigned modifiers = reference.isDefinition ? TokenModifier::Declaration : 0U;
  switch (declaration.kind) {
  case DeclarationKind::Builtin:
    return std::pair{declaration.name == "pi" ? TokenType::Variable : TokenType::Function,
                     modifiers | TokenModifier::DefaultLibrary |
                         (declaration.name == "pi" ? TokenModifier::Readonly : 0U)};
  case DeclarationKind::Function:
    return std::pair{TokenType::Function, modifiers};
  case DeclarationKind::Constant:
    return std::pair{TokenType::Variable, modifiers | TokenModifier::Readonly};
  case DeclarationKind::PartParameter:
  case DeclarationKind::FunctionParameter:
    return std::pair{TokenType::Parameter, modifiers};
  case DeclarationKind::Part:
    return std::pair{TokenType::Class, modifiers};
  default:
    return std::pair{TokenType::Variable, modifiers};
  }
}

bool isStatementWord(std::string_view word) {
  return word == "units" || word == "tool" || word == "feed" || word == "spindle" ||
         word == "safe" || word == "origin" || word == "coolant";
}

bool isIdentifier(const std::vector<Token>& tokens, std::size_t i, std::string_view text) {
  return tokens[i].kind == TokenKind::Identifier && tokens[i].text == text;
}

// The word of `units mm`, `coolant flood` and `origin G55`, and the `P3` of
// `origin G54.1 P3` (tokens `origin`, `G54`, `.1`, `P3`).
bool isStatementChoice(const std::vector<Token>& tokens, std::size_t i) {
  if (i >= 1 && (isIdentifier(tokens, i - 1, "units") || isIdentifier(tokens, i - 1, "coolant") ||
                 isIdentifier(tokens, i - 1, "origin"))) {
    return true;
  }
  return i >= 3 && tokens[i - 1].kind == TokenKind::Number && isIdentifier(tokens, i - 3, "origin");
}

// Whether tokens[i] is where a statement may begin: a line's first token,
// or the first after '{', '}' or ';'.
bool startsStatement(const std::vector<Token>& tokens, std::size_t i) {
  if (tokens[i].startsLine || i == 0) {
    return true;
  }
  TokenKind previous = tokens[i - 1].kind;
  return previous == TokenKind::LeftBrace || previous == TokenKind::RightBrace ||
         previous == TokenKind::Semicolon;
}

bool isOperator(TokenKind kind) {
  return kind >= TokenKind::Plus && kind <= TokenKind::Bang;
}

class Classifier {
public:
  explicit Classifier(const Analysis& analysis) : analysis_(analysis) {
    for (const Reference& reference : analysis.program().references) {
      if (reference.span.file == analysis.file() && reference.declaration != nullptr) {
        references_[reference.span.begin] = &reference;
      }
    }
  }

  std::vector<Classified> run() {
    DiagnosticEngine ignored(0);
    std::vector<SourceSpan> comments;
    std::vector<Token> tokens = lex(analysis_.sources(), analysis_.file(), ignored, &comments);
    std::vector<Classified> result;
    for (std::size_t i = 0; i < tokens.size(); ++i) {
      if (std::optional<Classified> classified = classify(tokens, i)) {
        result.push_back(*classified);
      }
    }
    for (SourceSpan comment : comments) {
      result.push_back({comment.begin, comment.end, TokenType::Comment, 0});
    }
    std::sort(result.begin(), result.end(),
              [](const Classified& a, const Classified& b) { return a.begin < b.begin; });
    return result;
  }

private:
  std::optional<Classified> classify(const std::vector<Token>& tokens, std::size_t i) const {
    const Token& token = tokens[i];
    auto make = [&](TokenType type, unsigned modifiers = 0) {
      return Classified{token.span.begin, token.span.end, type, modifiers};
    };
    if (token.kind >= TokenKind::KwPart && token.kind <= TokenKind::KwFalse) {
      return make(TokenType::Keyword);
    }
    switch (token.kind) {
    case TokenKind::Number:
      return make(TokenType::Number);
    case TokenKind::String:
      return make(TokenType::String);
    case TokenKind::Identifier:
      return classifyIdentifier(tokens, i);
    default:
      return isOperator(token.kind) ? std::optional(make(TokenType::Operator)) : std::nullopt;
    }
  }

  std::optional<Classified> classifyIdentifier(const std::vector<Token>& tokens,
                                               std::size_t i) const {
    const Token& token = tokens[i];
    auto found = references_.find(token.span.begin);
    if (found != references_.end() && found->second->span.end == token.span.end) {
      if (auto type = classifyDeclaration(*found->second)) {
        return Classified{token.span.begin, token.span.end, type->first, type->second};
      }
    }
    TokenType type = TokenType::Property; // named arguments, settings, modifiers
    if (startsStatement(tokens, i) && isStatementWord(token.text)) {
      type = TokenType::Keyword;
    } else if (isStatementChoice(tokens, i)) {
      type = TokenType::EnumMember;
    } else if (i + 1 < tokens.size() && tokens[i + 1].kind != TokenKind::Equal &&
               std::find(cutModifierNames().begin(), cutModifierNames().end(), token.text) ==
                   cutModifierNames().end()) {
      return std::nullopt; // an unresolved name (reported as a diagnostic)
    }
    return Classified{token.span.begin, token.span.end, type, 0};
  }

  const Analysis& analysis_;
  std::unordered_map<std::uint32_t, const Reference*> references_;
};

// Appends the relative encoding of one single-line piece.
void encode(std::vector<std::uint32_t>& data, Position& previous, Position start,
            std::uint32_t length, const Classified& token) {
  std::uint32_t deltaLine = start.line - previous.line;
  std::uint32_t deltaStart =
      deltaLine == 0 ? start.character - previous.character : start.character;
  data.insert(data.end(), {deltaLine, deltaStart, length, static_cast<std::uint32_t>(token.type),
                           token.modifiers});
  previous = start;
}

} // namespace

Json semanticTokensLegend() {
  return {{"tokenTypes",
           {"keyword", "number", "string", "comment", "operator", "function", "parameter",
            "variable", "class", "property", "enumMember"}},
          {"tokenModifiers", {"declaration", "readonly", "defaultLibrary"}}};
}

// Tokens that span lines (block comments) are sent one piece per line, as
// clients without multiline token support expect.
Json semanticTokens(const Analysis& analysis) {
  const TextPositions& positions = analysis.positions();
  std::vector<std::uint32_t> data;
  Position previous;
  for (const Classified& token : Classifier(analysis).run()) {
    Position start = positions.positionOf(token.begin);
    Position end = positions.positionOf(token.end);
    for (std::uint32_t line = start.line; line <= end.line; ++line) {
      Position pieceStart = line == start.line ? start : Position{line, 0};
      std::uint32_t pieceEnd =
          line == end.line ? end.character
                           : positions.positionOf(positions.offsetOf({line + 1, 0}) - 1).character;
      if (pieceEnd > pieceStart.character) {
        encode(data, previous, pieceStart, pieceEnd - pieceStart.character, token);
      }
    }
  }
  return {{"data", data}};
}

} // namespace cncc::lsp
