#include "cncc/backends/macro_program.h"
#include "cncc/backends/nurbs_blocks.h"

#include "cncc/backends/gcode_writer.h"
#include "cncc/backends/line_spans.h"
#include "cncc/backends/program_format.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/nurbs_move.h"
#include "macro_expressions.h"
#include "macro_loop_stepping.h"
#include "macro_simplify.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>

namespace cncc::backends {

namespace {

using ir::Opcode;
using ir::ValueId;

// A word in force: a literal, or the IR value it printed (SSA: the same
// value is the same number while it is used, its variable is not reused).
struct ModalWord {
  std::string text;
  std::optional<std::uint32_t> value; // none for a literal
  friend bool operator==(const ModalWord&, const ModalWord&) = default;
};

// The words a move printed last, so that a word already in force is not
// written again. Where control flow joins only what both ways agree on is
// kept (a loop: what holds at its entry and after its body).
struct ModalState {
  std::string motion;
  std::map<char, ModalWord> words;
  std::optional<double> z; // the last literal Z, to order a rapid's axes
  void forget() { *this = ModalState{}; }
  ModalState agreedWith(const ModalState& other) const {
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
  friend bool operator==(const ModalState&, const ModalState&) = default;
};

// Lines printed aside (a loop body, a branch) before they are placed, with
// the CDL span of each.
struct CapturedLines {
  std::vector<std::string> lines;
  std::vector<frontend::SourceSpan> spans;
};

class ProgramPrinter {
public:
  ProgramPrinter(const ir::Function& function, const ir::Allocation& allocation,
                 const SteppedLoops& stepped, const ControllerProfile& profile,
                 const MacroProgramOptions& options, std::vector<std::string>& errors,
                 int* longestBlock = nullptr, MacroProgram* mapped = nullptr)
      : function_(function), allocation_(allocation), profile_(profile), options_(options),
        errors_(errors), longestBlock_(longestBlock), mapped_(mapped),
        expressions_(function, allocation, profile, errors), steppedLoops_(stepped.scaleOfIndex),
        scaledValues_(stepped.scaledValues) {}

  std::string print() {
    line("%");
    line(fmt::format("O{}", options_.programNumber));
    printHeader();
    for (std::string& block : startBlocks(options_.setup, options_.inches)) {
      line(std::move(block));
    }
    printParameterDefaults();
    printFixedParameterChecks();
    printTables();
    printRegion(function_.body);
    if (spindleOn_) {
      line("M5");
    }
    for (const std::string& block : options_.setup.end) {
      line(block);
    }
    line(options_.callable ? "M99" : "M30");
    line("%");
    std::string text;
    std::size_t longest = 0;
    int tooLong = 0;
    std::vector<frontend::SourceSpan> spans = lineSpans_.spans(lines_.size());
    FormattedProgram formatted = formatProgram(std::move(lines_), options_.setup, errors_);
    if (mapped_ != nullptr) {
      mapped_->lineSpans = LineSpans::kept(spans, formatted.printedLine);
      mapped_->variables = std::move(variableMeanings_);
    }
    for (const std::string& block : formatted.lines) {
      if (static_cast<int>(block.size()) > profile_.maximumBlockLength) {
        longest = std::max(longest, block.size());
        ++tooLong;
      }
      text += block;
      text += '\n';
    }
    if (longestBlock_ != nullptr) {
      *longestBlock_ = static_cast<int>(longest);
    }
    if (tooLong > 0) {
      errors_.push_back(fmt::format("{} blocks exceed the controller's {} characters, the longest "
                                    "has {}",
                                    tooLong, profile_.maximumBlockLength, longest));
    }
    return text;
  }

private:
  void line(std::string text) { lines_.push_back(std::move(text)); }

  void comment(std::string_view text) {
    std::string body = gcodeCommentText(text);
    std::size_t room = static_cast<std::size_t>(std::max(0, profile_.maximumBlockLength - 2));
    line("(" + body.substr(0, room) + ")");
  }

  // ---- header ----------------------------------------------------------

  std::string parameterDefault(std::size_t index) const {
    return expressions_.constant(function_.parameters[index].defaultValue);
  }

