// A word among a few known lower-case spellings (keywords, parameter names),
// found by its length and first letter (private to the front end): at most
// two spellings share both, so a word is compared with one or two of them
// instead of with every spelling.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace cncc::frontend {

// The spellings of one length and first letter: their indices plus one, 0
// for none. (Plain bytes rather than optionals: g++ 12 mis-initialises a
// nested std::array of structs whose members have default initialisers in
// a constant expression when they are read back as "none".)
struct SpellingCandidates {
  std::uint8_t first = 0;
  std::uint8_t second = 0;
};

template <std::size_t Longest>
using SpellingTable = std::array<std::array<SpellingCandidates, 26>, Longest + 1>;

// The table of `count` spellings, spellingAt(i) the i-th; a third spelling
// of the same length and first letter, or one longer than `Longest`, stops
// the compilation of the constant expression that builds it.
template <std::size_t Longest, typename SpellingAt>
constexpr SpellingTable<Longest> makeSpellingTable(std::size_t count, SpellingAt spellingAt) {
  SpellingTable<Longest> table{};
  for (std::size_t i = 0; i < count; ++i) {
    std::string_view spelling = spellingAt(i);
    SpellingCandidates& candidates =
        table.at(spelling.size()).at(static_cast<std::size_t>(spelling[0] - 'a'));
    auto candidate = static_cast<std::uint8_t>(i + 1);
    if (candidates.first == 0) {
      candidates.first = candidate;
    } else if (candidates.second == 0) {
      candidates.second = candidate;
    } else {
      throw "a third spelling of the same length and first letter";
    }
  }
  return table;
}

// The candidates for `word`; null when no spelling can be it. (`Lengths`
// is Longest + 1, which is what a call can deduce.)
template <std::size_t Lengths>
const SpellingCandidates*
spellingCandidates(const std::array<std::array<SpellingCandidates, 26>, Lengths>& table,
                   std::string_view word) {
  if (word.empty() || word.size() >= Lengths || word[0] < 'a' || word[0] > 'z') {
    return nullptr;
  }
  return &table[word.size()][static_cast<std::size_t>(word[0] - 'a')];
}

} // namespace cncc::frontend
