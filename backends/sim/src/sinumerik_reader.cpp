#include "sinumerik_blocks.h"

#include <fmt/format.h>

#include <cctype>
#include <charconv>

namespace cncc::backends::sinumerik {

ProgramError::ProgramError(std::string program, int line, const std::string& message)
    : std::runtime_error(
          fmt::format("{}line {}: {}", program.empty() ? "" : program + ", ", line, message)),
      program_(std::move(program)), line_(line) {}

namespace {

bool isLetter(char c) {
  return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}

bool isDigit(char c) {
  return std::isdigit(static_cast<unsigned char>(c)) != 0;
}

std::string upper(std::string_view text) {
  std::string out;
  for (char c : text) {
    out += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  }
  return out;
}

class LineReader {
public:
  LineReader(std::string_view text, int line, const std::string& program)
      : text_(text), line_(line), program_(program) {}

  SinumerikBlock read() {
    SinumerikBlock block;
    block.line = line_;
    while (skipSpace()) {
      block.words.push_back(word());
    }
    return block;
  }

private:
  [[noreturn]] void fail(const std::string& message) const {
    throw ProgramError(program_, line_, message);
  }

  bool skipSpace() {
    while (at_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[at_]))) {
      ++at_;
    }
    return at_ < text_.size();
  }

  SinumerikWord word() {
    if (!isLetter(text_[at_])) {
      fail(fmt::format("unexpected '{}'", text_[at_]));
    }
    std::size_t begin = at_;
    // An address is its letters; a name (subprogram, keyword) may go on
    // with digits and underscores after two letters.
    while (at_ < text_.size() && isLetter(text_[at_])) {
      ++at_;
    }
    if (at_ - begin >= 2) {
      while (at_ < text_.size() && (isLetter(text_[at_]) || isDigit(text_[at_]))) {
        ++at_;
      }
    }
    SinumerikWord word;
    word.address = upper(text_.substr(begin, at_ - begin));
    if (at_ < text_.size() && text_[at_] == '(') {
      std::size_t close = text_.find(')', at_);
      if (close == std::string_view::npos) {
        fail("a '(' without ')'");
      }
      word.text = upper(text_.substr(at_ + 1, close - at_ - 1));
      at_ = close + 1;
      return word;
    }
    bool assigned = at_ < text_.size() && text_[at_] == '=';
    if (assigned) {
      ++at_;
      skipSpace();
      if (at_ < text_.size() && text_[at_] == '"') {
        std::size_t close = text_.find('"', at_ + 1);
        if (close == std::string_view::npos) {
          fail("a string without its closing '\"'");
        }
        word.text = std::string(text_.substr(at_ + 1, close - at_ - 1));
        at_ = close + 1;
        return word;
      }
    }
    std::size_t numberBegin = at_;
    while (at_ < text_.size() &&
           (isDigit(text_[at_]) || text_[at_] == '.' || text_[at_] == '-' || text_[at_] == '+')) {
      ++at_;
    }
    if (numberBegin == at_) {
      if (assigned) {
        fail(fmt::format("{}= needs a number (expressions are not modelled)", word.address));
      }
      return word;
    }
    std::string_view digits = text_.substr(numberBegin, at_ - numberBegin);
    if (digits.front() == '+') {
      digits.remove_prefix(1);
    }
    double value = 0;
    auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (error != std::errc() || end != digits.data() + digits.size()) {
      fail(fmt::format("'{}' is not a number", digits));
    }
    word.value = value;
    return word;
  }

  std::string_view text_;
  std::size_t at_ = 0;
  int line_;
  const std::string& program_;
};

// `%_N_NAME_MPF` / `%_N_NAME_SPF`: the program's name and kind.
std::optional<SinumerikProgramUnit> archiveHeader(std::string_view line) {
  if (line.size() < 8 || line.substr(0, 3) != "%_N") {
    return std::nullopt;
  }
  std::string text = upper(line.substr(4));
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) {
    text.pop_back();
  }
  if (text.size() < 5) {
    return std::nullopt;
  }
  std::string suffix = text.substr(text.size() - 4);
  if (suffix != "_MPF" && suffix != "_SPF") {
    return std::nullopt;
  }
  SinumerikProgramUnit unit;
  unit.name = text.substr(0, text.size() - 4);
  unit.subprogram = suffix == "_SPF";
  return unit;
}

} // namespace

std::vector<SinumerikProgramUnit> readSinumerikText(std::string_view text) {
  std::vector<SinumerikProgramUnit> units(1);
  int lineNumber = 0;
  std::size_t at = 0;
  while (at <= text.size()) {
    std::size_t end = text.find('\n', at);
    std::string_view line =
        text.substr(at, end == std::string_view::npos ? text.size() - at : end - at);
    ++lineNumber;
    at = end == std::string_view::npos ? text.size() + 1 : end + 1;
    if (std::optional<SinumerikProgramUnit> header = archiveHeader(line)) {
      if (units.size() == 1 && units.front().name.empty() && units.front().blocks.empty()) {
        units.clear();
      }
      units.push_back(std::move(*header));
      continue;
    }
    std::size_t comment = line.find(';');
    std::string_view code = line.substr(0, comment);
    LineReader reader(code, lineNumber, units.back().name);
    SinumerikBlock block = reader.read();
    if (!block.words.empty()) {
      units.back().blocks.push_back(std::move(block));
    }
  }
  for (std::size_t i = 0; i < units.size(); ++i) {
    if (!units[i].subprogram) {
      std::swap(units[0], units[i]);
      return units;
    }
  }
  throw ProgramError("", 1, "the text has no main program (_MPF)");
}

} // namespace cncc::backends::sinumerik
