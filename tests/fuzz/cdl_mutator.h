// A structured mutator for CDL sources: the changes a user's typo makes to a
// working part, which random byte flips rarely reach because they break the
// syntax first. One mutation of a source is one of:
// - a number replaced by an extreme value (0, a negative one, 1e-9, 1e9, ...);
// - an argument dropped from an argument list;
// - two lines swapped (statements out of order);
// - a number's sign flipped.
// Used by pipeline_fuzzer.cpp's LLVMFuzzerCustomMutator; header-only so the
// fuzzer is one translation unit.
#pragma once

#include <array>
#include <cctype>
#include <cstddef>
#include <cstdint>
#include <random>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace cncc::fuzz {

// The values typos and careless edits produce.
inline constexpr std::array<std::string_view, 16> extremeNumbers = {
    "0",   "-1",     "-5",    "1e-9", "1e9",       "1e6",    "4e9",    "-0.5",
    "360", "1e-300", "1e300", "2.5",  "99999.999", "100000", "0.0001", "-1e6"};

struct TextRange {
  std::size_t begin = 0;
  std::size_t end = 0;
};

// The number literals of a source (digits with an optional point and
// exponent, not part of a name).
inline std::vector<TextRange> numberLiterals(std::string_view text) {
  std::vector<TextRange> numbers;
  std::size_t i = 0;
  auto isNameCharacter = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
  };
  while (i < text.size()) {
    bool starts = std::isdigit(static_cast<unsigned char>(text[i])) != 0 &&
                  (i == 0 || (!isNameCharacter(text[i - 1]) && text[i - 1] != '.'));
    if (!starts) {
      ++i;
      continue;
    }
    std::size_t begin = i;
    while (i < text.size() &&
           (std::isdigit(static_cast<unsigned char>(text[i])) != 0 || text[i] == '.')) {
      ++i;
    }
    if (i < text.size() && (text[i] == 'e' || text[i] == 'E')) {
      std::size_t exponent = i + 1;
      if (exponent < text.size() && (text[exponent] == '-' || text[exponent] == '+')) {
        ++exponent;
      }
      if (exponent < text.size() && std::isdigit(static_cast<unsigned char>(text[exponent]))) {
        i = exponent;
        while (i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]))) {
          ++i;
        }
      }
    }
    numbers.push_back({begin, i});
  }
  return numbers;
}

// The arguments of the source's parenthesised lists: for each `(`, the
// comma-separated ranges between it and its `)` (an argument keeps its
// comma, so dropping it leaves a well-formed list).
inline std::vector<TextRange> argumentRanges(std::string_view text) {
  std::vector<TextRange> arguments;
  std::vector<std::size_t> openings;
  std::vector<std::size_t> starts;
  for (std::size_t i = 0; i < text.size(); ++i) {
    char c = text[i];
    if (c == '(' || c == '[') {
      openings.push_back(i);
      starts.push_back(i + 1);
    } else if ((c == ',' || c == ')' || c == ']') && !openings.empty()) {
      std::size_t end = c == ',' ? i + 1 : i;
      if (end > starts.back()) {
        arguments.push_back({starts.back(), end});
      }
      starts.back() = i + 1;
      if (c != ',') {
        openings.pop_back();
        starts.pop_back();
      }
    }
  }
  return arguments;
}

inline std::vector<TextRange> lineRanges(std::string_view text) {
  std::vector<TextRange> lines;
  std::size_t begin = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\n') {
      lines.push_back({begin, i + 1});
      begin = i + 1;
    }
  }
  if (begin < text.size()) {
    lines.push_back({begin, text.size()});
  }
  return lines;
}

inline std::string replaced(std::string_view text, TextRange range, std::string_view with) {
  std::string result(text.substr(0, range.begin));
  result += with;
  result += text.substr(range.end);
  return result;
}

// One structured mutation of `text`, chosen by `random`; the text unchanged
// when it offers nothing to mutate.
inline std::string mutateCdl(std::string_view text, std::mt19937& random) {
  auto pick = [&](std::size_t count) {
    return std::uniform_int_distribution<std::size_t>(0, count - 1)(random);
  };
  for (int attempt = 0; attempt < 4; ++attempt) {
    switch (pick(4)) {
    case 0:
    case 3: {
      std::vector<TextRange> numbers = numberLiterals(text);
      if (numbers.empty()) {
        break;
      }
      TextRange number = numbers[pick(numbers.size())];
      if (pick(4) == 0) { // flip the sign
        bool negative = number.begin > 0 && text[number.begin - 1] == '-';
        return negative ? replaced(text, {number.begin - 1, number.begin}, "")
                        : replaced(text, {number.begin, number.begin}, "-");
      }
      return replaced(text, number, extremeNumbers[pick(extremeNumbers.size())]);
    }
    case 1: {
      std::vector<TextRange> arguments = argumentRanges(text);
      if (arguments.empty()) {
        break;
      }
      return replaced(text, arguments[pick(arguments.size())], "");
    }
    case 2: {
      std::vector<TextRange> lines = lineRanges(text);
      if (lines.size() < 2) {
        break;
      }
      std::size_t a = pick(lines.size());
      std::size_t b = pick(lines.size());
      if (a == b) {
        break;
      }
      if (a > b) {
        std::swap(a, b);
      }
      std::string result(text.substr(0, lines[a].begin));
      result += text.substr(lines[b].begin, lines[b].end - lines[b].begin);
      result += text.substr(lines[a].end, lines[b].begin - lines[a].end);
      result += text.substr(lines[a].begin, lines[a].end - lines[a].begin);
      result += text.substr(lines[b].end);
      return result;
    }
    default:
      break;
    }
  }
  return std::string(text);
}

} // namespace cncc::fuzz
