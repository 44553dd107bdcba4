#include "heidenhain_blocks.h"

#include <fmt/format.h>

namespace cncc::backends {

namespace {

using ir::Opcode;

enum TncJump { Equal = 9, NotEqual = 10, Greater = 11, Less = 12 };

// An operand (`+3`, `-0.5`, `+QL4`) as a term of a formula.
std::string term(const std::string& operand) {
  return operand.starts_with('+') ? operand.substr(1) : "( " + operand + " )";
}

} // namespace

void TncBlockWriter::block(std::string text) {
  lines_.push_back(std::move(text));
}

void TncBlockWriter::releaseScratch() {
  nextScratch_ = 0;
}

std::string TncBlockWriter::scratch() {
  // The last scratch parameter holds the tool's Z (trackZ).
  if (nextScratch_ >= profile_.scratch.count() - 1) {
    errors_.push_back(fmt::format(
        "a block needs more than the {} scratch parameters {}-{}", profile_.scratch.count() - 1,
        tncParameterName(profile_.scratch.first), tncParameterName(profile_.scratch.last - 1)));
    return tncParameterName(profile_.scratch.first);
  }
  return tncParameterName(profile_.scratch.first + nextScratch_++);
}

std::string TncBlockWriter::operand(ir::ValueId value, bool coordinate) {
  if (std::optional<double> number = formulas_.constantOf(value)) {
    return coordinate ? formulas_.signedCoordinate(*number) : formulas_.signedNumber(*number);
  }
  if (formulas_.atom(value)) {
    return "+" + formulas_.variable(value);
  }
  std::string parameter = scratch();
  assign(parameter, value);
  return "+" + parameter;
}

void TncBlockWriter::assign(const std::string& target, ir::ValueId value) {
  if (std::optional<double> number = formulas_.constantOf(value)) {
    block(fmt::format("FN 0: {} = {}", target, formulas_.signedNumber(*number)));
    return;
  }
  block(fmt::format("{} = {}", target, formulas_.value(value).text));
}

int TncBlockWriter::newLabel() {
  if (nextLabel_ == profile_.maximumLabel + 1) {
    errors_.push_back(fmt::format("the program needs more labels than the TNC's LBL 1-LBL {}",
                                  profile_.maximumLabel));
  }
  return nextLabel_++;
}

void TncBlockWriter::label(int number) {
  block(fmt::format("LBL {}", number));
  forget();
}

void TncBlockWriter::jump(int label) {
  block(fmt::format("FN 9: IF +0 EQU +0 GOTO LBL {}", label));
}

void TncBlockWriter::comparison(int fn, ir::ValueId left, ir::ValueId right, int label) {
  std::string a = operand(left);
  std::string b = operand(right);
  std::string_view name = fn == Equal ? "EQU" : fn == NotEqual ? "NE" : fn == Greater ? "GT" : "LT";
  block(fmt::format("FN {}: IF {} {} {} GOTO LBL {}", fn, a, name, b, label));
}

// Jumps to `label` when the condition holds (negated: when it does not).
// The TNC compares with EQU, NE, GT and LT: `a <= b` is two jumps.
void TncBlockWriter::compare(ir::ValueId condition, bool negated, int label) {
  const ir::Instruction& instruction = formulas_.definitionOf(condition);
  const std::vector<ir::ValueId>& operands = instruction.operands;
  switch (instruction.opcode) {
  case Opcode::ConstBool:
    if ((instruction.number != 0) != negated) {
      jump(label);
    }
    return;
  case Opcode::Not:
    compare(operands[0], !negated, label);
    return;
  case Opcode::And:
  case Opcode::Or: {
    // Jumps when both hold (and, or the negation of or), else when either.
    bool both = (instruction.opcode == Opcode::And) != negated;
    if (!both) {
      compare(operands[0], negated, label);
      compare(operands[1], negated, label);
      return;
    }
    int skip = newLabel();
    compare(operands[0], !negated, skip);
    compare(operands[1], negated, label);
    this->label(skip);
    return;
  }
  default:
    break;
  }
  Opcode opcode = instruction.opcode;
  if (negated) {
    opcode = opcode == Opcode::Lt   ? Opcode::Ge
             : opcode == Opcode::Le ? Opcode::Gt
             : opcode == Opcode::Gt ? Opcode::Le
             : opcode == Opcode::Ge ? Opcode::Lt
             : opcode == Opcode::Eq ? Opcode::Ne
             : opcode == Opcode::Ne ? Opcode::Eq
                                    : opcode;
  }
  ir::ValueId a = operands.empty() ? condition : operands[0];
  ir::ValueId b = operands.size() < 2 ? condition : operands[1];
  switch (opcode) {
  case Opcode::Lt:
    comparison(Less, a, b, label);
    return;
  case Opcode::Gt:
    comparison(Greater, a, b, label);
    return;
  case Opcode::Le:
    comparison(Less, a, b, label);
    comparison(Equal, a, b, label);
    return;
  case Opcode::Ge:
    comparison(Greater, a, b, label);
    comparison(Equal, a, b, label);
    return;
  case Opcode::Eq:
    comparison(Equal, a, b, label);
    return;
  case Opcode::Ne:
    comparison(NotEqual, a, b, label);
    return;
  default:
    errors_.push_back(fmt::format("a TNC program cannot test the condition {}",
                                  ir::opcodeInfo(instruction.opcode).spelling));
    return;
  }
}

void TncBlockWriter::jumpIf(ir::ValueId condition, int label) {
  compare(condition, false, label);
}

void TncBlockWriter::jumpUnless(ir::ValueId condition, int label) {
  compare(condition, true, label);
}

void TncBlockWriter::forget() {
  words_.clear();
  feed_.clear();
  z_.reset();
}

std::string TncBlockWriter::word(char letter, ir::ValueId value, bool coordinate) {
  std::optional<double> literal = formulas_.constantOf(value);
  TncWord current{operand(value, coordinate),
                  literal ? std::nullopt : std::optional<std::uint32_t>(value.index)};
  auto known = words_.find(letter);
  if (known != words_.end() && known->second == current) {
    return "";
  }
  words_[letter] = current;
  return fmt::format(" {}{}", letter, current.text);
}

std::string TncBlockWriter::feedWord(ir::ValueId feedRate) {
  std::string text;
  if (std::optional<double> literal = formulas_.constantOf(feedRate)) {
    text = formulas_.number(*literal);
  } else {
    text = operand(feedRate).substr(1); // `FQL5`: the parameter without its sign
  }
  bool known = formulas_.constantOf(feedRate) && text == feed_;
  feed_ = formulas_.constantOf(feedRate) ? text : "";
  return known ? "" : " F" + text;
}

void TncBlockWriter::motion(std::string text, ir::ValueId z) {
  text += pendingWords_;
  pendingWords_.clear();
  block(std::move(text));
  bool changes = !z_ || !(*z_ == z);
  z_ = z;
  if (zParameter_ >= 0 && changes) {
    assign(tncParameterName(zParameter_), z);
  }
}

void TncBlockWriter::flushWords(std::string_view words) {
  std::string text = pendingWords_ + (words.empty() ? "" : " " + std::string(words));
  pendingWords_.clear();
  if (!text.empty()) {
    block("L" + text);
  }
}

void TncBlockWriter::rapid(ir::ValueId x, ir::ValueId y, ir::ValueId z) {
  std::optional<double> target = formulas_.constantOf(z);
  std::optional<double> from = z_ ? formulas_.constantOf(*z_) : std::nullopt;
  bool descending = target && from && *target < *from - 1e-12;
  auto line = [&](std::string words, ir::ValueId height) {
    if (!words.empty()) {
      motion("L" + words + " R0 FMAX", height);
    }
  };
  // A word may first write the block that computes it: one at a time.
  auto plane = [&] {
    std::string yWord = word('Y', y);
    return word('X', x) + yWord;
  };
  if (descending) {
    ir::ValueId before = *z_;
    line(plane(), before);
    line(word('Z', z), z);
  } else {
    line(word('Z', z), z);
    line(plane(), z);
  }
  feed_.clear(); // FMAX is not modal, but the F before it is: written again to be plain
}

void TncBlockWriter::climb(ir::ValueId z) {
  std::string words = word('Z', z);
  if (!words.empty()) {
    motion("L" + words + " R0 FMAX", z);
  }
  feed_.clear();
}

void TncBlockWriter::feed(ir::ValueId x, ir::ValueId y, ir::ValueId z, ir::ValueId feedRate) {
  // Z, Y, X: the order their scratch parameters have always been assigned in.
  std::string zWord = word('Z', z);
  std::string yWord = word('Y', y);
  std::string plane = word('X', x) + yWord;
  std::string words = plane + zWord;
  if (words.empty()) {
    return;
  }
  if (!plane.empty() && !pendingRadius_.empty()) {
    words += " " + pendingRadius_;
    pendingRadius_.clear();
  }
  motion("L" + words + feedWord(feedRate), z);
}

void TncBlockWriter::arc(bool clockwise, std::span<const ir::ValueId> operands) {
  if (!pendingRadius_.empty()) {
    errors_.push_back(fmt::format("{} on an arc: the TNC switches radius compensation on and off "
                                  "on a straight line",
                                  pendingRadius_));
    pendingRadius_.clear();
  }
  // Each operand may first write the block that computes it: one at a time.
  std::string centreY = operand(operands[4], true);
  std::string centreX = operand(operands[3], true);
  block(fmt::format("CC IX{} IY{}", centreX, centreY));
  words_.erase('X');
  words_.erase('Y');
  std::string yWord = word('Y', operands[1]);
  std::string words = word('X', operands[0]) + yWord;
  ir::ValueId z = operands[2];
  std::optional<double> to = formulas_.constantOf(z);
  std::optional<double> from = z_ ? formulas_.constantOf(*z_) : std::nullopt;
  bool planar = z_ && (*z_ == z || (to && from && *to == *from));
  if (!planar) {
    std::string rise;
    if (to && from) {
      rise = formulas_.signedCoordinate(*to - *from);
    } else {
      if (!z_ && zParameter_ < 0) {
        errors_.push_back("a helix whose start height the printer does not know");
        return;
      }
      std::string start = z_ ? operand(*z_, true) : "+" + tncParameterName(zParameter_);
      std::string end = operand(z, true);
      std::string difference = scratch();
      block(fmt::format("{} = {} - {}", difference, term(end), term(start)));
      rise = "+" + difference;
    }
    words += " IZ" + rise;
    words_.erase('Z');
  }
  words += clockwise ? " DR-" : " DR+";
  motion("C" + words + feedWord(operands[5]), z);
}

void TncBlockWriter::spline(std::span<const ir::ValueId> operands) {
  std::string text = "SPL";
  for (int axis = 0; axis < 3; ++axis) {
    text += fmt::format(" {}{}", "XYZ"[axis], operand(operands[axis], true));
  }
  for (int axis = 0; axis < 3; ++axis) {
    for (int k = 0; k < 3; ++k) {
      std::optional<double> coefficient = formulas_.constantOf(operands[3 + 3 * axis + k]);
      if (!coefficient) {
        errors_.push_back("an SPL coefficient the compiler does not know (the TNC takes numbers)");
        return;
      }
      text +=
          fmt::format(" K{}{}{}", 3 - k, "XYZ"[axis], formulas_.splineCoefficient(*coefficient));
    }
  }
  for (char letter : {'X', 'Y', 'Z'}) {
    words_.erase(letter); // the next block writes its coordinates again
  }
  motion(text + feedWord(operands[12]), operands[2]);
}

} // namespace cncc::backends