  void printHeader() {
    comment(fmt::format("{} - PART {}", options_.sourceName, options_.partName));
    if (options_.callable) {
      std::string call = fmt::format("CALL G65 P{}", options_.programNumber);
      for (std::size_t i = 0; i < function_.parameters.size(); ++i) {
        if (std::optional<char> letter =
                profile_.letterForLocal(allocation_.parameterVariables[i])) {
          call += fmt::format(" {}{}", *letter, parameterDefault(i));
        }
      }
      comment(call);
    }
    for (std::size_t i = 0; i < function_.parameters.size(); ++i) {
      comment(fmt::format(
          "#{} {}, {} {}", allocation_.parameterVariables[i], function_.parameters[i].name,
          function_.parameters[i].fixed ? "FIXED AT" : "DEFAULT", parameterDefault(i)));
      variableMeanings_[allocation_.parameterVariables[i]].meaning =
          fmt::format("parameter {}", function_.parameters[i].name);
    }
    for (const auto& [base, tables] : ir::tablesByBase(function_, allocation_)) {
      int count = static_cast<int>(function_.tables[tables.front()].size());
      comment(fmt::format("#{}-#{} TABLE {}, {} VALUES", base, base + count - 1,
                          fmt::join(tables, " AND "), count));
    }
    printValueVariables();
  }

