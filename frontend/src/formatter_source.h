// The formatter's view of the source (private to the front end): the tokens
// and comments of one file, walked in step with the tree.
//
// The formatter builds its document in source order and asks for every
// token it prints through `print()`. The cursor hands over each comment
// exactly once: the comments before a token come out in front of it, and a
// comment that ends the token's line comes out right after it (before any
// separator the formatter adds), so a trailing `// note` stays on its line.
// Tokens the formatter drops (redundant parentheses, a trailing comma, `;`)
// hand their comments to the next token printed.
#pragma once

#include "cncc/frontend/lexer.h"
#include "formatter_layout.h"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::frontend::format {

class SourceCursor {
public:
  SourceCursor(std::string_view text, std::vector<Token> tokens,
               const std::vector<SourceSpan>& comments);

  // The token that begins at `offset`, or the first token of `kind` at or
  // after `offset` (the source parsed, so it exists; EndOfFile otherwise).
  const Token& tokenAt(std::uint32_t offset) const;
  const Token& find(TokenKind kind, std::uint32_t offset) const;
  // The bracket that closes `open` (a '(', '[' or '{').
  const Token& closing(const Token& open) const;

  // The document for printing `token`, with the comments it carries; the
  // same for tokenAt(offset) and find(kind, offset).
  Doc print(const Token& token);
  // print() in two halves, for a closing bracket whose trailing comment
  // must not break the bracket's group.
  Doc printWithoutTrailing(const Token& token);
  Doc trailingComments(const Token& token) { return trailingComments(token.span.end); }
  Doc printAt(std::uint32_t offset) { return print(tokenAt(offset)); }
  // The tokens of `span` (written together, so no comment is between them)
  // printed as `text`, their canonical spelling, with their comments.
  Doc printAs(SourceSpan span, std::string text);
  Doc printNext(TokenKind kind, std::uint32_t offset) { return print(find(kind, offset)); }

  // The comments not yet printed that begin before `offset`.
  Doc commentsBefore(std::uint32_t offset);
  // Whether the source has an empty line right before `offset` (never
  // right after a block opens).
  bool blankLineBefore(std::uint32_t offset) const;
  // The line break before a statement or item at `offset` (called after
  // commentsBefore): an empty line where the source has one, none after a
  // `/* comment */` that the statement continues on its line.
  Doc lineBreakBefore(std::uint32_t offset) const;
  // A block or the file begins: blank lines right after it are dropped.
  void markBlockStart() { atBlockStart_ = true; }
  // Where the statement or item being printed ends. A comment after its
  // last token is not printed with that token but before what follows, at
  // block level: it must not break the statement's groups.
  void setStatementEnd(std::uint32_t offset) { statementEnd_ = offset; }
  std::uint32_t statementEnd() const { return statementEnd_; }

  std::uint32_t endOfText() const { return static_cast<std::uint32_t>(text_.size()); }

private:
  struct Comment {
    SourceSpan span;
    bool isLine;            // `// ...` rather than `/* ... */`
    bool startsLine;        // only whitespace before it on its line
    bool codeFollowsOnLine; // a token follows it on the same line
  };

  Comment describeComment(SourceSpan span) const;
  Doc printComment(const Comment& comment, bool beforeCode);
  Doc trailingComments(std::uint32_t tokenEnd);
  std::size_t tokenIndexFrom(std::uint32_t offset) const;
  int lineBreaksBetween(std::uint32_t begin, std::uint32_t end) const;

  std::string_view text_;
  std::vector<Token> tokens_;
  std::vector<Comment> comments_;
  std::size_t nextComment_ = 0;
  bool atBlockStart_ = true;
  bool commentContinuesLine_ = false;
  std::uint32_t statementEnd_ = 0;
};

} // namespace cncc::frontend::format
