// Reads a program file into blocks: lines, comments, `%`, `O` and `N`, then
// the statement of each block, then the loop structure of each program.
#include "cncc/backends/sim_program.h"

#include "sim_expression_parser.h"

#include <fmt/format.h>

#include <map>

namespace cncc::backends::sim {

namespace {

bool isDigit(char c) {
  return c >= '0' && c <= '9';
}
bool isUpperLetter(char c) {
  return c >= 'A' && c <= 'Z';
}

[[noreturn]] void failAt(int line, std::string_view text, const std::string& message) {
  throw SimulationError(line, std::string(text), message);
}

// The characters a controller's tape code has; anything else is refused
// rather than guessed at. Strict reading also refuses lower-case letters and
// `;` anywhere; otherwise they are checked after the comments are removed.
void checkCharacters(int line, std::string_view text, const ReadingRules& rules) {
  for (char c : text) {
    auto byte = static_cast<unsigned char>(c);
    if (byte >= 0x80 || (byte < 0x20 && c != '\t')) {
      failAt(line, text, fmt::format("the character 0x{:02X} is not allowed", byte));
    }
    if (!rules.strict) {
      continue;
    }
    if (c >= 'a' && c <= 'z' && !rules.lowerCaseComments) {
      failAt(line, text, "lower-case letters are not allowed; write programs in upper case");
    }
    if (c == ';') {
      failAt(line, text, "';' is not a comment on this controller; use ( )");
    }
  }
}

// Outside comments, lower-case letters are refused however the program is read.
void checkCodeCase(int line, std::string_view text, std::string_view code) {
  for (char c : code) {
    if (c >= 'a' && c <= 'z') {
      failAt(line, text,
             "lower-case letters are only allowed in comments; write the code in upper case");
    }
  }
}

// The blocks of one line: `;` outside comments ends a block, and what
// follows it on the line is the next block.
std::vector<std::string_view> splitAtEndOfBlock(std::string_view text) {
  std::vector<std::string_view> segments;
  std::size_t start = 0;
  bool inComment = false;
  for (std::size_t position = 0; position < text.size(); ++position) {
    char c = text[position];
    if (c == '(') {
      inComment = true;
    } else if (c == ')') {
      inComment = false;
    } else if (c == ';' && !inComment) {
      segments.push_back(text.substr(start, position - start));
      start = position + 1;
    }
  }
  std::string_view rest = text.substr(start);
  if (segments.empty() || rest.find_first_not_of(" \t") != std::string_view::npos) {
    segments.push_back(rest);
  }
  return segments;
}

// Removes `( )` comments; the first one's text goes to `comment`.
std::string stripComments(int line, std::string_view lineText, std::string_view text,
                          std::string& comment) {
  std::string code;
  bool first = true;
  std::size_t position = 0;
  while (position < text.size()) {
    char c = text[position];
    if (c == ')') {
      failAt(line, lineText, "')' without '('");
    }
    if (c != '(') {
      code += c;
      ++position;
      continue;
    }
    std::size_t close = text.find_first_of("()", position + 1);
    if (close == std::string_view::npos) {
      failAt(line, lineText, "a comment without its ')'");
    }
    if (text[close] == '(') {
      failAt(line, lineText, "a comment cannot contain '('");
    }
    if (first) {
      comment = std::string(text.substr(position + 1, close - position - 1));
      first = false;
    }
    code += ' ';
    position = close + 1;
  }
  return code;
}

int parseWholeNumber(BlockCursor& cursor, std::string_view what) {
  if (!isDigit(cursor.peek())) {
    cursor.fail(fmt::format("expected the number of {}", what));
  }
  NumberLiteral literal = parseNumber(cursor);
  if (literal.hasPoint) {
    cursor.fail(fmt::format("{} is a whole number, without a decimal point", what));
  }
  return static_cast<int>(literal.value);
}

void parseAssignment(BlockCursor& cursor, Block& block) {
  cursor.expect('#', "'#'");
  block.variable = parseVariableNumber(cursor);
  cursor.expect('=', "'=' after the variable");
  block.value = parseExpression(cursor);
  checkArithmetic(block.variable, cursor);
  checkArithmetic(block.value, cursor);
}

Expression parseCondition(BlockCursor& cursor) {
  if (cursor.peek() != '[') {
    cursor.fail("expected '[' before the condition");
  }
  Expression condition = parseBracketed(cursor);
  checkCondition(condition, cursor);
  return condition;
}

void parseLoopIdentifier(BlockCursor& cursor, Block& block, std::string_view keyword) {
  block.loopIdentifier = parseWholeNumber(cursor, std::string(keyword) + "m");
  const ControllerProfile& profile = cursor.profile();
  if (block.loopIdentifier < 1 || block.loopIdentifier > profile.maximumLoopIdentifier) {
    cursor.fail(fmt::format("{}{}: m must be 1 to {} on {}", keyword, block.loopIdentifier,
                            profile.maximumLoopIdentifier, profile.name));
  }
}

// IF, GOTO, WHILE, DO, END and assignments; false for address words.
bool parseMacroStatement(BlockCursor& cursor, Block& block) {
  if (cursor.peek() == '#') {
    block.kind = Block::Kind::Assignment;
    parseAssignment(cursor, block);
  } else if (cursor.consumeKeyword("IF")) {
    block.condition = parseCondition(cursor);
    if (cursor.consumeMacroWord("GOTO")) {
      block.kind = Block::Kind::IfGoto;
      block.target = parseExpression(cursor);
      checkArithmetic(block.target, cursor);
    } else if (cursor.consumeMacroWord("THEN")) {
      if (!cursor.profile().hasThen) {
        cursor.fail(fmt::format("{} has no IF .. THEN", cursor.profile().name));
      }
      block.kind = Block::Kind::IfThen;
      if (cursor.peek() != '#') {
        cursor.fail("THEN takes one assignment, `#n = value`");
      }
      parseAssignment(cursor, block);
    } else {
      cursor.failOnAbbreviation();
      cursor.fail("expected GOTO or THEN after the condition");
    }
  } else if (cursor.consumeMacroWord("GOTO")) {
    block.kind = Block::Kind::Goto;
    block.target = parseExpression(cursor);
    checkArithmetic(block.target, cursor);
  } else if (cursor.consumeMacroWord("WHILE")) {
    block.kind = Block::Kind::While;
    block.hasCondition = true;
    block.condition = parseCondition(cursor);
    if (!cursor.consumeKeyword("DO")) {
      cursor.fail("expected DOm after the WHILE condition");
    }
    parseLoopIdentifier(cursor, block, "DO");
  } else if (cursor.consumeKeyword("DO")) {
    block.kind = Block::Kind::While;
    parseLoopIdentifier(cursor, block, "DO");
  } else if (cursor.consumeMacroWord("END")) {
    block.kind = Block::Kind::End;
    parseLoopIdentifier(cursor, block, "END");
  } else {
    cursor.failOnAbbreviation();
    return false;
  }
  if (!cursor.atEnd()) {
    cursor.fail(fmt::format("unexpected '{}' after the statement", cursor.peek()));
  }
  return true;
}

void parseWords(BlockCursor& cursor, Block& block) {
  block.kind = Block::Kind::Words;
  while (!cursor.atEnd()) {
    char letter = cursor.peek();
    if (!isUpperLetter(letter)) {
      cursor.fail(fmt::format("expected an address letter, found '{}'", letter));
    }
    cursor.advance();
    Word word;
    word.letter = letter;
    NumberLiteral literal;
    word.value = parseAddressValue(cursor, &literal, word.isLiteral);
    word.literalHasPoint = literal.hasPoint;
    word.literalDecimals = literal.decimals;
    checkArithmetic(word.value, cursor);
    word.containsRound = containsFunction(word.value, Function::Round);
    for (const Word& previous : block.words) {
      if (previous.letter == letter && letter != 'G' && letter != 'M') {
        cursor.fail(fmt::format("the address {} appears twice in the block", letter));
      }
    }
    block.words.push_back(std::move(word));
  }
}

void parseStatement(BlockCursor& cursor, Block& block) {
  const ControllerProfile& profile = cursor.profile();
  cursor.consume('/'); // block skip: the switch is taken as off
  if (cursor.consume('N')) {
    int number = parseWholeNumber(cursor, "the sequence number");
    if (number < 1 || number > profile.maximumSequenceNumber) {
      cursor.fail(fmt::format("N{}: sequence numbers are 1 to {} on {}", number,
                              profile.maximumSequenceNumber, profile.name));
    }
    block.sequenceNumber = number;
  }
  if (cursor.atEnd()) {
    return;
  }
  if (!parseMacroStatement(cursor, block)) {
    parseWords(cursor, block);
  }
}

Block readBlock(int line, std::string_view lineText, std::string_view text,
                const ControllerProfile& profile, const ReadingRules& rules) {
  Block block;
  block.line = line;
  block.text = std::string(lineText);
  std::string code = stripComments(line, lineText, text, block.comment);
  checkCodeCase(line, lineText, code);
  BlockCursor cursor(code, line, lineText, profile, rules.allowsAbbreviations(profile));
  if (cursor.peek() == 'O') {
    cursor.advance();
    block.kind = Block::Kind::ProgramName;
    block.programNumber = parseWholeNumber(cursor, "the program");
    if (block.programNumber < 1 || block.programNumber > profile.maximumProgramNumber) {
      cursor.fail(fmt::format("O{}: program numbers are 1 to {} on {}", block.programNumber,
                              profile.maximumProgramNumber, profile.name));
    }
    if (!cursor.atEnd()) {
      cursor.fail("nothing but a comment may follow the program number");
    }
    return block;
  }
  parseStatement(cursor, block);
  return block;
}

// Pairs each WHILE/DO with its END inside one program and records which
// loops every block is in.
void matchLoops(ProgramText& program, const ProgramUnit& unit, const ControllerProfile& profile) {
  std::vector<std::size_t> open;
  for (std::size_t index = unit.first; index < unit.end; ++index) {
    Block& block = program.blocks[index];
    if (block.kind == Block::Kind::End) {
      if (open.empty()) {
        failAt(block.line, block.text,
               fmt::format("END{} without DO{}", block.loopIdentifier, block.loopIdentifier));
      }
      Block& loop = program.blocks[open.back()];
      if (loop.loopIdentifier != block.loopIdentifier) {
        failAt(block.line, block.text,
               fmt::format("END{} closes the loop DO{} of line {}: loops may not cross",
                           block.loopIdentifier, loop.loopIdentifier, loop.line));
      }
      block.loops = open;
      block.partner = open.back();
      loop.partner = index;
      open.pop_back();
      continue;
    }
    block.loops = open;
    if (block.kind != Block::Kind::While) {
      continue;
    }
    for (std::size_t outer : open) {
      if (program.blocks[outer].loopIdentifier == block.loopIdentifier) {
        failAt(block.line, block.text,
               fmt::format("DO{} inside the loop DO{} of line {}", block.loopIdentifier,
                           block.loopIdentifier, program.blocks[outer].line));
      }
    }
    if (static_cast<int>(open.size()) >= profile.maximumLoopNesting) {
      failAt(block.line, block.text,
             fmt::format("loops nested {} deep; {} allows {}", open.size() + 1, profile.name,
                         profile.maximumLoopNesting));
    }
    open.push_back(index);
  }
  if (!open.empty()) {
    const Block& loop = program.blocks[open.back()];
    failAt(loop.line, loop.text,
           fmt::format("DO{} without END{}", loop.loopIdentifier, loop.loopIdentifier));
  }
}

bool isPercentLine(std::string_view text) {
  std::size_t first = text.find_first_not_of(" \t");
  return first != std::string_view::npos && text[first] == '%' &&
         text.find_first_not_of(" \t", first + 1) == std::string_view::npos;
}

// Adds one block to `program`, opening a new program unit at an `O` line.
void addBlock(ProgramText& program, Block block, bool& started) {
  if (block.kind == Block::Kind::ProgramName) {
    for (const ProgramUnit& unit : program.programs) {
      if (unit.number == block.programNumber) {
        failAt(block.line, block.text,
               fmt::format("O{} is already the program of line {}", unit.number, unit.line));
      }
    }
    if (!program.programs.empty()) {
      program.programs.back().end = program.blocks.size();
    }
    program.programs.push_back({block.programNumber, block.line, program.blocks.size() + 1, 0});
  } else if (program.programs.empty() && block.kind != Block::Kind::Empty) {
    program.programs.push_back({0, block.line, program.blocks.size(), 0});
  }
  started |= block.kind != Block::Kind::Empty || !block.comment.empty();
  program.blocks.push_back(std::move(block));
}

} // namespace

ControllerFamily controllerFamilyOf(std::string_view profile) {
  return profile == "m80" ? ControllerFamily::Mitsubishi : ControllerFamily::Fanuc;
}

ProgramText readProgram(std::string_view text, const ControllerProfile& profile,
                        const ReadingRules& rules) {
  ProgramText program;
  bool started = false; // a block or an `O` has been read
  int line = 0;
  std::size_t position = 0;
  while (position < text.size()) {
    std::size_t end = text.find('\n', position);
    std::string_view lineText = text.substr(
        position, end == std::string_view::npos ? std::string_view::npos : end - position);
    position = end == std::string_view::npos ? text.size() : end + 1;
    ++line;
    if (!lineText.empty() && lineText.back() == '\r') {
      lineText.remove_suffix(1);
    }
    if (static_cast<int>(lineText.size()) > profile.maximumBlockLength) {
      failAt(line, lineText,
             fmt::format("the block has {} characters; {} allows {}", lineText.size(), profile.name,
                         profile.maximumBlockLength));
    }
    checkCharacters(line, lineText, rules);
    std::vector<std::string_view> segments =
        rules.strict ? std::vector<std::string_view>{lineText} : splitAtEndOfBlock(lineText);
    if (isPercentLine(segments.front())) {
      if (!started) {
        continue; // the leader before the program
      }
      Block block;
      block.kind = Block::Kind::EndOfRecord;
      block.line = line;
      block.text = std::string(lineText);
      program.blocks.push_back(std::move(block));
      break; // the controller reads nothing after the end of record
    }
    for (std::string_view segment : segments) {
      addBlock(program, readBlock(line, lineText, segment, profile, rules), started);
    }
  }
  if (!program.programs.empty()) {
    program.programs.back().end = program.blocks.size();
    if (program.blocks.back().kind == Block::Kind::EndOfRecord) {
      program.programs.back().end -= 1;
    }
  }
  for (const ProgramUnit& unit : program.programs) {
    matchLoops(program, unit, profile);
  }
  return program;
}

} // namespace cncc::backends::sim