  // For source maps: what `variable` holds (meanings joined when it is
  // reused) and from which statements.
  void noteVariable(int variable, const std::string& upperMeaning, frontend::SourceSpan span) {
    VariableMeaning& noted = variableMeanings_[variable];
    std::string meaning = upperMeaning;
    std::transform(meaning.begin(), meaning.end(), meaning.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    // One variable's: "loop index", "work value".
    meaning = meaning.ends_with("indexes") ? meaning.substr(0, meaning.size() - 2)
                                           : meaning.substr(0, meaning.size() - 1);
    if (noted.meaning.find(meaning) == std::string::npos) {
      noted.meaning += (noted.meaning.empty() ? "" : ", ") + meaning;
    }
    if (span.valid() &&
        std::find(noted.spans.begin(), noted.spans.end(), span) == noted.spans.end()) {
      noted.spans.push_back(span);
    }
  }

  // Variables of values, one line per meaning: `(#4-#8 #10 WORK VALUES)`.
  void printValueVariables() {
    std::set<std::uint32_t> bounds;
    for (const ir::Instruction& instruction : function_.instructions) {
      if (instruction.opcode == Opcode::Loop) {
        bounds.insert(instruction.operands[1].index);
      }
    }
    std::map<std::string, std::set<int>> variables;
    for (const ir::Instruction& instruction : function_.instructions) {
      if (!instruction.result.valid() || instruction.opcode == Opcode::Param ||
          scaledValues_.contains(instruction.result.index)) {
        continue;
      }
      int variable = allocation_.variableOfValue[instruction.result.index];
      if (variable < 0) {
        continue;
      }
      std::string meaning = "WORK VALUES";
      if (instruction.opcode == Opcode::Loop) {
        meaning =
            steppedLoops_.contains(instruction.result.index) ? "CURVE PARAMETERS" : "LOOP INDEXES";
      } else if (bounds.contains(instruction.result.index)) {
        meaning = "STEP COUNTS";
      }
      variables[meaning].insert(variable);
      noteVariable(variable, meaning, instruction.span);
    }
    // Meanings joined on as few lines as the block length allows.
    std::string text;
    auto append = [&](const std::string& piece, const char* separator) {
      if (!text.empty() &&
          static_cast<int>(text.size() + piece.size()) + 4 > profile_.maximumBlockLength) {
        comment(text);
        text.clear();
      }
      text += (text.empty() ? "" : separator) + piece;
    };
    for (const auto& [meaning, set] : variables) {
      for (auto it = set.begin(); it != set.end();) {
        auto last = it;
        auto next = std::next(it);
        while (next != set.end() && *next == *last + 1) {
          last = next++;
        }
        append(last == it ? fmt::format("#{}", *it) : fmt::format("#{}-#{}", *it, *last),
               it == set.begin() ? ", " : " ");
        it = next;
      }
      append(meaning, " ");
    }
    if (!text.empty()) {
      comment(text);
    }
  }

  // A main program assigns the defaults where the operator edits them; a
  // macro, or parameters in common variables, keep what the caller or the
  // operator set and fill in only what is vacant.
  void printParameterDefaults() {
    bool assignAlways = !options_.callable && !options_.parametersInCommon;
    for (std::size_t i = 0; i < function_.parameters.size(); ++i) {
      std::string variable = fmt::format("#{}", allocation_.parameterVariables[i]);
      std::string assignment = fmt::format("{}={}", variable, parameterDefault(i));
      if (assignAlways) {
        line(assignment);
      } else {
        conditional(fmt::format("[{} EQ #0]", variable), fmt::format("[{} NE #0]", variable),
                    assignment);
      }
    }
  }

  // A parameter whose default the compiler built into the program (a loop
  // bound, a curve's points): any other value raises alarm 3001 rather
  // than cutting a part the operator did not ask for. The value is compared
  // with the literal the defaults assign, so the test is exact.
  void printFixedParameterChecks() {
    for (std::size_t i = 0; i < function_.parameters.size(); ++i) {
      if (!function_.parameters[i].fixed) {
        continue;
      }
      std::string variable = fmt::format("#{}", allocation_.parameterVariables[i]);
      std::string literal = parameterDefault(i);
      std::string condition = fmt::format("[{} NE {}]", variable, literal);
      std::string message = fmt::format("{} is fixed at {}", function_.parameters[i].name, literal);
      conditional(condition, fmt::format("[{} EQ {}]", variable, literal),
                  alarmStatement(message, profile_.hasThen ? condition.size() + 9 : 0));
    }
  }

  // `#3000=1 (MESSAGE)`: alarm 3001, its message cut to what the block
  // length leaves beside `reserved` characters (an IF around it).
  std::string alarmStatement(std::string_view text, std::size_t reserved) const {
    std::string_view alarm = "#3000=1";
    std::string message = gcodeCommentText(text);
    std::size_t used = alarm.size() + 3 + reserved;
    auto limit = static_cast<std::size_t>(std::max(0, profile_.maximumBlockLength));
    std::size_t room = limit > used ? limit - used : 0;
    return fmt::format("{} ({})", alarm, message.substr(0, room));
  }

  void printTables() {
    for (const auto& [base, tables] : ir::tablesByBase(function_, allocation_)) {
      const std::vector<double>& values = function_.tables[tables.front()];
      for (std::size_t i = 0; i < values.size(); ++i) {
        line(fmt::format("#{}={}", base + static_cast<int>(i), expressions_.constant(values[i])));
      }
    }
  }

  // ---- statements --------------------------------------------------------

  int newLabel() {
    int label = nextLabel_++;
    if (label > profile_.maximumSequenceNumber) {
      errors_.push_back(fmt::format("the program needs sequence number N{}, the controller allows "
                                    "up to N{}",
                                    label, profile_.maximumSequenceNumber));
    }
    return label;
  }

  // `IF [c] THEN statement`, or a jump over it where THEN is missing.
  void conditional(const std::string& condition, const std::string& negatedCondition,
                   const std::string& statement) {
    if (profile_.hasThen) {
      line(fmt::format("IF {} THEN {}", condition, statement));
      return;
    }
    int label = newLabel();
    line(fmt::format("IF {} GOTO {}", negatedCondition, label));
    line(statement);
    line(fmt::format("N{}", label));
  }

  void printRegion(const ir::Region& region) {
    for (ir::InstructionId id : region.instructions) {
      printInstruction(function_.instructions[id]);
    }
  }

  void printInstruction(const ir::Instruction& instruction) {
    InstructionLines marked(lineSpans_, lines_, instruction.span, currentSpan_);
    switch (instruction.opcode) {
    case Opcode::Loop:
      printLoop(instruction);
      return;
    case Opcode::If:
      printIf(instruction);
      return;
    case Opcode::Rapid:
      printRapid(instruction);
      return;
    case Opcode::Feed:
      printFeed(instruction);
      return;
    case Opcode::Arc:
      printArc(instruction);
      return;
    case Opcode::Nurbs:
      printNurbs(instruction);
      return;
    case Opcode::Spline: // lowered only for the sinumerik target
      errors_.push_back("this controller has no Sinumerik spline blocks (move.spline)");
      return;
    case Opcode::Spindle:
      line(fmt::format("S{} M3", spindleSpeed(instruction.operands[0])));
      spindleOn_ = true;
      return;
    case Opcode::Tool:
      printTool(instruction);
      return;
    case Opcode::Origin:
    case Opcode::Coolant:
    case Opcode::Contouring:
    case Opcode::Home:
      for (std::string& block : setupBlocks(options_.setup, instruction,
                                            expressions_.coordinateLiteral(instruction.number))) {
        line(std::move(block));
      }
      if (instruction.opcode == Opcode::Home) { // Z is at the machine's reference
        modal_.forget();
      }
      return;
    case Opcode::Alarm:
      line(alarmStatement(instruction.text, 0));
      return;
    case Opcode::Comment:
      comment(instruction.text);
      return;
    case Opcode::CutBegin: // the cut's own comment says it
    case Opcode::Param:
      return;
    default:
      break;
    }
    if (instruction.result.valid() && allocation_.inVariable(instruction.result) &&
        !scaledValues_.contains(instruction.result.index)) {
      printAssignment(instruction);
    }
  }

  std::string spindleSpeed(ValueId speed) const {
    const ir::Instruction& definition = function_.definition(speed);
    if (definition.opcode == Opcode::Const) {
      return fmt::format("{}", std::llround(definition.number));
    }
    return expressions_.operand(speed);
  }

  void printTool(const ir::Instruction& instruction) {
    if (spindleOn_) {
      line("M5");
      spindleOn_ = false;
    }
    std::string diameterComment;
    const ir::Instruction& diameter = function_.definition(instruction.operands[0]);
    if (diameter.opcode == Opcode::Const) {
      diameterComment =
          fmt::format("(DIAMETER {})", expressions_.coordinateLiteral(diameter.number));
    }
    for (std::string& block :
         toolChangeBlocks(options_.setup, std::llround(instruction.number), diameterComment)) {
      line(std::move(block));
    }
    modal_.forget();
    beforeZ_ = lengthOffsetWords(options_.setup, static_cast<int>(std::llround(instruction.number)),
                                 instruction.index);
  }

  // The Z word of a move, after the words the first Z move after a tool
  // change carries (its length offset).
  std::string zWord(ValueId z) {
    std::string text = word('Z', z);
    if (!text.empty() && !beforeZ_.empty()) {
      text = " " + beforeZ_ + text;
      beforeZ_.clear();
    }
    return text;
  }

  void printAssignment(const ir::Instruction& instruction) {
    std::string target = expressions_.variable(instruction.result);
    auto operand = [&](std::size_t i) { return expressions_.operand(instruction.operands[i]); };
    switch (instruction.opcode) {
    case Opcode::Min:
    case Opcode::Max: {
      bool isMin = instruction.opcode == Opcode::Min;
      line(fmt::format("{}={}", target, expressions_.value(instruction.operands[0]).text));
      conditional(fmt::format("[{} {} {}]", operand(1), isMin ? "LT" : "GT", target),
                  fmt::format("[{} {} {}]", operand(1), isMin ? "GE" : "LE", target),
                  fmt::format("{}={}", target, expressions_.value(instruction.operands[1]).text));
      return;
    }
    case Opcode::Floor:
    case Opcode::Ceil: { // FIX truncates toward zero; one step fixes the other sign
      bool isFloor = instruction.opcode == Opcode::Floor;
      line(fmt::format("{}=FIX[{}]", target, expressions_.value(instruction.operands[0]).text));
      conditional(fmt::format("[{} {} {}]", target, isFloor ? "GT" : "LT", operand(0)),
                  fmt::format("[{} {} {}]", target, isFloor ? "LE" : "GE", operand(0)),
                  fmt::format("{}={}{}1.", target, target, isFloor ? "-" : "+"));
      return;
    }
    case Opcode::Select:
      line(fmt::format("{}={}", target, expressions_.value(instruction.operands[2]).text));
      conditional(expressions_.condition(instruction.operands[0]),
                  expressions_.condition(instruction.operands[0], true),
                  fmt::format("{}={}", target, expressions_.value(instruction.operands[1]).text));
      return;
    case Opcode::Rem: // fmod: a - FIX[a/b]*b, a and b are atoms here
      line(fmt::format("{}={}-FIX[{}/{}]*{}", target, operand(0), operand(0), operand(1),
                       operand(1)));
      return;
    case Opcode::Atan:
    case Opcode::Atan2: {
      // ATAN[y]/[x] gives 0..360 or -180..180 degrees by a parameter; both
      // become the IR's -pi..pi.
      std::string x = instruction.opcode == Opcode::Atan ? "1." : operand(1);
      line(fmt::format("{}=ATAN[{}]/[{}]", target, expressions_.value(instruction.operands[0]).text,
                       instruction.opcode == Opcode::Atan
                           ? x
                           : expressions_.value(instruction.operands[1]).text));
      conditional(fmt::format("[{} GT 180.]", target), fmt::format("[{} LE 180.]", target),
                  fmt::format("{}={}-360.", target, target));
      line(fmt::format("{}={}*{}", target, target, expressions_.constant(1 / degreesPerRadian)));
      return;
    }
    default:
      line(fmt::format("{}={}", target, expressions_.definition(instruction.result).text));
      return;
    }
  }

  // ---- control flow ------------------------------------------------------

  void printLoop(const ir::Instruction& instruction) {
    ++loopDepth_;
    int limit = std::min(profile_.maximumLoopNesting, profile_.maximumLoopIdentifier);
    if (loopDepth_ > limit && !reportedLoopDepth_) {
      errors_.push_back(
          fmt::format("the program nests {} loops, the controller allows {}", loopDepth_, limit));
      reportedLoopDepth_ = true;
    }
    std::string index = expressions_.variable(instruction.result);
    auto stepped = steppedLoops_.find(instruction.result.index);
    if (stepped != steppedLoops_.end() && std::isnan(stepped->second)) {
      // The index variable holds i / high, stepped by 1 / high.
      std::string high = expressions_.operand(instruction.operands[1]);
      line(fmt::format("{}=1./{}", index, high));
      line(fmt::format("WHILE [{} LE 1.+.5/{}] DO{}", index, high, loopDepth_));
    } else if (stepped != steppedLoops_.end()) {
      // The index variable holds i * scale, stepped by the scale.
      double scale = stepped->second;
      double low = *constantOf(instruction.operands[0]);
      double high = *constantOf(instruction.operands[1]);
      line(fmt::format("{}={}", index, expressions_.constant(low * scale)));
      line(fmt::format("WHILE [{} {} {}] DO{}", index, scale > 0 ? "LE" : "GE",
                       expressions_.constant((high + 0.5) * scale), loopDepth_));
    } else {
      line(fmt::format("{}={}", index, expressions_.value(instruction.operands[0]).text));
      line(fmt::format("WHILE [{} LE {}] DO{}", index,
                       expressions_.operand(instruction.operands[1]), loopDepth_));
    }
    // The body as it prints from the words in force before the loop, then
    // from those that also hold after one pass through it, until stable.
    ModalState entry = modal_;
    CapturedLines body;
    for (int attempt = 0;; ++attempt) {
      if (attempt >= 3) {
        entry.forget();
      }
      int labels = nextLabel_;
      std::size_t errorCount = errors_.size();
      body = capture(instruction.regions[0], entry);
      ModalState agreed = entry.agreedWith(modal_);
      if (agreed == entry || attempt >= 3) {
        modal_ = agreed;
        break;
      }
      nextLabel_ = labels;
      errors_.resize(errorCount);
      entry = agreed;
    }
    append(body);
    if (stepped != steppedLoops_.end() && std::isnan(stepped->second)) {
      line(fmt::format("{}={}+1./{}", index, index, expressions_.operand(instruction.operands[1])));
    } else if (stepped != steppedLoops_.end()) {
      line(fmt::format("{}={}+{}", index, index, expressions_.constant(stepped->second)));
    } else {
      line(fmt::format("{}={}+1.", index, index));
    }
    line(fmt::format("END{}", loopDepth_));
    --loopDepth_;
  }

  // The region's lines, printed from `entry`; modal_ is left as it ends.
  CapturedLines capture(const ir::Region& region, const ModalState& entry) {
    modal_ = entry;
    return captureLines(region);
  }

  CapturedLines capture(const ir::Region& region) {
    modal_.forget();
    CapturedLines captured = captureLines(region);
    modal_.forget();
    return captured;
  }

  // The region's lines and where each comes from, printed aside.
  CapturedLines captureLines(const ir::Region& region) {
    std::vector<std::string> savedLines = std::move(lines_);
    LineSpans savedSpans = std::move(lineSpans_);
    lines_.clear();
    lineSpans_ = LineSpans();
    lineSpans_.start(0, currentSpan_);
    printRegion(region);
    CapturedLines captured{std::move(lines_), {}};
    captured.spans = lineSpans_.spans(captured.lines.size());
    lines_ = std::move(savedLines);
    lineSpans_ = std::move(savedSpans);
    return captured;
  }

  // Appends captured lines; the lines after them are the current span's.
  void append(const CapturedLines& captured) {
    for (std::size_t k = 0; k < captured.lines.size(); ++k) {
      lineSpans_.start(lines_.size(), captured.spans[k]);
      lines_.push_back(captured.lines[k]);
    }
    lineSpans_.start(lines_.size(), currentSpan_);
  }

  // IF THEN where one statement is the whole branch; jumps otherwise.
  void printIf(const ir::Instruction& instruction) {
    ValueId condition = instruction.operands[0];
    CapturedLines thenLines = capture(instruction.regions[0]);
    CapturedLines elseLines =
        instruction.regions.size() > 1 ? capture(instruction.regions[1]) : CapturedLines{};
    if (thenLines.lines.empty() && elseLines.lines.empty()) {
      return;
    }
    bool single = elseLines.lines.empty() && thenLines.lines.size() == 1 &&
                  thenLines.lines[0].starts_with("#");
    if (single && profile_.hasThen) {
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

  // ---- moves -------------------------------------------------------------

  std::optional<double> constantOf(ValueId value) const {
    const ir::Instruction& definition = function_.definition(value);
    return definition.opcode == Opcode::Const ? std::optional<double>(definition.number)
                                              : std::nullopt;
  }

  // " X12.5", or nothing when that word is in force already.
  std::string word(char letter, ValueId value, bool isCoordinate = true) {
    std::string text = isCoordinate ? expressions_.coordinate(value) : expressions_.operand(value);
    if (!isCoordinate && constantOf(value)) {
      text = expressions_.constant(*constantOf(value));
    }
    ModalWord current{text,
                      constantOf(value) ? std::nullopt : std::optional<std::uint32_t>(value.index)};
    auto known = modal_.words.find(letter);
    if (known != modal_.words.end() && known->second == current) {
      return "";
    }
    modal_.words[letter] = current;
    return fmt::format(" {}{}", letter, text);
  }

  void block(std::string_view motion, const std::string& words) {
    if (words.empty()) {
      return;
    }
    std::string text = motion == modal_.motion ? words.substr(1) : std::string(motion) + words;
    modal_.motion = std::string(motion);
    line(text);
  }

  void rememberZ(ValueId z) { modal_.z = constantOf(z); }

  // Up first and down last, so a rapid never moves sideways below where it
  // starts or ends; where the heights are not literals, Z goes first (the
  // lowering's rapids climb to the safe height).
  void printRapid(const ir::Instruction& instruction) {
    ValueId x = instruction.operands[0], y = instruction.operands[1], z = instruction.operands[2];
    std::optional<double> target = constantOf(z);
    bool descending = target && modal_.z && *target < *modal_.z - 1e-12;
    if (descending) {
      block("G0", word('X', x) + word('Y', y));
      block("G0", zWord(z));
    } else {
      block("G0", zWord(z));
      block("G0", word('X', x) + word('Y', y));
    }
    rememberZ(z);
  }

  void printFeed(const ir::Instruction& instruction) {
    std::string words = word('X', instruction.operands[0]) + word('Y', instruction.operands[1]) +
                        zWord(instruction.operands[2]);
    if (!words.empty()) {
      words += word('F', instruction.operands[3], false);
    }
    block("G1", words);
    rememberZ(instruction.operands[2]);
  }

  // move.arc: G2/G3 with X and Y always (a full turn ends where it starts),
  // Z when it changes (a helix), the centre's I J from the start always.
  void printArc(const ir::Instruction& instruction) {
    const std::vector<ValueId>& operands = instruction.operands;
    for (char always : {'X', 'Y', 'I', 'J'}) {
      modal_.words.erase(always);
    }
    std::string words = word('X', operands[0]) + word('Y', operands[1]) + zWord(operands[2]) +
                        word('I', operands[3]) + word('J', operands[4]) +
                        word('F', operands[5], false);
    modal_.words.erase('I');
    modal_.words.erase('J');
    bool clockwise = instruction.index == static_cast<std::uint32_t>(ir::ArcTurn::Clockwise);
    block(clockwise ? "G2" : "G3", words);
    rememberZ(operands[2]);
  }

  // move.nurbs: the G06.2 blocks of its table at the pass height; a weight
  // computed on the controller (a part parameter) is printed as its
  // expression, R#3, as the syntax allows.
  void printNurbs(const ir::Instruction& instruction) {
    std::size_t count = instruction.operands.size() - 2;
    std::optional<ir::NurbsBlockData> data =
        ir::readNurbsMoveTable(function_.tables[instruction.index], count);
    std::optional<double> z = constantOf(instruction.operands[0]);
    if (!data || !z) {
      errors_.push_back("G06.2: a NURBS move without its block data or a constant height");
      return;
    }
    std::vector<double> weights;
    NurbsBlockOptions options;
    for (std::size_t k = 0; k < count; ++k) {
      ir::ValueId weight = instruction.operands[2 + k];
      weights.push_back(constantOf(weight).value_or(1.0));
      options.weightVariables.push_back(constantOf(weight) ? "" : expressions_.operand(weight));
    }
    std::optional<geom::NurbsCurve> curve;
    try {
      curve = ir::nurbsMoveCurve(*data, 0, weights);
    } catch (const ir::InterpreterError& error) {
      errors_.push_back(fmt::format("G06.2: {}", error.what()));
      return;
    }
    std::string feed = word('F', instruction.operands[1], false);
    options.dialect = profile_.name == "m80" ? NurbsDialect::Mitsubishi : NurbsDialect::Fanuc;
    options.coordinateDecimals = profile_.coordinateDecimals + (options_.inches ? 1 : 0);
    options.z = *z;
    options.feedText = feed.empty() ? modal_.words['F'].text : feed.substr(2);
    options.currentPosition = data->points.front() + Eigen::Vector3d(0, 0, *z);
    NurbsBlocks blocks = writeNurbsBlocks(*curve, options);
    errors_.insert(errors_.end(), blocks.errors.begin(), blocks.errors.end());
    for (std::string& text : blocks.lines) {
      line(std::move(text));
    }
    modal_.forget(); // G06.2 is modal now, and the position is the curve's end
  }

  const ir::Function& function_;
  const ir::Allocation& allocation_;
  const ControllerProfile& profile_;
  const MacroProgramOptions& options_;
  std::vector<std::string>& errors_;
  int* longestBlock_;
  MacroProgram* mapped_;
  std::map<int, VariableMeaning> variableMeanings_;
  MacroExpressionWriter expressions_;
  const std::map<std::uint32_t, double>& steppedLoops_;
  const std::set<std::uint32_t>& scaledValues_;
  std::vector<std::string> lines_;
  ModalState modal_;
  int loopDepth_ = 0;
  bool reportedLoopDepth_ = false;
  int nextLabel_ = 1;
  bool spindleOn_ = false;
  LineSpans lineSpans_;
  frontend::SourceSpan currentSpan_;
  std::string beforeZ_; // the length offset words of the next Z move
};

} // namespace

std::vector<int> macroParameterVariables(std::size_t parameterCount,
                                         const ControllerProfile& profile, bool inCommon,
                                         std::vector<std::string>& errors) {
  std::vector<int> candidates;
  if (inCommon) {
    for (const VariableRange& range : profile.retainedCommon) {
      for (int variable = range.first; variable <= range.last; ++variable) {
        candidates.push_back(variable);
      }
    }
  } else {
    for (const ArgumentLetter& argument : profile.argumentLetters) {
      candidates.push_back(argument.variable);
    }
    std::sort(candidates.begin(), candidates.end());
  }
  if (candidates.size() < parameterCount) {
    errors.push_back(fmt::format("the part has {} parameters, the controller has {} {} for them",
                                 parameterCount, candidates.size(),
                                 inCommon ? "retained common variables" : "argument letters"));
    candidates.resize(parameterCount, 0);
  }
  candidates.resize(parameterCount);
  return candidates;
}

ir::AllocationOptions macroAllocationOptions(const ControllerProfile& profile,
                                             std::vector<int> parameterVariables) {
  ir::AllocationOptions options;
  options.variables.push_back({profile.locals.first, profile.locals.last});
  for (const VariableRange& range : profile.volatileCommon) {
    options.variables.push_back({range.first, range.last});
  }
  for (const VariableRange& range : profile.retainedCommon) {
    options.variables.push_back({range.first, range.last});
  }
  options.parameterVariables = std::move(parameterVariables);
  options.maximumBracketDepth = profile.maximumBracketNesting;
  // Counted in characters (macroInlineShape with the profile), with room
  // for the addresses of a move or `#nnn=`; the printer checks every block's
  // real length.
  options.maximumInlineOperations = std::max(16, profile.maximumBlockLength - 20);
  options.maximumAssignmentOperations = std::max(16, profile.maximumBlockLength - 8);
  options.shape = [&profile](const ir::Function& function, const ir::Instruction& instruction,
                             std::span<const ir::InlineShape> operands) {
    return macroInlineShape(profile, function, instruction, operands);
  };
  options.statementOpcodes = macroStatementOpcodes();
  return options;
}

ir::LoweringOptions macroLoweringOptions(const ControllerProfile& profile, bool inches) {
  ir::LoweringOptions options;
  options.controllerLoops = true;
  options.arcBlocks = true; // arcs=true, --arcs: host-fitted G02/G03 blocks
  options.coordinateIncrement =
      inches ? profile.leastInputIncrement / 10 : profile.leastInputIncrement;
  options.maximumLoopNesting = std::min(profile.maximumLoopNesting, profile.maximumLoopIdentifier);
  return options;
}

MacroProgram writeMacroProgram(const ir::Function& function, const ControllerProfile& profile,
                               const MacroProgramOptions& options) {
  MacroProgram program;
  if (options.programNumber < 1 || options.programNumber > profile.maximumProgramNumber) {
    program.errors.push_back(fmt::format("program number O{} is outside the controller's 1..{}",
                                         options.programNumber, profile.maximumProgramNumber));
    return program;
  }
  if (!profile.hasIndirectVariables && !function.tables.empty()) {
    program.errors.push_back(fmt::format("the part reads {} tables, and the controller has no "
                                         "indirect variables #[..] to read them",
                                         function.tables.size()));
    return program;
  }
  ir::Function simplified = simplifyForMacroProgram(function);
  std::vector<int> parameterVariables = macroParameterVariables(
      simplified.parameters.size(), profile, options.parametersInCommon, program.errors);
  if (!program.errors.empty()) {
    return program;
  }
  // The allocator estimates the length of a block; where a printed block is
  // longer than the controller takes, the limits shrink and it runs again.
  ir::AllocationOptions allocationOptions = macroAllocationOptions(profile, parameterVariables);
  ir::AllocationResult allocated;
  std::string text;
  for (int attempt = 0;; ++attempt) {
    program.errors.clear();
    allocated = ir::allocateVariables(simplified, allocationOptions);
    for (const ir::AllocationFailure& failure : allocated.failures) {
      program.errors.push_back(failure.message);
    }
    if (!program.errors.empty()) {
      return program;
    }
    SteppedLoops stepped = stepLoopsByTheirScale(simplified, allocated.allocation);
    int longest = 0;
    text = ProgramPrinter(simplified, allocated.allocation, stepped, profile, options,
                          program.errors, &longest, &program)
               .print();
    bool onlyTooLong = program.errors.size() == 1 && longest > profile.maximumBlockLength;
    if (!onlyTooLong || attempt == 4 || allocationOptions.maximumInlineOperations <= 16) {
      break;
    }
    int excess = longest - profile.maximumBlockLength;
    allocationOptions.maximumInlineOperations =
        std::max(16, allocationOptions.maximumInlineOperations - excess - 2);
    allocationOptions.maximumAssignmentOperations =
        std::max(16, allocationOptions.maximumAssignmentOperations - excess - 2);
  }
  if (!program.errors.empty()) {
    return program;
  }
  program.text = std::move(text);
  program.statistics = measureMacroProgram(program.text);
  program.statistics.variables = static_cast<int>(allocated.allocation.usedVariables.size());
  return program;
}

} // namespace cncc::backends
