// Reads a LinuxCNC program as LinuxCNC's interpreter does: outside comments
// a line's spaces are dropped and its letters lower-cased; `( )` comments
// (not nested) and `;` to the end of the line; a `%` on the first line
// makes a second `%` end the program. Then the o-word structure is paired:
// every loop, `if` and `sub` closed by its own name, crossings refused.
#include "linuxcnc_blocks.h"

#include <fmt/format.h>

#include <array>
#include <cctype>

namespace cncc::backends::sim::linuxcnc {

namespace {

struct KeywordSpelling {
  std::string_view text;
  Keyword keyword;
};

// Longer words first where one begins another (elseif, else; endsub, ...).
constexpr std::array<KeywordSpelling, 15> keywordSpellings{{
    {"endsub", Keyword::EndSub},
    {"endwhile", Keyword::EndWhile},
    {"endif", Keyword::EndIf},
    {"endrepeat", Keyword::EndRepeat},
    {"elseif", Keyword::ElseIf},
    {"else", Keyword::Else},
    {"sub", Keyword::Sub},
    {"call", Keyword::Call},
    {"return", Keyword::Return},
    {"while", Keyword::While},
    {"do", Keyword::Do},
    {"if", Keyword::If},
    {"repeat", Keyword::Repeat},
    {"break", Keyword::Break},
    {"continue", Keyword::Continue},
}};

std::string_view trimmed(std::string_view text) {
  std::size_t first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) {
    return {};
  }
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

std::string lowerCase(std::string_view text) {
  std::string lower(text);
  for (char& c : lower) {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return lower;
}

// `(debug, ...)` and its kin; other comments say nothing to the machine.
void readComment(std::string_view comment, Block& block) {
  constexpr std::array<std::pair<std::string_view, Message::Kind>, 4> kinds{{
      {"abort,", Message::Kind::Abort},
      {"debug,", Message::Kind::Debug},
      {"print,", Message::Kind::Print},
      {"msg,", Message::Kind::Msg},
  }};
  std::string_view text = trimmed(comment);
  std::string head = lowerCase(text.substr(0, 6));
  for (const auto& [prefix, kind] : kinds) {
    if (head.starts_with(prefix)) {
      block.messages.push_back({kind, std::string(text.substr(prefix.size()))});
      return;
    }
  }
}

// The code of the line without spaces, in lower case; the comments go into
// the block's messages.
std::string codeOfLine(std::string_view line, Block& block) {
  std::string code;
  for (std::size_t i = 0; i < line.size(); ++i) {
    char c = line[i];
    if (c == ';') {
      break;
    }
    if (c == '(') {
      std::size_t close = line.find_first_of("()", i + 1);
      if (close == std::string_view::npos || line[close] == '(') {
        failAt(block.context(), close == std::string_view::npos
                                    ? "a comment '(' is not closed on its line"
                                    : "comments do not nest: '(' inside '( )'");
      }
      readComment(line.substr(i + 1, close - i - 1), block);
      i = close;
      continue;
    }
    if (c == ')') {
      failAt(block.context(), "')' without its '('");
    }
    if (c == ' ' || c == '\t') {
      continue;
    }
    if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) {
      failAt(block.context(),
             fmt::format("the character {:#04x} is not G-code", static_cast<unsigned char>(c)));
    }
    code.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  }
  return code;
}

void readOWord(Cursor& cursor, Block& block) {
  block.kind = Block::Kind::OWord;
  if (cursor.consume('<')) {
    block.name = "<" + parseParameterName(cursor) + ">";
  } else {
    while (cursor.peek() >= '0' && cursor.peek() <= '9') {
      block.name.push_back(cursor.peek());
      cursor.consume(cursor.peek());
    }
    if (block.name.empty()) {
      cursor.fail("an o-word needs a number or a <name> (o#n is not modelled)");
    }
  }
  const KeywordSpelling* spelling = nullptr;
  for (const KeywordSpelling& candidate : keywordSpellings) {
    if (cursor.consumeWord(candidate.text)) {
      spelling = &candidate;
      break;
    }
  }
  if (spelling == nullptr) {
    cursor.fail(fmt::format("o{} without sub, call, while, do, if, repeat or another o-word "
                            "keyword",
                            block.name));
  }
  block.keyword = spelling->keyword;
  switch (block.keyword) {
  case Keyword::While:
  case Keyword::If:
  case Keyword::ElseIf:
  case Keyword::Repeat:
    if (cursor.peek() != '[') {
      cursor.fail(fmt::format("o{} {} needs a [condition]", block.name, spelling->text));
    }
    block.argument = parseValue(cursor);
    break;
  case Keyword::EndSub:
  case Keyword::Return:
    if (cursor.peek() == '[') {
      block.argument = parseValue(cursor);
    }
    break;
  case Keyword::Call:
    while (cursor.peek() == '[') {
      block.callArguments.push_back(parseValue(cursor));
    }
    break;
  default:
    break;
  }
  if (!cursor.atEnd()) {
    cursor.fail(
        fmt::format("'{}' after o{} {}", cursor.rest().substr(0, 12), block.name, spelling->text));
  }
}

void readWords(Cursor& cursor, Block& block) {
  block.kind = Block::Kind::Words;
  while (!cursor.atEnd()) {
    char c = cursor.peek();
    if (cursor.consume('#')) {
      ParameterSetting setting;
      if (cursor.consume('<')) {
        setting.named = true;
        setting.name = parseParameterName(cursor);
      } else {
        setting.number = parseValue(cursor);
      }
      cursor.expect('=', "'=' after a parameter at the start of a setting");
      setting.value = parseValue(cursor);
      block.settings.push_back(std::move(setting));
    } else if (c >= 'a' && c <= 'z') {
      cursor.consume(c);
      block.words.push_back({c, parseValue(cursor)});
    } else {
      cursor.fail(fmt::format("'{}' where a letter or a parameter setting should be", c));
    }
  }
}

Block readBlock(std::string_view line, int lineNumber) {
  Block block;
  block.line = lineNumber;
  block.text = std::string(trimmed(line));
  std::string code = codeOfLine(line, block);
  Cursor cursor(code, block.context());
  if (cursor.peek() == '/') {
    cursor.fail("block delete '/' is not modelled");
  }
  if (cursor.peek() == 'n') { // a line number
    cursor.consume('n');
    while ((cursor.peek() >= '0' && cursor.peek() <= '9') || cursor.peek() == '.') {
      cursor.consume(cursor.peek());
    }
  }
  if (cursor.atEnd()) {
    return block;
  }
  if (cursor.consume('o')) {
    readOWord(cursor, block);
  } else {
    readWords(cursor, block);
  }
  return block;
}

// The open o-word constructs while the file is read.
class StructurePairing {
public:
  explicit StructurePairing(Program& program) : program_(program) {}

