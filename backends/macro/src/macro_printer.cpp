#include "macro_printer.h"

#include "cncc/backends/gcode_writer.h"
#include "cncc/backends/program_format.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>

namespace cncc::backends {

using ir::Opcode;
using ir::ValueId;

namespace {

// `{key}` in `pattern` replaced by `value`.
std::string replaced(std::string pattern, std::string_view key, std::string_view value) {
  std::size_t at = pattern.find(key);
  if (at != std::string::npos) {
    pattern.replace(at, key.size(), value);
  }
  return pattern;
}

} // namespace

PrintedMacroProgram MacroProgramPrinter::print() {
  for (const std::string& pattern : dialect_.programStart) {
    line(frameLine(pattern));
  }
  printHeader();
  if (options_.callable && !dialect_.subroutineStart.empty()) {
    line(frameLine(dialect_.subroutineStart));
  }
  if (dialect_.parametersBeforeSetUp) {
    printParameters();
  }
  for (std::string& block : startBlocks(*options_.setup, options_.inches, options_.blend)) {
    line(std::move(block));
  }
  if (!dialect_.parametersBeforeSetUp) {
    printParameters();
  }
  printTables();
  printRegion(function_.body);
  if (spindleOn_) {
    line("M5");
  }
  for (const std::string& block : options_.setup->end) {
    line(block);
  }
  for (const std::string& pattern : options_.callable ? dialect_.callableEnd : dialect_.mainEnd) {
    line(frameLine(pattern));
  }
  return finish();
}

std::string MacroProgramPrinter::frameLine(const std::string& pattern) const {
  return replaced(replaced(pattern, "{number}", std::to_string(options_.programNumber)), "{name}",
                  options_.subroutineName);
}

// The lines as the machine's setup formats them, and where each comes from.
PrintedMacroProgram MacroProgramPrinter::finish() {
  PrintedMacroProgram printed;
  std::size_t longest = 0;
  int tooLong = 0;
  std::vector<LineOrigin> origins = lineSpans_.origins(lines_.size());
  FormattedProgram formatted = formatProgram(std::move(lines_), *options_.setup, errors_);
  printed.lineOrigins.lines = LineSpans::kept(origins, formatted.printedLine);
  printed.lineOrigins.loops = std::move(loops_);
  printed.variables = std::move(variableMeanings_);
  for (const std::string& block : formatted.lines) {
    if (static_cast<int>(block.size()) > dialect_.maximumLineLength) {
      longest = std::max(longest, block.size());
      ++tooLong;
    }
    printed.text += block;
    printed.text += '\n';
  }
  if (tooLong > 0) {
    errors_.push_back(fmt::format("{} {} exceed {}'s {} characters, the longest has {}", tooLong,
                                  dialect_.linesName, dialect_.controllerName,
                                  dialect_.maximumLineLength, longest));
  }
  return printed;
}

std::string MacroProgramPrinter::commentText(std::string_view text) const {
  auto limit = static_cast<std::size_t>(std::max(0, dialect_.maximumLineLength));
  if (dialect_.comments == CommentStyle::Parenthesised) {
    return "(" + gcodeCommentText(text).substr(0, limit > 2 ? limit - 2 : 0) + ")";
  }
  // `;` comments have no special meaning (`(MSG,..)` would).
  std::string comment = "; ";
  for (char c : text) {
    comment += std::isprint(static_cast<unsigned char>(c)) ? c : ' ';
  }
  comment.resize(std::min(comment.size(), limit));
  return comment;
}

std::string MacroProgramPrinter::keyword(std::string_view words) const {
  std::string text(words);
  if (dialect_.upperCaseComments) {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  }
  return text;
}

// ---- control flow ----------------------------------------------------------

int MacroProgramPrinter::newLabel() {
  int label = nextLabel_++;
  if (label > dialect_.maximumLabel) {
    errors_.push_back(fmt::format("the program needs sequence number N{}, the controller allows "
                                  "up to N{}",
                                  label, dialect_.maximumLabel));
  }
  return label;
}

void MacroProgramPrinter::conditional(const std::string& condition,
                                      const std::string& negatedCondition,
                                      const std::string& statement) {
  if (dialect_.control == ControlWords::OWords) {
    int label = newLabel();
    line(fmt::format("o{} if {}", label, condition));
    line(statement);
    line(fmt::format("o{} endif", label));
    return;
  }
  if (dialect_.hasThen) {
    line(fmt::format("IF {} THEN {}", condition, statement));
    return;
  }
  int label = newLabel();
  line(fmt::format("IF {} GOTO {}", negatedCondition, label));
  line(statement);
  line(fmt::format("N{}", label));
}

void MacroProgramPrinter::choose(const std::string& condition, const std::string& negatedCondition,
                                 const std::string& target, const std::string& whenTrue,
                                 const std::string& whenFalse) {
  if (dialect_.control == ControlWords::OWords) {
    int label = newLabel();
    line(fmt::format("o{} if {}", label, condition));
    line(assignment(target, whenTrue));
    line(fmt::format("o{} else", label));
    line(assignment(target, whenFalse));
    line(fmt::format("o{} endif", label));
    return;
  }
  line(assignment(target, whenFalse));
  conditional(condition, negatedCondition, assignment(target, whenTrue));
}

void MacroProgramPrinter::printRegion(const ir::Region& region) {
  for (ir::InstructionId id : region.instructions) {
    printInstruction(function_.instructions[id]);
  }
}

void MacroProgramPrinter::printInstruction(const ir::Instruction& instruction) {
  InstructionLines marked(lineSpans_, lines_, instruction, currentOrigin_);
  switch (instruction.opcode) {
  case Opcode::Loop:
    printLoop(instruction);
    return;
  case Opcode::If:
    printIf(instruction);
    return;
  case Opcode::Rapid:
    moves_.rapid(instruction.operands[0], instruction.operands[1], instruction.operands[2]);
    return;
  case Opcode::Climb:
    moves_.climb(instruction.operands[0]);
    return;
  case Opcode::Feed:
    moves_.feed(instruction.operands[0], instruction.operands[1], instruction.operands[2],
                instruction.operands[3]);
    return;
  case Opcode::Arc:
    moves_.arc(instruction.index == static_cast<std::uint32_t>(ir::ArcTurn::Clockwise),
               instruction.operands);
    return;
  case Opcode::Nurbs:
    printNurbs(instruction);
    return;
  case Opcode::Spline: // lowered only for the sinumerik target
    errors_.push_back(
        fmt::format("{} has no Sinumerik spline blocks (move.spline)", dialect_.controllerName));
    return;
  case Opcode::Polynomial: // lowered only for the heidenhain target
    errors_.push_back(fmt::format("{} has no polynomial spline blocks (move.polynomial)",
                                  dialect_.controllerName));
    return;
  case Opcode::Spindle:
    printSpindle(instruction);
    return;
  case Opcode::Tool:
    printTool(instruction);
    return;
  case Opcode::Origin:
  case Opcode::Coolant:
  case Opcode::Contouring:
  case Opcode::Home:
    for (std::string& block : setupBlocks(*options_.setup, instruction,
                                          expressions_.coordinateLiteral(instruction.number))) {
      line(std::move(block));
    }
    if (instruction.opcode == Opcode::Home) { // Z is at the machine's reference
      moves_.forget();
    }
    return;
  case Opcode::Compensation:
    moves_.beforeNextPlaneMove(compensationWords(instruction));
    return;
  case Opcode::CornerArc:
    printCornerArc(instruction);
    return;
  case Opcode::Alarm:
    line(alarmStatement(instruction.text, 0));
    return;
  case Opcode::Comment:
    comment(instruction.text);
    return;
  case Opcode::CutBegin: // the cut's own comment says it
  case Opcode::Param:
  case Opcode::LoopNext: // printed by its loop (stepLoop)
    return;
  default:
    break;
  }
  if (instruction.result.valid() && allocation_.inVariable(instruction.result) &&
      !allocation_.isSteppedProduct(instruction.result)) {
    printAssignment(instruction);
  }
}

void MacroProgramPrinter::printLoop(const ir::Instruction& instruction) {
  ++loopDepth_;
  if (loopDepth_ > dialect_.maximumLoopNesting && !reportedLoopDepth_) {
    errors_.push_back(fmt::format("the program nests {} loops, the controller allows {}",
                                  loopDepth_, dialect_.maximumLoopNesting));
    reportedLoopDepth_ = true;
  }
  int label = dialect_.control == ControlWords::OWords ? newLabel() : 0;
  std::string index = expressions_.variable(instruction.result);
  openLoop(instruction, index, label);
  append(loopBody(instruction));
  stepLoop(instruction, index);
  line(dialect_.control == ControlWords::OWords ? fmt::format("o{} endwhile", label)
                                                : fmt::format("END{}", loopDepth_));
  --loopDepth_;
}

// The index's first value and the loop's head.
void MacroProgramPrinter::openLoop(const ir::Instruction& instruction, const std::string& index,
                                   int label) {
  auto head = [&](const std::string& condition) {
    enterLoop(lineSpans_, loops_, lines_.size(), instruction, currentOrigin_);
    line(dialect_.control == ControlWords::OWords
             ? fmt::format("o{} while {}", label, condition)
             : fmt::format("WHILE {} DO{}", condition, loopDepth_));
  };
  auto stepped = allocation_.stepOfLoop.find(instruction.result.index);
  if (stepped != allocation_.stepOfLoop.end() && std::isnan(stepped->second)) {
    // The index variable holds i / high, stepped by 1 / high.
    std::string high = expressions_.operand(instruction.operands[1]);
    line(assignment(index, fmt::format("{}/{}", dialect_.one, high)));
    head(fmt::format("[{} LE {}+.5/{}]", index, dialect_.one, high));
  } else if (stepped != allocation_.stepOfLoop.end()) {
    // The index variable holds i * scale, stepped by the scale.
    double scale = stepped->second;
    double low = *expressions_.constantOf(instruction.operands[0]);
    double high = *expressions_.constantOf(instruction.operands[1]);
    line(assignment(index, expressions_.constant(low * scale)));
    head(fmt::format("[{} {} {}]", index, scale > 0 ? "LE" : "GE",
                     expressions_.constant((high + 0.5) * scale)));
  } else {
    line(assignment(index, expressions_.at(expressions_.value(instruction.operands[0]),
                                           MacroPosition::AssignedValue)));
    bool advancing = ir::loopAdvance(function_, instruction).valid();
    head(fmt::format(
        "[{} {} {}]", index, advancing ? "LT" : "LE",
        expressions_.at(expressions_.value(instruction.operands[1]), MacroPosition::Compared)));
  }
}

void MacroProgramPrinter::stepLoop(const ir::Instruction& instruction, const std::string& index) {
  if (ir::ValueId advance = ir::loopAdvance(function_, instruction); advance.valid()) {
    std::string next = expressions_.at(expressions_.value(advance), MacroPosition::AssignedValue);
    if (next != index) { // the next value was computed into the variable itself
      line(assignment(index, next));
    }
    return;
  }
  auto stepped = allocation_.stepOfLoop.find(instruction.result.index);
  std::string next;
  if (stepped != allocation_.stepOfLoop.end() && std::isnan(stepped->second)) {
    next =
        fmt::format("{}+{}/{}", index, dialect_.one, expressions_.operand(instruction.operands[1]));
  } else if (stepped != allocation_.stepOfLoop.end()) {
    next = fmt::format("{}+{}", index, expressions_.constant(stepped->second));
  } else {
    next = fmt::format("{}+{}", index, dialect_.one);
  }
  line(assignment(index,
                  expressions_.at({next, MacroForm::Additive}, MacroPosition::AssignedValue)));
}

// The body as it prints from the words in force before the loop, then from
// those that also hold after one pass through it, until stable; where the
// dialect keeps no words through loops, from none.
MacroProgramPrinter::Captured MacroProgramPrinter::loopBody(const ir::Instruction& instruction) {
  if (!dialect_.keepsWordsThroughLoops) {
    return capture(instruction.regions[0]);
  }
  ModalState entry = moves_.state();
  Captured body;
  for (int attempt = 0;; ++attempt) {
    if (attempt >= 3) {
      entry.forget();
    }
    int labels = nextLabel_;
    std::size_t errorCount = errors_.size();
    body = capture(instruction.regions[0], entry);
    ModalState agreed = entry.agreedWith(moves_.state());
    if (agreed == entry || attempt >= 3) {
      moves_.state() = agreed;
      return body;
    }
    nextLabel_ = labels;
    errors_.resize(errorCount);
    entry = agreed;
  }
}

// The region's lines, printed from `entry`; the words in force are left as
// it ends.
MacroProgramPrinter::Captured MacroProgramPrinter::capture(const ir::Region& region,
                                                           const ModalState& entry) {
  moves_.state() = entry;
  return captureLines(region);
}

MacroProgramPrinter::Captured MacroProgramPrinter::capture(const ir::Region& region) {
  moves_.forget();
  Captured captured = captureLines(region);
  moves_.forget();
  return captured;
}

// The region's lines and where each comes from, printed aside.
MacroProgramPrinter::Captured MacroProgramPrinter::captureLines(const ir::Region& region) {
  std::vector<std::string> savedLines = std::move(lines_);
  LineSpans savedSpans = std::move(lineSpans_);
  lines_.clear();
  lineSpans_ = LineSpans();
  lineSpans_.start(0, currentOrigin_);
  printRegion(region);
  Captured captured{std::move(lines_), {}};
  captured.origins = lineSpans_.origins(captured.lines.size());
  lines_ = std::move(savedLines);
  lineSpans_ = std::move(savedSpans);
  return captured;
}

// Appends captured lines; the lines after them are the current span's.
void MacroProgramPrinter::append(const Captured& captured) {
  for (std::size_t k = 0; k < captured.lines.size(); ++k) {
    lineSpans_.start(lines_.size(), captured.origins[k]);
    lines_.push_back(captured.lines[k]);
  }
  lineSpans_.start(lines_.size(), currentOrigin_);
}

// IF THEN where one statement is the whole branch; jumps otherwise.
void MacroProgramPrinter::printIf(const ir::Instruction& instruction) {
  if (dialect_.control == ControlWords::OWords) {
    printOWordIf(instruction);
    return;
  }
  ValueId condition = instruction.operands[0];
  Captured thenLines = capture(instruction.regions[0]);
  Captured elseLines =
      instruction.regions.size() > 1 ? capture(instruction.regions[1]) : Captured{};
  if (thenLines.lines.empty() && elseLines.lines.empty()) {
    return;
  }
  bool single =
      elseLines.lines.empty() && thenLines.lines.size() == 1 && thenLines.lines[0].starts_with("#");
  if (single && dialect_.hasThen) {
    line(fmt::format("IF {} THEN {}", expressions_.condition(condition), thenLines.lines[0]));
    return;
  }
  int skipThen = newLabel();
  line(fmt::format("IF {} GOTO {}", expressions_.condition(condition, true), skipThen));
  append(thenLines);
  if (elseLines.lines.empty()) {
    line(fmt::format("N{}", skipThen));
    return;
  }
  int skipElse = newLabel();
  line(fmt::format("GOTO {}", skipElse));
  line(fmt::format("N{}", skipThen));
  append(elseLines);
  line(fmt::format("N{}", skipElse));
}

// `o1 if [c]` .. `o1 else` .. `o1 endif`.
void MacroProgramPrinter::printOWordIf(const ir::Instruction& instruction) {
  int label = newLabel();
  line(fmt::format("o{} if {}", label, expressions_.condition(instruction.operands[0])));
  append(capture(instruction.regions[0]));
  if (instruction.regions.size() > 1 && !instruction.regions[1].instructions.empty()) {
    line(fmt::format("o{} else", label));
    append(capture(instruction.regions[1]));
  }
  line(fmt::format("o{} endif", label));
}

} // namespace cncc::backends
