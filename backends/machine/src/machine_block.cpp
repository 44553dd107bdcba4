#include "machine_block.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <utility>

namespace cncc::backends::machine {

namespace {

bool isLetter(char c) {
  return std::isalpha(static_cast<unsigned char>(c)) != 0;
}

bool isDigit(char c) {
  return std::isdigit(static_cast<unsigned char>(c)) != 0;
}

bool isIdentifierCharacter(char c) {
  return isLetter(c) || isDigit(c) || c == '_';
}

std::size_t skipSpaces(std::string_view text, std::size_t at) {
  while (at < text.size() && (text[at] == ' ' || text[at] == '\t')) {
    ++at;
  }
  return at;
}

// The end of a number (sign, digits, at most one point, some digit) at
// `at`, or `at` when there is none.
std::size_t numberEnd(std::string_view text, std::size_t at) {
  std::size_t end = at;
  if (end < text.size() && (text[end] == '-' || text[end] == '+')) {
    ++end;
  }
  bool digits = false;
  bool point = false;
  while (end < text.size() && (isDigit(text[end]) || (text[end] == '.' && !point))) {
    digits |= isDigit(text[end]);
    point |= text[end] == '.';
    ++end;
  }
  return digits ? end : at;
}

std::size_t identifierEnd(std::string_view text, std::size_t at) {
  while (at < text.size() && isIdentifierCharacter(text[at])) {
    ++at;
  }
  return at;
}

// The end of the balanced parentheses that open at `at`, or npos.
std::size_t closingParenthesis(std::string_view text, std::size_t at) {
  int depth = 0;
  for (std::size_t i = at; i < text.size(); ++i) {
    if (text[i] == '(') {
      ++depth;
    } else if (text[i] == ')' && --depth == 0) {
      return i + 1;
    }
  }
  return std::string_view::npos;
}

BlockProblem invalid(std::string message) {
  return {"machine-invalid-block", std::move(message)};
}

// A word: a letter and a number (G43, Z0., P10000). Returns its end.
std::optional<std::size_t> wordEnd(std::string_view block, std::size_t at, BlockProblem& problem) {
  std::size_t end = numberEnd(block, at + 1);
  if (end == at + 1) {
    problem = invalid(fmt::format("'{}' in '{}' is not followed by a number", block[at], block));
    return std::nullopt;
  }
  return end;
}

// ISO dialects: words and parenthesised comments.
std::optional<BlockProblem> isoBlockProblem(std::string_view block) {
  BlockProblem problem;
  for (std::size_t at = skipSpaces(block, 0); at < block.size(); at = skipSpaces(block, at)) {
    char c = block[at];
    if (c == '(') {
      std::size_t end = block.find(')', at);
      if (end == std::string_view::npos ||
          block.substr(at + 1, end - at - 1).find('(') != std::string_view::npos) {
        return invalid(fmt::format("unclosed or nested comment in '{}'", block));
      }
      at = end + 1;
    } else if (c == '#') {
      return invalid(fmt::format("'{}': variables and #-expressions are not allowed in a "
                                 "machine block",
                                 block));
    } else if (!isLetter(c)) {
      return invalid(fmt::format("unexpected '{}' in '{}': a block is words of a letter and a "
                                 "number",
                                 c, block));
    } else if (std::optional<std::size_t> end = wordEnd(block, at, problem)) {
      at = *end;
    } else {
      return problem;
    }
  }
  return std::nullopt;
}

// After NAME= on Sinumerik: a number, a name, a call or a string.
std::optional<std::size_t> sinumerikValueEnd(std::string_view block, std::size_t at) {
  if (std::size_t end = numberEnd(block, at); end != at) {
    return end;
  }
  if (at < block.size() && block[at] == '"') {
    std::size_t close = block.find('"', at + 1);
    return close == std::string_view::npos ? std::nullopt : std::optional(close + 1);
  }
  std::size_t end = identifierEnd(block, at);
  if (end == at) {
    return std::nullopt;
  }
  if (end < block.size() && block[end] == '(') {
    std::size_t close = closingParenthesis(block, end);
    return close == std::string_view::npos ? std::nullopt : std::optional(close);
  }
  return end;
}

// Sinumerik: a name is a word (G0, Z-5), a keyword (SUPA), a call
// (CYCLE832(0.01, _FINISH, 1)) or an assignment (X=AC(5)).
std::optional<std::size_t> sinumerikItemEnd(std::string_view block, std::size_t at) {
  std::size_t end = identifierEnd(block, at);
  if (end < block.size() && block[end] == '(') {
    std::size_t close = closingParenthesis(block, end);
    return close == std::string_view::npos ? std::nullopt : std::optional(close);
  }
  if (end < block.size() && block[end] == '=') {
    return sinumerikValueEnd(block, end + 1);
  }
  if (end < block.size() && (block[end] == '.' || block[end] == '-' || block[end] == '+')) {
    std::size_t number = numberEnd(block, at + 1); // Z-5, Z0.
    return number == at + 1 ? std::nullopt : std::optional(number);
  }
  return end;
}

std::optional<BlockProblem> sinumerikBlockProblem(std::string_view block) {
  for (std::size_t at = skipSpaces(block, 0); at < block.size(); at = skipSpaces(block, at)) {
    char c = block[at];
    if (c == ';') {
      return std::nullopt; // a comment to the end of the block
    }
    if (c == '#') {
      return invalid(fmt::format("'{}': #-expressions are not allowed in a machine block", block));
    }
    if (c == '(') {
      return invalid(fmt::format("'{}': a Sinumerik comment starts with ';'", block));
    }
    std::optional<std::size_t> end =
        isLetter(c) || c == '_' ? sinumerikItemEnd(block, at) : std::nullopt;
    if (!end) {
      return invalid(fmt::format("unexpected '{}' in '{}': expected a word, a keyword, NAME(...) "
                                 "or NAME=value",
                                 block.substr(at, 1), block));
    }
    at = *end;
  }
  return std::nullopt;
}

} // namespace

std::optional<BlockProblem> placeholderProblem(std::string_view pattern,
                                               std::span<const std::string_view> allowed) {
  for (std::size_t at = 0; at < pattern.size(); ++at) {
    if (pattern[at] == '}') {
      return BlockProblem{"machine-placeholder", fmt::format("unmatched '}}' in '{}'", pattern)};
    }
    if (pattern[at] != '{') {
      continue;
    }
    std::size_t close = pattern.find('}', at);
    if (close == std::string_view::npos) {
      return BlockProblem{"machine-placeholder", fmt::format("unclosed '{{' in '{}'", pattern)};
    }
    std::string_view name = pattern.substr(at + 1, close - at - 1);
    if (std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
      std::string takes = "none";
      if (!allowed.empty()) {
        takes = "";
        for (std::string_view each : allowed) {
          takes += fmt::format("{}{{{}}}", takes.empty() ? "" : " and ", each);
        }
      }
      return BlockProblem{
          "machine-placeholder",
          fmt::format("'{{{}}}' is not a placeholder of this field, which takes {}", name, takes)};
    }
    at = close;
  }
  return std::nullopt;
}

std::string withSampleValues(std::string_view pattern) {
  std::string text;
  for (std::size_t at = 0; at < pattern.size(); ++at) {
    std::size_t close = pattern[at] == '{' ? pattern.find('}', at) : std::string_view::npos;
    if (close == std::string_view::npos) {
      text += pattern[at];
      continue;
    }
    std::string_view name = pattern.substr(at + 1, close - at - 1);
    text += name == "code"                           ? "54"
            : name == "tolerance" || name == "blend" ? "0.01"
            : name == "units"                        ? "G21"
                                                     : "1";
    at = close;
  }
  return text;
}

std::optional<BlockProblem> blockProblem(std::string_view block, std::string_view dialect,
                                         int maximumLength) {
  if (block.find_first_of("\r\n") != std::string_view::npos) {
    return invalid("a block is one line, without line breaks");
  }
  if (static_cast<int>(block.size()) > maximumLength) {
    return BlockProblem{"machine-block-too-long",
                        fmt::format("'{}' is {} characters long; the controller takes at most {}",
                                    block, block.size(), maximumLength)};
  }
  return dialect == "sinumerik" ? sinumerikBlockProblem(block) : isoBlockProblem(block);
}

} // namespace cncc::backends::machine
