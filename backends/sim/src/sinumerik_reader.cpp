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
    if (at_ < text_.size() && text_[at_] == ':') {
      fail(fmt::format("the label '{}:' and jumps to it (GOTOF, GOTOB) are not modelled",
                       text_.substr(begin, at_ - begin)));
    }
    if (at_ < text_.size() && text_[at_] == '(') {
      std::size_t close = text_.find(')', at_);
      if (close == std::string_view::npos) {
        fail("a '(' without ')'");
      }
      word.text = upper(text_.substr(at_ + 1, close - at_ - 1));
      at_ = close + 1;
      return word;
    }
    if (word.address == "R" && at_ < text_.size() && isDigit(text_[at_])) {
      return parameterAssignment();
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
    if (assigned) {
      assignedValue(word);
      return word;
    }
    std::size_t numberBegin = at_;
    while (at_ < text_.size() &&
           (isDigit(text_[at_]) || text_[at_] == '.' || text_[at_] == '-' || text_[at_] == '+')) {
      ++at_;
    }
    if (numberBegin == at_) {
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

  // What follows `=` up to a space outside brackets: a number, or an
  // expression the block evaluates when it runs.
  std::string_view assignedText() {
    std::size_t begin = at_;
    int depth = 0;
    while (at_ < text_.size() &&
           (depth > 0 || !std::isspace(static_cast<unsigned char>(text_[at_])))) {
      depth += text_[at_] == '(' ? 1 : text_[at_] == ')' ? -1 : 0;
      ++at_;
    }
    if (begin == at_) {
      fail("'=' without a value");
    }
    return text_.substr(begin, at_ - begin);
  }

  void assignedValue(SinumerikWord& word) {
    std::string_view token = assignedText();
    std::string_view digits = token.front() == '+' ? token.substr(1) : token;
    double value = 0;
    auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
    if (!digits.empty() && error == std::errc() && end == digits.data() + digits.size()) {
      word.value = value;
    } else {
      word.expression = upper(token);
    }
  }

  // `R12=...`: parameter 12 takes the value.
  SinumerikWord parameterAssignment() {
    std::size_t begin = at_;
    while (at_ < text_.size() && isDigit(text_[at_])) {
      ++at_;
    }
    SinumerikWord word;
    word.address = "R";
    std::string_view digits = text_.substr(begin, at_ - begin);
    if (digits.size() > 4 || at_ >= text_.size() || text_[at_] != '=') {
      fail(fmt::format("R{} needs '=': a parameter is set as R1=value", digits));
    }
    std::from_chars(digits.data(), digits.data() + digits.size(), word.parameter);
    ++at_;
    assignedValue(word);
    return word;
  }

  std::string_view text_;
  std::size_t at_ = 0;
  int line_;
  const std::string& program_;
};

std::string_view trimmed(std::string_view text) {
  std::size_t first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) {
    return {};
  }
  std::size_t last = text.find_last_not_of(" \t\r");
  return text.substr(first, last - first + 1);
}

// `keyword` followed by a space, a '(' or the end.
bool startsWithKeyword(std::string_view code, std::string_view keyword) {
  return code.substr(0, keyword.size()) == keyword &&
         (code.size() == keyword.size() || code[keyword.size()] == ' ' ||
          code[keyword.size()] == '(' || code[keyword.size()] == '\t');
}

// IF / ELSE / ENDIF / FOR / ENDFOR / WHILE / ENDWHILE lines; nullopt for others.
std::optional<SinumerikBlock> controlBlock(std::string_view line, int lineNumber,
                                           const std::string& program) {
  std::string code = upper(trimmed(line));
  SinumerikBlock block;
  block.line = lineNumber;
  auto rest = [&](std::string_view keyword) {
    return std::string(trimmed(std::string_view(code).substr(keyword.size())));
  };
  if (code == "ELSE" || code == "ENDIF" || code == "ENDFOR" || code == "ENDWHILE") {
    block.control = code == "ELSE"     ? Control::Else
                    : code == "ENDIF"  ? Control::EndIf
                    : code == "ENDFOR" ? Control::EndFor
                                       : Control::EndWhile;
    return block;
  }
  if (startsWithKeyword(code, "IF") || startsWithKeyword(code, "WHILE")) {
    bool isIf = startsWithKeyword(code, "IF");
    block.control = isIf ? Control::If : Control::While;
    block.condition = rest(isIf ? "IF" : "WHILE");
    if (block.condition.empty()) {
      throw ProgramError(program, lineNumber,
                         fmt::format("{} without a condition", isIf ? "IF" : "WHILE"));
    }
    return block;
  }
  if (!startsWithKeyword(code, "FOR")) {
    return std::nullopt;
  }
  std::string loop = rest("FOR");
  std::size_t to = loop.find(" TO ");
  if (to == std::string::npos) {
    throw ProgramError(program, lineNumber, "FOR needs `FOR R1=start TO end`");
  }
  block.control = Control::For;
  block.condition = std::string(trimmed(std::string_view(loop).substr(to + 4)));
  SinumerikBlock counter =
      LineReader(std::string_view(loop).substr(0, to), lineNumber, program).read();
  if (counter.words.size() != 1 || counter.words[0].parameter < 0 || block.condition.empty()) {
    throw ProgramError(program, lineNumber, "FOR needs `FOR R1=start TO end`");
  }
  block.counter = counter.words[0];
  return block;
}

// Pairs IF/ELSE/ENDIF, FOR/ENDFOR and WHILE/ENDWHILE inside one program.
void matchControl(SinumerikProgramUnit& unit) {
  std::vector<std::size_t> open;
  auto fail = [&](const SinumerikBlock& block, const std::string& message) {
    throw ProgramError(unit.name, block.line, message);
  };
  for (std::size_t index = 0; index < unit.blocks.size(); ++index) {
    SinumerikBlock& block = unit.blocks[index];
    Control opener = block.control == Control::Else || block.control == Control::EndIf ? Control::If
                     : block.control == Control::EndFor   ? Control::For
                     : block.control == Control::EndWhile ? Control::While
                                                          : Control::None;
    if (block.control == Control::If || block.control == Control::For ||
        block.control == Control::While) {
      open.push_back(index);
      continue;
    }
    if (opener == Control::None) {
      continue;
    }
    if (open.empty() ||
        (unit.blocks[open.back()].control != opener &&
         !(opener == Control::If && unit.blocks[open.back()].control == Control::Else))) {
      fail(block, "a closing word without its opening IF, FOR or WHILE (or structures that cross)");
    }
    SinumerikBlock& start = unit.blocks[open.back()];
    if (block.control == Control::Else && start.control == Control::Else) {
      fail(block, "a second ELSE for one IF");
    }
    start.partner = index;
    if (block.control == Control::Else) {
      open.back() = index; // ENDIF closes the ELSE
      continue;
    }
    block.partner = open.back();
    open.pop_back();
  }
  if (!open.empty()) {
    fail(unit.blocks[open.back()], "IF, FOR or WHILE without its end");
  }
}

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
    if (std::optional<SinumerikBlock> control = controlBlock(code, lineNumber, units.back().name)) {
      units.back().blocks.push_back(std::move(*control));
      continue;
    }
    LineReader reader(code, lineNumber, units.back().name);
    SinumerikBlock block = reader.read();
    if (!block.words.empty()) {
      units.back().blocks.push_back(std::move(block));
    }
  }
  for (SinumerikProgramUnit& unit : units) {
    matchControl(unit);
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
