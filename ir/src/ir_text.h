// What the IR text's reader and writer (parser.cpp, printer.cpp and the
// tables' text) read words, lists, numbers and strings with; a Failure is
// the reader's message for the line.
#pragma once

#include <charconv>
#include <cstdint>
#include <fmt/format.h>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::ir::text {

struct Failure {
  std::string message;
};

inline std::string_view trim(std::string_view text) {
  while (!text.empty() && (text.front() == ' ' || text.front() == '\t')) {
    text.remove_prefix(1);
  }
  while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r')) {
    text.remove_suffix(1);
  }
  return text;
}

inline bool startsWith(std::string_view text, std::string_view prefix) {
  return text.substr(0, prefix.size()) == prefix;
}

// `a, b, c`: the trimmed parts between commas.
inline std::vector<std::string_view> splitList(std::string_view text) {
  std::vector<std::string_view> parts;
  while (!trim(text).empty()) {
    std::size_t comma = text.find(',');
    parts.push_back(trim(text.substr(0, comma)));
    if (comma == std::string_view::npos) {
      break;
    }
    text.remove_prefix(comma + 1);
  }
  return parts;
}

// The words between spaces.
inline std::vector<std::string_view> splitWords(std::string_view text) {
  std::vector<std::string_view> words;
  std::size_t at = 0;
  while (at < text.size()) {
    std::size_t end = text.find(' ', at);
    end = end == std::string_view::npos ? text.size() : end;
    if (end > at) {
      words.push_back(text.substr(at, end - at));
    }
    at = end + 1;
  }
  return words;
}

// The index of `word` in `names`, or the failure: expected `what`, found it.
inline std::size_t namedIndex(std::span<const std::string_view> names, std::string_view word,
                              std::string_view what) {
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (names[i] == word) {
      return i;
    }
  }
  throw Failure{fmt::format("expected {}, found '{}'", what, word)};
}

inline double parseNumber(std::string_view text) {
  text = trim(text);
  double value = 0;
  auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) {
    throw Failure{fmt::format("expected a number, found '{}'", text)};
  }
  return value;
}

// A whole number that fits an index (`cut.begin n`, a register).
inline std::uint32_t parseWholeNumber(std::string_view text) {
  text = trim(text);
  std::uint32_t index = 0;
  auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), index);
  if (error != std::errc() || end != text.data() + text.size()) {
    throw Failure{fmt::format("expected a whole number, found '{}'", text)};
  }
  return index;
}

// `"text"`, a quote or backslash escaped by a backslash, a newline a space.
inline std::string quoted(std::string_view text) {
  std::string result = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') {
      result += '\\';
    }
    result += c == '\n' ? ' ' : c;
  }
  return result + "\"";
}

inline std::string unquote(std::string_view text) {
  if (text.size() < 2 || text.front() != '"' || text.back() != '"') {
    throw Failure{"expected a quoted string"};
  }
  std::string result;
  for (std::size_t i = 1; i + 1 < text.size(); ++i) {
    if (text[i] == '\\' && i + 2 < text.size()) {
      ++i;
    }
    result += text[i];
  }
  return result;
}

} // namespace cncc::ir::text