  void add(std::size_t index);
  void finish();

private:
  struct Open {
    std::size_t index = 0;
    std::size_t lastBranch = 0; // if: the latest if, elseif or else
    std::vector<std::size_t> branches{};
    bool elseSeen = false;
  };

  Block& at(std::size_t index) { return program_.blocks[index]; }
  [[noreturn]] void mismatch(const Block& block) const;
  Open& top(const Block& block, Keyword opening);
  void closeIf(Open& open, std::size_t index);

  Program& program_;
  std::vector<Open> open_;
};

std::string describe(const Block& block) {
  return fmt::format("o{} {}", block.name, keywordName(block.keyword));
}

void StructurePairing::mismatch(const Block& block) const {
  if (open_.empty()) {
    failAt(block.context(), fmt::format("{} without its opening o-word", describe(block)));
  }
  const Block& opening = program_.blocks[open_.back().index];
  failAt(block.context(), fmt::format("{} where {} (line {}) is still open", describe(block),
                                      describe(opening), opening.line));
}

StructurePairing::Open& StructurePairing::top(const Block& block, Keyword opening) {
  if (open_.empty()) {
    mismatch(block);
  }
  const Block& candidate = program_.blocks[open_.back().index];
  if (candidate.keyword != opening || candidate.name != block.name) {
    mismatch(block);
  }
  return open_.back();
}

void StructurePairing::closeIf(Open& open, std::size_t index) {
  at(open.lastBranch).partner = index;
  open.lastBranch = index;
  open.branches.push_back(index);
}

void StructurePairing::add(std::size_t index) {
  Block& block = at(index);
  auto pair = [&](Open& open) {
    block.partner = open.index;
    at(open.index).partner = index;
  };
  switch (block.keyword) {
  case Keyword::Sub:
    if (!open_.empty()) {
      failAt(block.context(), fmt::format("{} inside {}: subroutines are defined at the top level",
                                          describe(block), describe(at(open_.back().index))));
    }
    if (!program_.subs.emplace(block.name, index).second) {
      failAt(block.context(), fmt::format("o{} is defined twice", block.name));
    }
    open_.push_back({index});
    break;
  case Keyword::While:
    if (!open_.empty() && at(open_.back().index).keyword == Keyword::Do &&
        at(open_.back().index).name == block.name) {
      block.closesDo = true;
      pair(open_.back());
      open_.pop_back();
    } else {
      open_.push_back({index});
    }
    break;
  case Keyword::Do:
  case Keyword::Repeat:
    open_.push_back({index});
    break;
  case Keyword::If:
    open_.push_back({index, index, {index}});
    break;
  case Keyword::ElseIf:
  case Keyword::Else: {
    Open& open = top(block, Keyword::If);
    if (open.elseSeen) {
      failAt(block.context(), fmt::format("{} after o{} else", describe(block), block.name));
    }
    open.elseSeen = block.keyword == Keyword::Else;
    closeIf(open, index);
    break;
  }
  case Keyword::EndIf: {
    Open& open = top(block, Keyword::If);
    closeIf(open, index);
    for (std::size_t branch : open.branches) {
      at(branch).end = index;
    }
    open_.pop_back();
    break;
  }
  case Keyword::EndSub:
  case Keyword::EndWhile:
  case Keyword::EndRepeat: {
    Keyword opening = block.keyword == Keyword::EndSub     ? Keyword::Sub
                      : block.keyword == Keyword::EndWhile ? Keyword::While
                                                           : Keyword::Repeat;
    pair(top(block, opening));
    open_.pop_back();
    break;
  }
  case Keyword::Return:
    if (open_.empty() || at(open_.front().index).keyword != Keyword::Sub ||
        at(open_.front().index).name != block.name) {
      failAt(block.context(), fmt::format("{} outside o{} sub", describe(block), block.name));
    }
    block.partner = open_.front().index;
    break;
  case Keyword::Break:
  case Keyword::Continue:
    for (auto open = open_.rbegin(); open != open_.rend(); ++open) {
      const Block& loop = at(open->index);
      // LinuxCNC's break and continue leave while and do loops, not repeat.
      bool isLoop = loop.keyword == Keyword::While || loop.keyword == Keyword::Do;
      if (isLoop && loop.name == block.name) {
        block.partner = open->index;
        return;
      }
    }
    failAt(block.context(),
           fmt::format("{} outside a loop o{} (while or do)", describe(block), block.name));
  case Keyword::Call:
    break;
  }
}

void StructurePairing::finish() {
  if (open_.empty()) {
    return;
  }
  const Block& block = at(open_.back().index);
  std::string_view closing = block.keyword == Keyword::Sub      ? "endsub"
                             : block.keyword == Keyword::Do     ? "while"
                             : block.keyword == Keyword::If     ? "endif"
                             : block.keyword == Keyword::Repeat ? "endrepeat"
                                                                : "endwhile";
  failAt(block.context(), fmt::format("{} has no o{} {} before the end of the program",
                                      describe(block), block.name, closing));
}

} // namespace

std::string_view keywordName(Keyword keyword) {
  for (const KeywordSpelling& spelling : keywordSpellings) {
    if (spelling.keyword == keyword) {
      return spelling.text;
    }
  }
  return "?";
}

Program readLinuxcncProgram(std::string_view text) {
  Program program;
  StructurePairing pairing(program);
  bool percentMode = false;
  bool anyLine = false;
  int lineNumber = 0;
  while (!text.empty()) {
    std::size_t newline = text.find('\n');
    std::string_view line = text.substr(0, newline);
    text = newline == std::string_view::npos ? std::string_view() : text.substr(newline + 1);
    ++lineNumber;
    if (!line.empty() && line.back() == '\r') {
      line.remove_suffix(1);
    }
    if (trimmed(line) == "%") {
      if (percentMode) {
        program.endsWithPercent = true;
        break;
      }
      if (anyLine) {
        failAt({lineNumber, line}, "'%' after the program started: only the first line opens "
                                   "a '%' program");
      }
      percentMode = true;
      continue;
    }
    anyLine = anyLine || !trimmed(line).empty();
    program.blocks.push_back(readBlock(line, lineNumber));
    if (program.blocks.back().kind == Block::Kind::OWord) {
      pairing.add(program.blocks.size() - 1);
    }
  }
  pairing.finish();
  return program;
}

} // namespace cncc::backends::sim::linuxcnc
