// Runs a LinuxCNC program: o-word control (sub/call/return, while, do,
// if/elseif/else, repeat, break, continue), parameters (#1-#30 local to a
// call, named #<x> local to it, #<_x> global) and messages; the words go to
// the Machine. The settings of a line take effect after all of its values
// are read, as in LinuxCNC: `#1 = 2 X#1` moves to the old #1.
#include "linuxcnc_machine.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace cncc::backends::sim::linuxcnc {

namespace {

// #1-#30: a call's arguments, saved and restored around it.
constexpr int callParameters = 30;
// LinuxCNC's limit on nested calls (its interpreter's MAX_NESTED_CALLS is
// larger in some versions; deeper is refused here).
constexpr std::size_t maximumCallDepth = 10;
constexpr int firstSystemParameter = 5000;

struct Frame {
  std::size_t returnTo = 0;
  std::array<double, callParameters> savedArguments{};
  std::map<std::string, double> named;
  std::map<std::size_t, long long> repeatsLeft; // by Repeat block
};

class Executor : public ParameterSource {
public:
  Executor(const Program& program, const LinuxcncRunOptions& options, LinuxcncRun& run)
      : program_(program), options_(options), run_(run), machine_(run, options),
        numbered_(5602, 0.0), frames_(1) {}

  void run();

  double numbered(int number, const LineContext& context) const override;
  double named(const std::string& name, const LineContext& context) const override;
  bool exists(const std::string& name) const override;

private:
  const Block& at(std::size_t index) const { return program_.blocks[index]; }
  double value(const Expression& expression, const Block& block) const {
    return evaluate(expression, *this, block.context());
  }
  bool condition(const Block& block) const { return value(*block.argument, block) != 0; }
  void messages(const Block& block);
  std::string substituted(std::string_view text) const;
  // Returns true when the program ends.
  bool words(const Block& block);
  std::size_t oWord(std::size_t index);
  std::size_t call(std::size_t index);
  std::size_t returnFromSub(const Block& block);
  std::size_t nextBranch(std::size_t index);
  std::size_t loopControl(std::size_t index);

  const Program& program_;
  const LinuxcncRunOptions& options_;
  LinuxcncRun& run_;
  Machine machine_;
  std::vector<double> numbered_;
  std::map<std::string, double> globals_;
  std::vector<Frame> frames_;
};

double Executor::numbered(int number, const LineContext& context) const {
  if (number >= 5420 && number <= 5422) {
    std::optional<double> coordinate = machine_.position(static_cast<char>('x' + number - 5420));
    if (!coordinate) {
      failAt(context, fmt::format("#{} after G53: the machine's Z is not modelled in work "
                                  "coordinates",
                                  number));
    }
    return *coordinate;
  }
  if (number >= firstSystemParameter) {
    failAt(context, fmt::format("the system parameter #{} is not modelled", number));
  }
  return numbered_[number];
}

double Executor::named(const std::string& name, const LineContext& context) const {
  const std::map<std::string, double>& scope =
      name.starts_with('_') ? globals_ : frames_.back().named;
  auto found = scope.find(name);
  if (found != scope.end()) {
    return found->second;
  }
  // LinuxCNC's predefined parameters (#<_x>, #<_value>, ...) are not
  // modelled: they too are unset here.
  failAt(context, fmt::format("#<{}> is read before it is set (LinuxCNC's predefined "
                              "parameters are not modelled)",
                              name));
}

bool Executor::exists(const std::string& name) const {
  const std::map<std::string, double>& scope =
      name.starts_with('_') ? globals_ : frames_.back().named;
  return scope.count(name) > 0;
}

// `#n` and `#<name>` in a (debug, ...) text become their values, as
// LinuxCNC prints them; what cannot be read stays as written.
std::string Executor::substituted(std::string_view text) const {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    std::size_t digits = i + 1;
    while (digits < text.size() && text[digits] >= '0' && text[digits] <= '9') {
      ++digits;
    }
    if (text[i] == '#' && digits > i + 1 && digits - i < 6) {
      int number = std::stoi(std::string(text.substr(i + 1, digits - i - 1)));
      if (number >= 1 && number < firstSystemParameter) {
        out += fmt::format("{:.6f}", numbered_[number]);
        i = digits - 1;
        continue;
      }
    }
    std::size_t close = text.find('>', i);
    if (text.substr(i, 2) == "#<" && close != std::string_view::npos) {
      std::string name;
      for (char c : text.substr(i + 2, close - i - 2)) {
        if (c != ' ' && c != '\t') {
          name.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
        }
      }
      if (exists(name)) {
        out += fmt::format("{:.6f}", named(name, {}));
        i = close;
        continue;
      }
    }
    out.push_back(text[i]);
  }
  return out;
}

void Executor::messages(const Block& block) {
  for (const Message& message : block.messages) {
    if (message.kind == Message::Kind::Abort) {
      failAt(block.context(), fmt::format("the program aborts:{}", substituted(message.text)));
    }
    run_.messages.push_back(message.kind == Message::Kind::Msg ? message.text
                                                               : substituted(message.text));
  }
}

bool Executor::words(const Block& block) {
  std::vector<std::pair<char, double>> values;
  for (const Word& word : block.words) {
    values.emplace_back(word.letter, value(word.value, block));
  }
  std::vector<std::pair<std::optional<int>, double>> settings;
  for (const ParameterSetting& setting : block.settings) {
    std::optional<int> number;
    if (!setting.named) {
      number = parameterNumber(value(setting.number, block), block.context());
      if (*number >= firstSystemParameter) {
        failAt(block.context(),
               fmt::format("setting the system parameter #{} is not modelled", *number));
      }
    }
    settings.emplace_back(number, value(setting.value, block));
  }
  for (std::size_t i = 0; i < settings.size(); ++i) {
    if (settings[i].first) {
      numbered_[*settings[i].first] = settings[i].second;
    } else {
      const std::string& name = block.settings[i].name;
      (name.starts_with('_') ? globals_ : frames_.back().named)[name] = settings[i].second;
    }
  }
  return machine_.execute(collectWords(values, block.context()), block.context());
}

