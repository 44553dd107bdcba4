#include "modal_moves.h"

#include <fmt/format.h>

namespace cncc::backends {

ModalState ModalState::agreedWith(const ModalState& other) const {
  ModalState agreed;
  agreed.motion = motion == other.motion ? motion : "";
  for (const auto& [letter, word] : words) {
    auto found = other.words.find(letter);
    if (found != other.words.end() && found->second == word) {
      agreed.words[letter] = word;
    }
  }
  agreed.z = z == other.z ? z : std::nullopt;
  return agreed;
}

std::string ModalMoveWriter::word(char letter, ir::ValueId value, bool isCoordinate) {
  std::optional<double> literal = expressions_.constantOf(value);
  std::string text = !literal       ? expressions_.operand(value)
                     : isCoordinate ? expressions_.coordinateLiteral(*literal)
                                    : expressions_.constant(*literal);
  ModalWord current{text, literal ? std::nullopt : std::optional<std::uint32_t>(value.index)};
  auto known = modal_.words.find(letter);
  if (known != modal_.words.end() && known->second == current) {
    return "";
  }
  modal_.words[letter] = current;
  return fmt::format(" {}{}", letter, text);
}

void ModalMoveWriter::block(std::string_view motion, const std::string& words) {
  if (words.empty()) {
    return;
  }
  std::string text = motion == modal_.motion ? words.substr(1) : std::string(motion) + words;
  modal_.motion = std::string(motion);
  lines_.push_back(std::move(text));
}

std::string ModalMoveWriter::zWord(ir::ValueId z) {
  std::string text = word('Z', z);
  if (!text.empty() && !beforeZ_.empty()) {
    text = " " + beforeZ_ + text;
    beforeZ_.clear();
  }
  return text;
}

void ModalMoveWriter::rapid(ir::ValueId x, ir::ValueId y, ir::ValueId z) {
  std::optional<double> target = expressions_.constantOf(z);
  bool descending = target && modal_.z && *target < *modal_.z - 1e-12;
  if (descending) {
    block("G0", word('X', x) + word('Y', y));
    block("G0", zWord(z));
  } else {
    block("G0", zWord(z));
    block("G0", word('X', x) + word('Y', y));
  }
  modal_.z = target;
}

void ModalMoveWriter::climb(ir::ValueId z) {
  block("G0", zWord(z));
  modal_.z = expressions_.constantOf(z);
}

void ModalMoveWriter::feed(ir::ValueId x, ir::ValueId y, ir::ValueId z, ir::ValueId feedRate) {
  std::string plane = word('X', x) + word('Y', y);
  std::string words = plane + zWord(z);
  if (!words.empty()) {
    words += word('F', feedRate, false);
  }
  if (!plane.empty() && !beforePlane_.empty()) {
    words = " " + beforePlane_ + words;
    beforePlane_.clear();
  }
  block("G1", words);
  modal_.z = expressions_.constantOf(z);
}

void ModalMoveWriter::arc(bool clockwise, std::span<const ir::ValueId> operands) {
  for (char always : {'X', 'Y', 'I', 'J'}) {
    modal_.words.erase(always);
  }
  std::string words = word('X', operands[0]) + word('Y', operands[1]) + zWord(operands[2]) +
                      word('I', operands[3]) + word('J', operands[4]) +
                      word('F', operands[5], false);
  modal_.words.erase('I');
  modal_.words.erase('J');
  block(clockwise ? "G2" : "G3", words);
  modal_.z = expressions_.constantOf(operands[2]);
}

} // namespace cncc::backends
