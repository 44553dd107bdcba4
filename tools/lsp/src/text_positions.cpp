#include "cncc/lsp/text_positions.h"

#include <algorithm>

namespace cncc::lsp {

std::uint32_t utf8SequenceLength(unsigned char leadByte) {
  if (leadByte >= 0xF0 && leadByte <= 0xF7) {
    return 4;
  }
  if (leadByte >= 0xE0 && leadByte <= 0xEF) {
    return 3;
  }
  if (leadByte >= 0xC0 && leadByte <= 0xDF) {
    return 2;
  }
  return 1; // ASCII, or a byte that starts no sequence
}

std::uint32_t utf16UnitsOf(unsigned char leadByte) {
  return utf8SequenceLength(leadByte) == 4 ? 2 : 1;
}

TextPositions::TextPositions(std::string_view text) : text_(text) {
  lineStarts_.push_back(0);
  for (std::uint32_t i = 0; i < text_.size(); ++i) {
    if (text_[i] == '\n') {
      lineStarts_.push_back(i + 1);
    }
  }
}

std::uint32_t TextPositions::lineContentEnd(std::uint32_t line) const {
  std::uint32_t end = line + 1 < lineStarts_.size() ? lineStarts_[line + 1] - 1
                                                    : static_cast<std::uint32_t>(text_.size());
  if (end > lineStarts_[line] && text_[end - 1] == '\r' && line + 1 < lineStarts_.size()) {
    --end;
  }
  return end;
}

std::uint32_t TextPositions::offsetOf(Position position) const {
  if (position.line >= lineStarts_.size()) {
    return static_cast<std::uint32_t>(text_.size());
  }
  std::uint32_t offset = lineStarts_[position.line];
  std::uint32_t end = lineContentEnd(position.line);
  std::uint32_t units = 0;
  while (offset < end) {
    auto lead = static_cast<unsigned char>(text_[offset]);
    std::uint32_t unitsHere = utf16UnitsOf(lead);
    if (units + unitsHere > position.character) {
      break; // the position is inside this character: take its start
    }
    units += unitsHere;
    offset = std::min(end, offset + utf8SequenceLength(lead));
  }
  return offset;
}

Position TextPositions::positionOf(std::uint32_t offset) const {
  offset = std::min(offset, static_cast<std::uint32_t>(text_.size()));
  auto next = std::upper_bound(lineStarts_.begin(), lineStarts_.end(), offset);
  auto line = static_cast<std::uint32_t>(next - lineStarts_.begin()) - 1;
  std::uint32_t units = 0;
  for (std::uint32_t i = lineStarts_[line]; i < offset;) {
    auto lead = static_cast<unsigned char>(text_[i]);
    units += utf16UnitsOf(lead);
    i += utf8SequenceLength(lead);
  }
  return {line, units};
}

Range TextPositions::rangeOf(std::uint32_t begin, std::uint32_t end) const {
  return {positionOf(begin), positionOf(std::max(begin, end))};
}

} // namespace cncc::lsp