std::size_t Executor::call(std::size_t index) {
  const Block& block = at(index);
  auto sub = program_.subs.find(block.name);
  if (sub == program_.subs.end()) {
    failAt(block.context(), fmt::format("o{} is not a sub of this file (subroutine files on "
                                        "LinuxCNC's search path are not read)",
                                        block.name));
  }
  if (block.callArguments.size() > callParameters) {
    failAt(block.context(), fmt::format("o{} call with {} arguments: at most {}", block.name,
                                        block.callArguments.size(), callParameters));
  }
  if (frames_.size() > maximumCallDepth) {
    failAt(block.context(), fmt::format("calls nest more than {} deep", maximumCallDepth));
  }
  std::array<double, callParameters> arguments{};
  for (std::size_t i = 0; i < block.callArguments.size(); ++i) {
    arguments[i] = value(block.callArguments[i], block);
  }
  Frame frame;
  frame.returnTo = index + 1;
  std::copy(numbered_.begin() + 1, numbered_.begin() + 1 + callParameters,
            frame.savedArguments.begin());
  std::copy(arguments.begin(), arguments.end(), numbered_.begin() + 1);
  frames_.push_back(std::move(frame));
  return sub->second + 1;
}

std::size_t Executor::returnFromSub(const Block& block) {
  if (block.argument) {
    value(*block.argument, block); // read for its errors; #<_value> is not modelled
  }
  Frame frame = std::move(frames_.back());
  frames_.pop_back();
  std::copy(frame.savedArguments.begin(), frame.savedArguments.end(), numbered_.begin() + 1);
  return frame.returnTo;
}

// After a false `if` or `elseif`: the first branch whose condition holds.
std::size_t Executor::nextBranch(std::size_t index) {
  while (at(index).keyword == Keyword::ElseIf) {
    if (++run_.blocksExecuted > options_.stepLimit) {
      return index; // the main loop reports the limit
    }
    if (condition(at(index))) {
      return index + 1;
    }
    index = at(index).partner;
  }
  return index + 1; // past else or endif
}

std::size_t Executor::loopControl(std::size_t index) {
  const Block& block = at(index);
  const Block& loop = at(block.partner);
  if (block.keyword == Keyword::Break) {
    return loop.partner + 1;
  }
  return loop.keyword == Keyword::While ? block.partner : loop.partner;
}

std::size_t Executor::oWord(std::size_t index) {
  const Block& block = at(index);
  std::map<std::size_t, long long>& repeats = frames_.back().repeatsLeft;
  switch (block.keyword) {
  case Keyword::Sub:
    return block.partner + 1; // a definition: skipped where it stands
  case Keyword::EndSub:
  case Keyword::Return:
    return returnFromSub(block);
  case Keyword::Call:
    return call(index);
  case Keyword::While:
    if (block.closesDo) {
      return condition(block) ? block.partner + 1 : index + 1;
    }
    return condition(block) ? index + 1 : block.partner + 1;
  case Keyword::EndWhile:
    return block.partner;
  case Keyword::Do:
  case Keyword::EndIf:
    return index + 1;
  case Keyword::If:
    return condition(block) ? index + 1 : nextBranch(block.partner);
  case Keyword::ElseIf:
  case Keyword::Else:
    return block.end + 1; // the branch before ran
  case Keyword::Repeat: {
    double count = std::floor(value(*block.argument, block));
    if (count < 1) {
      return block.partner + 1;
    }
    repeats[index] = count > 1e15 ? static_cast<long long>(1e15) : static_cast<long long>(count);
    return index + 1;
  }
  case Keyword::EndRepeat:
    if (--repeats[block.partner] > 0) {
      return block.partner + 1;
    }
    repeats.erase(block.partner);
    return index + 1;
  case Keyword::Break:
  case Keyword::Continue:
    return loopControl(index);
  }
  return index + 1;
}

void Executor::run() {
  std::size_t index = 0;
  const std::vector<Block>& blocks = program_.blocks;
  while (index < blocks.size()) {
    const Block& block = blocks[index];
    if (++run_.blocksExecuted > options_.stepLimit) {
      failAt(block.context(),
             fmt::format("more than {} blocks executed: an endless loop?", options_.stepLimit));
    }
    messages(block);
    if (block.kind == Block::Kind::OWord) {
      index = oWord(index);
    } else if (block.kind == Block::Kind::Words && words(block)) {
      return;
    } else {
      ++index;
    }
  }
  if (!program_.endsWithPercent) {
    int last = blocks.empty() ? 0 : blocks.back().line;
    failAt({last, blocks.empty() ? std::string_view() : std::string_view(blocks.back().text)},
           "the program ends without M2, M30 or a closing '%'");
  }
}

} // namespace

} // namespace cncc::backends::sim::linuxcnc

namespace cncc::backends::sim {

LinuxcncRun runLinuxcncProgram(std::string_view text, const LinuxcncRunOptions& options) {
  LinuxcncRun run;
  try {
    linuxcnc::Program program = linuxcnc::readLinuxcncProgram(text);
    linuxcnc::Executor(program, options, run).run();
  } catch (const SimulationError& error) {
    run.error = error;
  }
  return run;
}

} // namespace cncc::backends::sim
