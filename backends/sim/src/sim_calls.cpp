// Calls: G65 macro calls with arguments (their own locals), M98
// subprogram calls (the caller's locals) with repeat counts, and M99.
#include "sim_machine.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string_view>

namespace cncc::backends::sim {

namespace {

// Subprogram and macro calls together (S: Fanuc 0i and M80 manuals).
constexpr int maximumTotalNesting = 10;

} // namespace

std::size_t Machine::programIndex(int number, const Block& block, std::string_view call) const {
  auto found = std::find_if(program_.programs.begin(), program_.programs.end(),
                            [&](const ProgramUnit& unit) { return unit.number == number; });
  if (found == program_.programs.end() || number == 0) {
    failInBlock(block,
                fmt::format("{} P{}: there is no program O{} in the file", call, number, number));
  }
  return static_cast<std::size_t>(found - program_.programs.begin());
}

void Machine::checkCallNesting(const Block& block, bool macroCall) const {
  int macroLevel = options_.runAsMacroCall ? 1 : 0;
  for (const Frame& frame : frames_) {
    macroLevel += frame.subprogram ? 0 : 1;
  }
  macroLevel -= 1; // the main program's frame is no call
  if (macroCall && macroLevel + 1 > profile_.maximumCallNesting) {
    failInBlock(block, fmt::format("macro calls nested {} deep; {} allows {}", macroLevel + 1,
                                   profile_.name, profile_.maximumCallNesting));
  }
  int total = static_cast<int>(frames_.size()) + (options_.runAsMacroCall ? 1 : 0);
  if (total > maximumTotalNesting) {
    failInBlock(block, fmt::format("calls nested {} deep; the controller allows {}", total,
                                   maximumTotalNesting));
  }
}

// M98 P<program> L<repeats>; on Fanuc, without L, P may carry the repeat
// count in front of a four-digit program number (P50100: O100 five times).
void Machine::callSubprogram(const Block& block, const std::map<char, double>& values,
                             std::size_t& next) {
  for (const auto& [letter, value] : values) {
    if (letter != 'P' && letter != 'L' &&
        std::string_view("XYZF").find(letter) == std::string_view::npos) {
      failInBlock(block, fmt::format("the address {} of M98 is not simulated", letter));
    }
  }
  auto whole = [&](char letter) {
    double value = values.at(letter);
    if (value < 0 || value != std::floor(value) || value > 99999999) {
      failInBlock(block, fmt::format("M98 {}{:g}: a whole number is expected", letter, value));
    }
    return static_cast<int>(value);
  };
  if (values.count('P') == 0) {
    failInBlock(block, "M98 without P: which program?");
  }
  int number = whole('P');
  int repeats = 1;
  if (values.count('L') > 0) {
    repeats = whole('L');
  } else if (options_.reading.family == ControllerFamily::Fanuc && number > 9999) {
    repeats = number / 10000;
    number %= 10000;
  }
  if (repeats < 1 || repeats > 9999) {
    failInBlock(block, fmt::format("M98: the repeat count {} is not 1 to 9999", repeats));
  }
  checkCallNesting(block, false);
  Frame callee;
  callee.program = programIndex(number, block, "M98");
  callee.subprogram = true;
  callee.returnBlock = next;
  callee.repeatsLeft = repeats - 1;
  frames_.push_back(callee);
  next = program_.programs[callee.program].first;
}

// The frame a G65 or G66 block calls: P, L and the arguments, evaluated now.
Machine::Frame Machine::macroCallFrame(const Block& block, std::string_view call) {
  Frame callee;
  bool hasProgram = false;
  int repeats = 1;
  for (const Word& word : block.words) {
    if (word.letter == 'G') {
      continue;
    }
    Value value = evaluate(word.value, *this, block);
    if (word.letter == 'P' || word.letter == 'L') {
      if (word.isLiteral && word.literalHasPoint) {
        failInBlock(block,
                    fmt::format("{} of {} is written without a decimal point", word.letter, call));
      }
      int number =
          evaluateWholeNumber(word.value, *this, block, fmt::format("{} {}", call, word.letter));
      if (word.letter == 'L') {
        if (number < 1 || number > 9999) {
          failInBlock(block, fmt::format("{} L{}: the repeat count is 1 to 9999", call, number));
        }
        repeats = number;
        continue;
      }
      callee.program = programIndex(number, block, call);
      hasProgram = true;
      continue;
    }
    std::optional<int> local = profile_.localForLetter(word.letter);
    if (!local || *local >= localCount) {
      failInBlock(block,
                  fmt::format("{} is not a {} argument on {}", word.letter, call, profile_.name));
    }
    callee.arguments[*local] = value; // a vacant argument leaves the local vacant
  }
  if (!hasProgram) {
    failInBlock(block, fmt::format("{} without P: which program?", call));
  }
  callee.repeatsLeft = repeats - 1;
  callee.locals = callee.arguments;
  return callee;
}

void Machine::callMacro(const Block& block, std::size_t& next) {
  Frame callee = macroCallFrame(block, "G65");
  enterMacro(block, callee, next);
}

void Machine::enterMacro(const Block& block, Frame callee, std::size_t& next) {
  checkCallNesting(block, true);
  callee.returnBlock = next;
  frames_.push_back(callee);
  next = program_.programs[callee.program].first;
}

// G66: the call each later block with a move makes (G67 ends it); moves of
// the macro it calls do not call it again.
void Machine::setModalCall(const Block& block) {
  modal_.modalCall = ModalCall{macroCallFrame(block, "G66"), frames_.size()};
}

bool Machine::callAfterMove(const Block& block, std::size_t& next) {
  if (!modal_.modalCall || frames_.size() != modal_.modalCall->level) {
    return false;
  }
  enterMacro(block, modal_.modalCall->frame, next);
  return true;
}

// M99, or M99 P<n>: back to the caller after the call, or at its block Nn.
Machine::Next Machine::returnFromMacro(const Block& block, const std::map<char, double>& values,
                                       std::size_t& next) {
  if (frames_.size() == 1) {
    if (options_.runAsMacroCall && values.empty()) {
      return Next::Stop;
    }
    failInBlock(block, "M99 in the main program restarts it forever");
  }
  for (const auto& [letter, value] : values) {
    if (letter != 'P') {
      failInBlock(block, fmt::format("the address {} of M99 is not simulated", letter));
    }
  }
  Frame& frame = frames_.back();
  if (frame.repeatsLeft > 0) {
    if (!values.empty()) {
      failInBlock(block, "M99 P in a program called with repeats left is not simulated");
    }
    // Each repetition of a macro starts from the arguments again.
    --frame.repeatsLeft;
    if (!frame.subprogram) {
      frame.locals = frame.arguments;
    }
    next = program_.programs[frame.program].first;
    return Next::Jump;
  }
  std::size_t callBlock = frame.returnBlock - 1;
  next = frame.returnBlock;
  frames_.pop_back();
  if (values.count('P') > 0) {
    double number = values.at('P');
    if (number < 1 || number != std::floor(number) || number > 99999999) {
      failInBlock(block, fmt::format("M99 P{:g}: a sequence number is expected", number));
    }
    // As a GOTO from the call: it may leave the caller's loops, not enter one.
    next = findSequenceNumber(static_cast<int>(number), block, callBlock);
  }
  return Next::Jump;
}

} // namespace cncc::backends::sim
