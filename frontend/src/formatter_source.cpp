#include "formatter_source.h"

#include <algorithm>

namespace cncc::frontend::format {

SourceCursor::SourceCursor(std::string_view text, std::vector<Token> tokens,
                           const std::vector<SourceSpan>& comments)
    : text_(text), tokens_(std::move(tokens)) {
  for (SourceSpan span : comments) {
    comments_.push_back(describeComment(span));
  }
}

SourceCursor::Comment SourceCursor::describeComment(SourceSpan span) const {
  Comment comment{span, text_.substr(span.begin, 2) == "//", true, false};
  for (std::uint32_t i = span.begin; i > 0 && text_[i - 1] != '\n'; --i) {
    char c = text_[i - 1];
    if (c != ' ' && c != '\t' && c != '\r') {
      comment.startsLine = false;
      break;
    }
  }
  const Token& next = tokens_[tokenIndexFrom(span.end)];
  comment.codeFollowsOnLine =
      next.kind != TokenKind::EndOfFile && lineBreaksBetween(span.end, next.span.begin) == 0;
  return comment;
}

std::size_t SourceCursor::tokenIndexFrom(std::uint32_t offset) const {
  auto found = std::lower_bound(
      tokens_.begin(), tokens_.end(), offset,
      [](const Token& token, std::uint32_t value) { return token.span.begin < value; });
  return found == tokens_.end() ? tokens_.size() - 1
                                : static_cast<std::size_t>(found - tokens_.begin());
}

const Token& SourceCursor::tokenAt(std::uint32_t offset) const {
  return tokens_[tokenIndexFrom(offset)];
}

const Token& SourceCursor::find(TokenKind kind, std::uint32_t offset) const {
  for (std::size_t i = tokenIndexFrom(offset); i < tokens_.size(); ++i) {
    if (tokens_[i].kind == kind) {
      return tokens_[i];
    }
  }
  return tokens_.back();
}

const Token& SourceCursor::closing(const Token& open) const {
  int depth = 0;
  for (std::size_t i = tokenIndexFrom(open.span.begin); i < tokens_.size(); ++i) {
    TokenKind kind = tokens_[i].kind;
    if (kind == TokenKind::LeftParen || kind == TokenKind::LeftBracket ||
        kind == TokenKind::LeftBrace) {
      ++depth;
    } else if (kind == TokenKind::RightParen || kind == TokenKind::RightBracket ||
               kind == TokenKind::RightBrace) {
      if (--depth == 0) {
        return tokens_[i];
      }
    }
  }
  return tokens_.back();
}

int SourceCursor::lineBreaksBetween(std::uint32_t begin, std::uint32_t end) const {
  if (end <= begin) {
    return 0;
  }
  return static_cast<int>(std::count(text_.begin() + begin, text_.begin() + end, '\n'));
}

Doc SourceCursor::print(const Token& token) {
  Doc printed = printWithoutTrailing(token);
  return Doc::concat({std::move(printed), trailingComments(token.span.end)});
}

Doc SourceCursor::printWithoutTrailing(const Token& token) {
  Doc comments = commentsBefore(token.span.begin);
  Doc text =
      Doc::text(std::string(text_.substr(token.span.begin, token.span.end - token.span.begin)));
  atBlockStart_ = false;
  commentContinuesLine_ = false;
  return Doc::concat({std::move(comments), std::move(text)});
}

Doc SourceCursor::printAs(SourceSpan span, std::string text) {
  Doc comments = commentsBefore(span.begin);
  atBlockStart_ = false;
  commentContinuesLine_ = false;
  return Doc::concat({std::move(comments), Doc::text(std::move(text)), trailingComments(span.end)});
}

Doc SourceCursor::commentsBefore(std::uint32_t offset) {
  std::vector<Doc> parts;
  while (nextComment_ < comments_.size() && comments_[nextComment_].span.begin < offset) {
    parts.push_back(printComment(comments_[nextComment_++], true));
  }
  return Doc::concat(std::move(parts));
}

// The comments after a token and before the next one that do not begin
// their line.
Doc SourceCursor::trailingComments(std::uint32_t tokenEnd) {
  if (tokenEnd == statementEnd_) {
    return Doc::concat({}); // left for the statement's line, outside its groups
  }
  std::uint32_t nextToken = tokens_[tokenIndexFrom(tokenEnd)].span.begin;
  std::vector<Doc> parts;
  while (nextComment_ < comments_.size()) {
    const Comment& comment = comments_[nextComment_];
    if (comment.startsLine || comment.span.begin < tokenEnd || comment.span.begin >= nextToken) {
      break;
    }
    parts.push_back(printComment(comment, false));
    ++nextComment_;
  }
  return Doc::concat(std::move(parts));
}

// A comment before code continues on its line with a space; one right
// after a token leaves the spacing to what the formatter prints next.
Doc SourceCursor::printComment(const Comment& comment, bool beforeCode) {
  std::vector<Doc> parts;
  if (!comment.startsLine) {
    parts.push_back(Doc::space());
  } else {
    parts.push_back(blankLineBefore(comment.span.begin) ? Doc::blankLine() : Doc::hardLine());
  }
  std::string_view text = text_.substr(comment.span.begin, comment.span.end - comment.span.begin);
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r')) {
    text.remove_suffix(1);
  }
  parts.push_back(comment.startsLine ? Doc::text(std::string(text))
                                     : Doc::lineEnd(std::string(text)));
  bool breaksLine = comment.isLine || (comment.startsLine && !comment.codeFollowsOnLine);
  if (breaksLine) {
    parts.push_back(Doc::hardLine());
  } else if (beforeCode) {
    parts.push_back(Doc::space());
  }
  atBlockStart_ = false;
  commentContinuesLine_ = comment.startsLine && !breaksLine;
  return Doc::concat(std::move(parts));
}

// Counts the line breaks in the whitespace right before `offset`, so what
// the formatter dropped there (a parenthesis, a ';') does not count.
bool SourceCursor::blankLineBefore(std::uint32_t offset) const {
  if (atBlockStart_) {
    return false;
  }
  int lineBreaks = 0;
  for (std::uint32_t i = std::min(offset, endOfText()); i > 0; --i) {
    char c = text_[i - 1];
    if (c == '\n') {
      ++lineBreaks;
    } else if (c != ' ' && c != '\t' && c != '\r' && c != '\f' && c != '\v') {
      break;
    }
  }
  return lineBreaks >= 2;
}

Doc SourceCursor::lineBreakBefore(std::uint32_t offset) const {
  if (commentContinuesLine_) {
    return Doc::concat({});
  }
  return blankLineBefore(offset) ? Doc::blankLine() : Doc::hardLine();
}

} // namespace cncc::frontend::format
