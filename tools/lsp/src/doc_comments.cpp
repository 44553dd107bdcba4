#include "doc_comments.h"

#include <vector>

namespace cncc::lsp {

namespace {

std::string_view trim(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) {
    text.remove_prefix(1);
  }
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r')) {
    text.remove_suffix(1);
  }
  return text;
}

std::size_t lineStartBefore(std::string_view text, std::size_t offset) {
  while (offset > 0 && text[offset - 1] != '\n') {
    --offset;
  }
  return offset;
}

// The lines of a `/* ... */` block ending with `last`, found by walking up.
std::vector<std::string_view> blockCommentLines(std::string_view text, std::size_t lineStart) {
  std::vector<std::string_view> lines;
  while (true) {
    std::size_t end = text.find('\n', lineStart);
    std::string_view line =
        trim(text.substr(lineStart, end == std::string_view::npos ? end : end - lineStart));
    lines.insert(lines.begin(), line);
    if (line.substr(0, 2) == "/*" || lineStart == 0) {
      return line.substr(0, 2) == "/*" ? lines : std::vector<std::string_view>{};
    }
    lineStart = lineStartBefore(text, lineStart - 1);
  }
}

std::string joinLines(const std::vector<std::string_view>& lines) {
  std::string joined;
  for (std::string_view line : lines) {
    joined += (joined.empty() ? "" : "\n") + std::string(line);
  }
  return joined;
}

} // namespace

std::string docCommentAbove(std::string_view text, std::uint32_t offset) {
  if (offset > text.size()) {
    return {};
  }
  std::size_t lineStart = lineStartBefore(text, offset);
  std::vector<std::string_view> lines;
  while (lineStart > 0) {
    std::size_t previousStart = lineStartBefore(text, lineStart - 1);
    std::string_view line = trim(text.substr(previousStart, lineStart - 1 - previousStart));
    if (line.substr(0, 2) == "//") {
      lines.insert(lines.begin(), trim(line.substr(2)));
    } else if (lines.empty() && line.size() >= 2 && line.substr(line.size() - 2) == "*/") {
      std::vector<std::string_view> block = blockCommentLines(text, previousStart);
      if (block.empty()) {
        return {};
      }
      block.front() = trim(block.front().substr(2));
      block.back() = trim(block.back().substr(0, block.back().size() - 2));
      return joinLines(block);
    } else {
      break;
    }
    lineStart = previousStart;
  }
  return joinLines(lines);
}

} // namespace cncc::lsp
