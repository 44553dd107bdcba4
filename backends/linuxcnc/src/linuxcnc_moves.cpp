#include "linuxcnc_moves.h"

#include <fmt/format.h>

namespace cncc::backends {

void LinuxcncMoveWriter::forget() {
  motion_.clear();
  literals_.clear();
  z_.reset();
}

std::string LinuxcncMoveWriter::word(char letter, ir::ValueId value, bool isCoordinate) {
  std::optional<double> literal = expressions_.constantOf(value);
  std::string text = !literal       ? expressions_.operand(value)
                     : isCoordinate ? expressions_.coordinateLiteral(*literal)
                                    : expressions_.constant(*literal);
  auto known = literals_.find(letter);
  if (literal && known != literals_.end() && known->second == text) {
    return "";
  }
  if (literal) {
    literals_[letter] = text;
  } else {
    literals_.erase(letter);
  }
  return fmt::format(" {}{}", letter, text);
}

void LinuxcncMoveWriter::motionLine(std::string_view motion, const std::string& words) {
  if (words.empty()) {
    return;
  }
  std::string text = motion == motion_ ? words.substr(1) : std::string(motion) + words;
  motion_ = std::string(motion);
  lines_.push_back(std::move(text));
}

std::string LinuxcncMoveWriter::zWord(ir::ValueId z) {
  std::string text = word('Z', z);
  if (!text.empty() && !beforeZ_.empty()) {
    text = " " + beforeZ_ + text;
    beforeZ_.clear();
  }
  return text;
}

void LinuxcncMoveWriter::rapid(ir::ValueId x, ir::ValueId y, ir::ValueId z) {
  std::optional<double> target = expressions_.constantOf(z);
  bool descending = target && z_ && *target < *z_ - 1e-12;
  if (descending) {
    motionLine("G0", word('X', x) + word('Y', y));
    motionLine("G0", zWord(z));
  } else {
    motionLine("G0", zWord(z));
    motionLine("G0", word('X', x) + word('Y', y));
  }
  z_ = target;
}

void LinuxcncMoveWriter::feed(ir::ValueId x, ir::ValueId y, ir::ValueId z, ir::ValueId feedRate) {
  std::string words = word('X', x) + word('Y', y) + zWord(z);
  if (!words.empty()) {
    words += word('F', feedRate, false);
  }
  motionLine("G1", words);
  z_ = expressions_.constantOf(z);
}

void LinuxcncMoveWriter::arc(bool clockwise, std::span<const ir::ValueId> operands) {
  for (char always : {'X', 'Y', 'I', 'J'}) {
    literals_.erase(always);
  }
  std::string words = word('X', operands[0]) + word('Y', operands[1]) + zWord(operands[2]) +
                      word('I', operands[3]) + word('J', operands[4]) +
                      word('F', operands[5], false);
  literals_.erase('I');
  literals_.erase('J');
  motionLine(clockwise ? "G2" : "G3", words);
  z_ = expressions_.constantOf(operands[2]);
}

} // namespace cncc::backends
