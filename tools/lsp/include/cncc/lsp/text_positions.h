// Positions as the Language Server Protocol counts them: a zero-based line
// and a column in UTF-16 code units (what the protocol requires unless a
// client negotiates otherwise), converted to and from byte offsets.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

namespace cncc::lsp {

struct Position {
  std::uint32_t line = 0;
  std::uint32_t character = 0; // UTF-16 code units from the start of the line
  friend bool operator==(Position, Position) = default;
};

struct Range {
  Position start;
  Position end;
  friend bool operator==(Range, Range) = default;
};

// The line starts of one text, for conversions in both directions. The text
// must outlive it.
class TextPositions {
public:
  explicit TextPositions(std::string_view text);

  // The byte offset of `position`, clamped into the text: a line past the
  // end means the end of the text, a character past the end of its line
  // the end of that line (before its line break), and a character inside a
  // UTF-8 sequence the start of that sequence.
  std::uint32_t offsetOf(Position position) const;
  // The position of byte `offset` (clamped to the end of the text).
  Position positionOf(std::uint32_t offset) const;
  Range rangeOf(std::uint32_t begin, std::uint32_t end) const;

  std::uint32_t lineCount() const { return static_cast<std::uint32_t>(lineStarts_.size()); }

private:
  // The end of a line's content: before "\n" or "\r\n".
  std::uint32_t lineContentEnd(std::uint32_t line) const;

  std::string_view text_;
  std::vector<std::uint32_t> lineStarts_;
};

// How many UTF-16 code units the UTF-8 sequence starting with `leadByte`
// encodes (2 for a 4-byte sequence, else 1), and how many bytes it takes (1
// for a byte that cannot start a sequence, which counts as one unit).
std::uint32_t utf8SequenceLength(unsigned char leadByte);
std::uint32_t utf16UnitsOf(unsigned char leadByte);

} // namespace cncc::lsp
