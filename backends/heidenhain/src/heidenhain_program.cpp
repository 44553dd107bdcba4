#include "cncc/backends/heidenhain_program.h"

#include "cncc/backends/line_spans.h"
#include "cncc/backends/macro_program.h"
#include "heidenhain_blocks.h"
#include "heidenhain_formulas.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>

namespace cncc::backends {

namespace {

using ir::Opcode;
using ir::ValueId;

// FN 14 error numbers: a parameter edited away from the value the program
// was compiled for, and an alarm of the part (a degenerate arc).
constexpr int fixedParameterError = 1;
constexpr int partAlarmError = 2;
// A table read at an index outside the table.
constexpr int tableIndexError = 3;

constexpr double pi = 3.14159265358979;

// `; text`: printable characters only.
std::string commentLine(std::string_view text) {
  std::string line = "; ";
  for (char c : text) {
    line += std::isprint(static_cast<unsigned char>(c)) ? c : ' ';
  }
  return line;
}

bool usesArcs(const ir::Function& function) {
  return std::any_of(function.instructions.begin(), function.instructions.end(),
                     [](const ir::Instruction& i) { return i.opcode == Opcode::Arc; });
}

class ProgramPrinter {
public:
  ProgramPrinter(const ir::Function& function, const ir::Allocation& allocation,
                 const HeidenhainProgramOptions& options, std::vector<std::string>& errors)
      : function_(function), allocation_(allocation), options_(options), errors_(errors),
        formulas_(function, allocation, options.profile, options.inches, errors),
        blocks_(formulas_, options.profile, lines_, errors) {}

  std::string print() {
    std::string unit = options_.inches ? "INCH" : "MM";
    line(fmt::format("BEGIN PGM {} {}", options_.partName, unit));
    printHeader();
    printBlank();
    printParameters();
    if (usesArcs(function_)) {
      blocks_.trackZ(options_.profile.scratch.last);
    }
    printRegion(function_.body);
    flushTool();
    blocks_.flushWords(spindleOn_ ? "M5" : "");
    line(fmt::format("END PGM {} {}", options_.partName, unit));
    return numberedText();
  }

  LineOrigins takeLineOrigins() { return {std::move(printedOrigins_), std::move(loops_)}; }

private:
  void line(std::string text) { lines_.push_back(std::move(text)); }

  std::string numberedText() {
    std::string text;
    int tooLong = 0;
    std::size_t longest = 0;
    for (std::size_t i = 0; i < lines_.size(); ++i) {
      std::string block = fmt::format("{} {}", i, lines_[i]);
      if (static_cast<int>(block.size()) > options_.profile.maximumBlockLength) {
        ++tooLong;
        longest = std::max(longest, block.size());
      }
      text += block;
      text += '\n';
    }
    if (tooLong > 0) {
      errors_.push_back(fmt::format("{} blocks exceed the TNC's {} characters, the longest has {}",
                                    tooLong, options_.profile.maximumBlockLength, longest));
    }
    if (static_cast<int>(lines_.size()) - 1 > options_.profile.maximumBlockNumber) {
      errors_.push_back(fmt::format("the program has {} blocks, the TNC numbers them up to {}",
                                    lines_.size(), options_.profile.maximumBlockNumber));
    }
    printedOrigins_ = lineSpans_.origins(lines_.size());
    return text;
  }

  // ---- header ------------------------------------------------------------

  std::string parameterName(std::size_t index) const {
    return tncParameterName(allocation_.parameterVariables[index]);
  }

  std::string parameterDefault(std::size_t index) const {
    return formulas_.signedNumber(function_.parameters[index].defaultValue);
  }

  void printHeader() {
    line(commentLine(fmt::format("{} - part {}", options_.sourceName, options_.partName)));
    for (std::size_t i = 0; i < function_.parameters.size(); ++i) {
      const ir::Parameter& parameter = function_.parameters[i];
      line(commentLine(fmt::format("{} = {}, {} {}", parameterName(i), parameter.name,
                                   parameter.fixed ? "fixed at" : "default", parameterDefault(i))));
    }
  }

  void printBlank() {
    if (!options_.blank) {
      return;
    }
    const HeidenhainBlank& blank = *options_.blank;
    auto coordinate = [&](double value) { return formulas_.signedCoordinate(value); };
    line(fmt::format("BLK FORM 0.1 Z X{} Y{} Z{}", coordinate(blank.minX), coordinate(blank.minY),
                     coordinate(blank.minZ)));
    line(fmt::format("BLK FORM 0.2 X{} Y{} Z{}", coordinate(blank.maxX), coordinate(blank.maxY),
                     coordinate(blank.maxZ)));
  }

  void printParameters() {
    for (std::size_t i = 0; i < function_.parameters.size(); ++i) {
      line(fmt::format("FN 0: {} = {}", parameterName(i), parameterDefault(i)));
    }
    // A parameter whose default the compiler built into the program (a
    // loop bound, a curve's points): any other value stops the program.
    for (std::size_t i = 0; i < function_.parameters.size(); ++i) {
      if (!function_.parameters[i].fixed) {
        continue;
      }
      int accepted = blocks_.newLabel();
      line(fmt::format("FN 9: IF +{} EQU {} GOTO LBL {}", parameterName(i), parameterDefault(i),
                       accepted));
      line(commentLine(
          fmt::format("{} is fixed at {}", function_.parameters[i].name, parameterDefault(i))));
      line(fmt::format("FN 14: ERROR = {}", fixedParameterError));
      blocks_.label(accepted);
    }
  }

  // ---- statements ----------------------------------------------------------

  void printRegion(const ir::Region& region) {
    for (ir::InstructionId id : region.instructions) {
      printInstruction(function_.instructions[id]);
    }
  }

  void printInstruction(const ir::Instruction& instruction) {
    InstructionLines marked(lineSpans_, lines_, instruction, currentOrigin_);
    blocks_.releaseScratch();
    const std::vector<ValueId>& operands = instruction.operands;
    switch (instruction.opcode) {
    case Opcode::Loop:
      printLoop(instruction);
      return;
    case Opcode::If:
      printIf(instruction);
      return;
    case Opcode::Rapid:
      flushTool();
      blocks_.rapid(operands[0], operands[1], operands[2]);
      return;
    case Opcode::Climb:
      flushTool();
      blocks_.climb(operands[0]);
      return;
    case Opcode::Feed:
      flushTool();
      blocks_.feed(operands[0], operands[1], operands[2], operands[3]);
      return;
    case Opcode::Arc:
      flushTool();
      blocks_.arc(instruction.index == static_cast<std::uint32_t>(ir::ArcTurn::Clockwise),
                  operands);
      return;
    case Opcode::Polynomial:
      flushTool();
      blocks_.spline(operands);
      return;
    case Opcode::Nurbs: // lowered only for targets with NURBS blocks
      errors_.push_back("the TNC has no NURBS blocks of the G06.2 kind (move.nurbs)");
      return;
    case Opcode::Spline: // lowered only for the sinumerik target
      errors_.push_back("the TNC has no Sinumerik spline blocks (move.spline)");
      return;
    case Opcode::Compensation:
      printCompensation(instruction);
      return;
    case Opcode::CornerArc: // lowered for the Fanuc and Mitsubishi targets only
      errors_.push_back("the TNC has no corner arc block of the G39 kind (corner.arc)");
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
      printSetup(instruction);
      return;
    case Opcode::Alarm:
      line(commentLine(instruction.text));
      line(fmt::format("FN 14: ERROR = {}", partAlarmError));
      return;
    case Opcode::Comment:
      line(commentLine(instruction.text));
      return;
    case Opcode::CutBegin: // the cut's own comment says it
    case Opcode::Param:
    case Opcode::LoopNext: // printed by its loop (printLoop)
      return;
    default:
      break;
    }
    if (instruction.result.valid() && allocation_.inVariable(instruction.result)) {
      printAssignment(instruction);
    }
  }

  // Radius compensation: `RL`/`RR` on the start-up line, `R0` on the
  // cancel line, plain L and CC/C blocks between, as the lowering wrote
  // them. The TNC offsets by R of the called tool's row in its tool table
  // (plus any DR of the TOOL CALL): the program writes no DR, so the radius
  // the shop keeps in the table is the one used, as a Fanuc's D register.
  // APPR/DEP would have the control work out the lead arcs; the lines and
  // arcs the compiler computed are what it measures the path against, and a
  // TNC runs them as they are.
  void printCompensation(const ir::Instruction& instruction) {
    flushTool();
    if (instruction.number == 0) {
      blocks_.radiusCompensation("R0");
      return;
    }
    if (currentTool_ && instruction.index != *currentTool_ && explainedTool_ != currentTool_) {
      explainedTool_ = currentTool_;
      line(commentLine(fmt::format("radius of tool {} from the tool table (register {} is for "
                                   "G41/G42 controls)",
                                   *currentTool_, instruction.index)));
    }
    blocks_.radiusCompensation(instruction.number > 0 ? "RL" : "RR");
  }

  // `TOOL CALL n Z S..`: the tool waits for its spindle speed.
  void printTool(const ir::Instruction& instruction) {
    flushTool();
    if (spindleOn_) {
      blocks_.flushWords("M5");
      spindleOn_ = false;
    }
    pendingTool_ = std::llround(instruction.number);
    currentTool_ = *pendingTool_;
    if (std::optional<double> diameter = formulas_.constantOf(instruction.operands[0])) {
      line(commentLine(fmt::format("tool diameter {}", formulas_.number(*diameter))));
    }
  }

  void flushTool() {
    if (pendingTool_) {
      line(fmt::format("TOOL CALL {} Z", *pendingTool_));
      pendingTool_.reset();
      blocks_.forget();
    }
  }

  void printSpindle(const ir::Instruction& instruction) {
    ValueId speed = instruction.operands[0];
    std::optional<double> literal = formulas_.constantOf(speed);
    std::string word = literal ? fmt::format("S{}", std::llround(*literal))
                               : "S" + blocks_.operand(speed).substr(1);
    std::string tool = pendingTool_ ? fmt::format(" {}", *pendingTool_) : "";
    line(fmt::format("TOOL CALL{} Z {}", tool, word));
    pendingTool_.reset();
    blocks_.forget();
    blocks_.beforeNextMove("M3");
    spindleOn_ = true;
  }

  void printSetup(const ir::Instruction& instruction) {
    switch (instruction.opcode) {
    case Opcode::Origin:
      // The TNC machines in the active preset; G54 is the part's default.
      if (instruction.number != 54) {
        errors_.push_back(fmt::format("the TNC target selects no work offset other than the "
                                      "active preset (G54), the part asks for G{}",
                                      instruction.number));
      }
      return;
    case Opcode::Coolant: {
      auto mode = static_cast<ir::CoolantMode>(instruction.index);
      std::string_view word = mode == ir::CoolantMode::Flood  ? "M8"
                              : mode == ir::CoolantMode::Mist ? "M7"
                              : mode == ir::CoolantMode::Off  ? "M9"
                                                              : "";
      if (word.empty()) {
        errors_.push_back("the TNC target has no code for through-spindle coolant");
        return;
      }
      blocks_.beforeNextMove(std::string(word));
      return;
    }
    case Opcode::Contouring:
      line("CYCL DEF 32.0 TOLERANCE");
      line(instruction.number == 0
               ? std::string("CYCL DEF 32.1")
               : fmt::format("CYCL DEF 32.1 T{}", formulas_.signedCoordinate(instruction.number)));
      return;
    default: // move.home: Z to the machine's reference (M91: machine coordinates)
      blocks_.flushWords();
      line("L Z+0 R0 FMAX M91");
      blocks_.forget();
      return;
    }
  }

  // Operations of several blocks: jumps around assignments to `target`.
  // Every operand is read before the target is written (it may share its
  // parameter).
  // `whenTrue` when left < right.
  void chooseAssignment(const std::string& left, const std::string& right,
                        const std::string& target, ValueId whenTrue, ValueId whenFalse) {
    int chosen = blocks_.newLabel();
    int done = blocks_.newLabel();
    line(fmt::format("FN 12: IF {} LT {} GOTO LBL {}", left, right, chosen));
    blocks_.assign(target, whenFalse);
    blocks_.jump(done);
    blocks_.label(chosen);
    blocks_.assign(target, whenTrue);
    blocks_.label(done);
  }

  // Rounding down (or up): INT truncates, so a negative (positive) value
  // that is not whole is corrected by one.
  void printRounding(const ir::Instruction& instruction, const std::string& target, bool up) {
    std::string value = blocks_.operand(instruction.operands[0]);
    std::string whole = blocks_.scratch();
    line(fmt::format("{} = INT {}", whole, term(value)));
    int corrected = blocks_.newLabel();
    int done = blocks_.newLabel();
    std::string greater = up ? value : "+" + whole;
    std::string less = up ? "+" + whole : value;
    line(fmt::format("FN 11: IF {} GT {} GOTO LBL {}", greater, less, corrected));
    line(fmt::format("{} = {}", target, whole));
    blocks_.jump(done);
    blocks_.label(corrected);
    line(fmt::format("{} = {} {} 1", target, whole, up ? '+' : '-'));
    blocks_.label(done);
  }

  // atan2: ATAN of the quotient, a half turn added or taken away left of
  // the Y axis, a quarter turn on it.
  void printAtan2(const ir::Instruction& instruction, const std::string& target) {
    std::string y = blocks_.operand(instruction.operands[0]);
    std::string x = blocks_.operand(instruction.operands[1]);
    std::string angle = blocks_.scratch();
    int onAxis = blocks_.newLabel();
    int below = blocks_.newLabel();
    int done = blocks_.newLabel();
    line(fmt::format("FN 9: IF {} EQU +0 GOTO LBL {}", x, onAxis));
    line(fmt::format("{} = ATAN ( {} / {} ) * {}", angle, term(y), term(x),
                     formulas_.number(pi / 180)));
    line(fmt::format("FN 11: IF {} GT +0 GOTO LBL {}", x, done));
    line(fmt::format("FN 12: IF {} LT +0 GOTO LBL {}", y, below));
    line(fmt::format("{} = {} + {}", angle, angle, formulas_.number(pi)));
    blocks_.jump(done);
    blocks_.label(below);
    line(fmt::format("{} = {} - {}", angle, angle, formulas_.number(pi)));
    blocks_.jump(done);
    blocks_.label(onAxis);
    line(fmt::format("FN 0: {} = +0", angle));
    line(fmt::format("FN 9: IF {} EQU +0 GOTO LBL {}", y, done));
    line(fmt::format("{} = {} * SGN {}", angle, formulas_.number(pi / 2), term(y)));
    blocks_.label(done);
    line(fmt::format("{} = {}", target, angle));
  }

  // A TNC program has no indexed parameters: a table read at a computed
  // index is a chain of FN 12 jumps, one per entry, to an FN 0 of the
  // entry's value. As the IR reads it, the index is truncated (a jump
  // below k + 1 takes entry k), and one outside the table stops the program.
  void printTableRead(const ir::Instruction& instruction, const std::string& target) {
    const std::vector<double>& table = function_.tables.at(instruction.index);
    if (std::optional<double> constant = formulas_.constantOf(instruction.operands[0]);
        constant && *constant >= 0 && *constant < static_cast<double>(table.size())) {
      line(fmt::format("FN 0: {} = {}", target,
                       formulas_.signedNumber(table[static_cast<std::size_t>(*constant)])));
      return;
    }
    std::string index = blocks_.operand(instruction.operands[0]);
    int outside = blocks_.newLabel();
    line(fmt::format("FN 12: IF {} LT +0 GOTO LBL {}", index, outside));
    std::vector<int> entries;
    for (std::size_t k = 0; k < table.size(); ++k) {
      entries.push_back(blocks_.newLabel());
      line(fmt::format("FN 12: IF {} LT +{} GOTO LBL {}", index, k + 1, entries.back()));
    }
    blocks_.label(outside);
    line(commentLine(
        fmt::format("index outside table @{} of {} entries", instruction.index, table.size())));
    line(fmt::format("FN 14: ERROR = {}", tableIndexError));
    int done = blocks_.newLabel();
    for (std::size_t k = 0; k < table.size(); ++k) {
      blocks_.label(entries[k]);
      line(fmt::format("FN 0: {} = {}", target, formulas_.signedNumber(table[k])));
      if (k + 1 < table.size()) {
        blocks_.jump(done);
      }
    }
    blocks_.label(done);
  }

  static std::string term(const std::string& operand) {
    return operand.starts_with('+') ? operand.substr(1) : "( " + operand + " )";
  }

  void printAssignment(const ir::Instruction& instruction) {
    std::string target = formulas_.variable(instruction.result);
    const std::vector<ValueId>& operands = instruction.operands;
    switch (instruction.opcode) {
    case Opcode::Min:   // as std::min and std::max: the first unless the second is beyond it
    case Opcode::Max: { // min: b < a ? b : a; max: a < b ? b : a
      std::string a = blocks_.operand(operands[0]);
      std::string b = blocks_.operand(operands[1]);
      bool min = instruction.opcode == Opcode::Min;
      chooseAssignment(min ? b : a, min ? a : b, target, operands[1], operands[0]);
      return;
    }
    case Opcode::Select: {
      int otherwise = blocks_.newLabel();
      int done = blocks_.newLabel();
      blocks_.jumpUnless(operands[0], otherwise);
      blocks_.assign(target, operands[1]);
      blocks_.jump(done);
      blocks_.label(otherwise);
      blocks_.assign(target, operands[2]);
      blocks_.label(done);
      return;
    }
    case Opcode::Floor:
    case Opcode::Ceil:
      printRounding(instruction, target, instruction.opcode == Opcode::Ceil);
      return;
    case Opcode::Round: { // halves away from zero; SGN 0 is 0 or 1, either rounds 0 to 0
      std::string value = term(blocks_.operand(operands[0]));
      line(fmt::format("{} = INT ( {} + SGN {} * 0.5 )", target, value, value));
      return;
    }
    case Opcode::Rem: { // fmod: INT truncates, so the sign is the dividend's
      std::string a = term(blocks_.operand(operands[0]));
      std::string b = term(blocks_.operand(operands[1]));
      line(fmt::format("{} = {} - INT ( {} / {} ) * {}", target, a, a, b, b));
      return;
    }
    case Opcode::Atan2:
      printAtan2(instruction, target);
      return;
    case Opcode::TableLoad:
      printTableRead(instruction, target);
      return;
    default:
      line(fmt::format("{} = {}", target, formulas_.definition(instruction.result).text));
      return;
    }
  }

  // ---- control flow --------------------------------------------------------

  void printLoop(const ir::Instruction& instruction) {
    std::string index = formulas_.variable(instruction.result);
    blocks_.assign(index, instruction.operands[0]);
    int top = blocks_.newLabel();
    int end = blocks_.newLabel();
    enterLoop(lineSpans_, loops_, lines_.size(), instruction, currentOrigin_);
    blocks_.label(top);
    std::string high = blocks_.operand(instruction.operands[1]);
    line(fmt::format("FN 11: IF +{} GT {} GOTO LBL {}", index, high, end));
    ir::ValueId advance = ir::loopAdvance(function_, instruction);
    if (advance.valid()) { // runs while below high: no GE test, so GT and EQU
      line(fmt::format("FN 9: IF +{} EQU {} GOTO LBL {}", index, high, end));
    }
    printRegion(instruction.regions[0]);
    blocks_.releaseScratch();
    if (advance.valid()) {
      bool computedInPlace =
          allocation_.inVariable(advance) && formulas_.variable(advance) == index;
      if (!computedInPlace) {
        blocks_.assign(index, advance);
      }
    } else {
      line(fmt::format("{} = {} + 1", index, index));
    }
    blocks_.jump(top);
    blocks_.label(end);
  }

  void printIf(const ir::Instruction& instruction) {
    int otherwise = blocks_.newLabel();
    blocks_.jumpUnless(instruction.operands[0], otherwise);
    blocks_.forget();
    printRegion(instruction.regions[0]);
    if (instruction.regions.size() > 1 && !instruction.regions[1].instructions.empty()) {
      int done = blocks_.newLabel();
      blocks_.jump(done);
      blocks_.label(otherwise);
      printRegion(instruction.regions[1]);
      blocks_.label(done);
    } else {
      blocks_.label(otherwise);
    }
  }

  const ir::Function& function_;
  const ir::Allocation& allocation_;
  const HeidenhainProgramOptions& options_;
  std::vector<std::string>& errors_;
  std::vector<std::string> lines_;
  TncFormulaWriter formulas_;
  TncBlockWriter blocks_;
  LineSpans lineSpans_;
  LineOrigin currentOrigin_;
  std::vector<ControllerLoop> loops_; // every loop printed
  std::vector<LineOrigin> printedOrigins_;
  std::optional<long long> pendingTool_;
  std::optional<long long> currentTool_;   // for the radius RL/RR take
  std::optional<long long> explainedTool_; // whose radius register the comment named
  bool spindleOn_ = false;
};

ir::AllocationOptions allocationOptions(const TncProfile& profile,
                                        std::vector<int> parameterVariables) {
  ir::AllocationOptions options;
  for (const TncParameterRange& range : profile.work) {
    options.variables.push_back({range.first, range.last});
  }
  options.parameterVariables = std::move(parameterVariables);
  options.maximumBracketDepth = 8;
  // About ten characters an operation, room for the block number and `QL123 = `.
  options.maximumInlineOperations = (profile.maximumBlockLength - 20) / 10;
  options.shape = tncInlineShape;
  options.statementOpcodes = tncStatementOpcodes();
  return options;
}

} // namespace

std::vector<int> heidenhainParameterVariables(std::size_t parameterCount, const TncProfile& profile,
                                              std::vector<std::string>& errors) {
  const TncParameterRange& range = profile.partParameters;
  if (parameterCount > static_cast<std::size_t>(range.count())) {
    errors.push_back(fmt::format("the part has {} parameters, the {} profile has {} for them "
                                 "({}-{})",
                                 parameterCount, profile.name, range.count(),
                                 tncParameterName(range.first), tncParameterName(range.last)));
  }
  std::vector<int> variables;
  for (std::size_t i = 0; i < parameterCount; ++i) {
    variables.push_back(range.first + static_cast<int>(i));
  }
  return variables;
}

ir::LoweringOptions heidenhainLoweringOptions(const TncProfile& profile, bool inches) {
  ir::LoweringOptions options;
  options.controllerLoops = true;
  options.literalSignificantDigits = profile.significantDigits;
  options.polynomialBlocks = true;
  options.coordinateIncrement = std::pow(10.0, -(profile.coordinateDecimals + (inches ? 1 : 0)));
  options.passesBeforePrinting = macroPassesBeforePrinting();
  return options;
}

namespace {

void extendBlank(std::optional<HeidenhainBlank>& blank, const ir::MachineEvent& point) {
  if (!blank) {
    blank = HeidenhainBlank{point.x, point.y, point.z, point.x, point.y, point.z};
  }
  blank->minX = std::min(blank->minX, point.x);
  blank->minY = std::min(blank->minY, point.y);
  blank->minZ = std::min(blank->minZ, point.z);
  blank->maxX = std::max(blank->maxX, point.x);
  blank->maxY = std::max(blank->maxY, point.y);
  blank->maxZ = std::max(blank->maxZ, point.z);
}

} // namespace

// Feed moves and arcs (as chords within 0.01 mm), one arc at a time: a
// helix of thousands of turns is thousands of arcs.
void HeidenhainBlankFinder::event(const ir::MachineEvent& event) {
  if (event.kind == ir::MachineEvent::Kind::Feed) {
    extendBlank(blank_, event);
  } else if (event.kind == ir::MachineEvent::Kind::Arc) {
    chords_.clear();
    ir::appendArcChords(position_[0], position_[1], position_[2], event, 0.01, chords_);
    for (const ir::MachineEvent& chord : chords_) {
      extendBlank(blank_, chord);
    }
  }
  if (ir::isMove(event)) {
    position_ = {event.x, event.y, event.z};
  }
}

std::optional<HeidenhainBlank> HeidenhainBlankFinder::blank() const {
  std::optional<HeidenhainBlank> blank = blank_;
  if (blank) {
    blank->maxZ = std::max(blank->maxZ, 0.0);
  }
  return blank;
}

std::optional<HeidenhainBlank> heidenhainBlank(const ir::ToolPath& path) {
  HeidenhainBlankFinder finder;
  for (const ir::MachineEvent& event : path.events) {
    finder.event(event);
  }
  return finder.blank();
}

HeidenhainProgram writeHeidenhainProgram(const ir::Function& function,
                                         const HeidenhainProgramOptions& options) {
  HeidenhainProgram program;
  std::vector<int> parameters =
      heidenhainParameterVariables(function.parameters.size(), options.profile, program.errors);
  if (!program.errors.empty()) {
    return program;
  }
  ir::AllocationResult allocated =
      ir::allocateVariables(function, allocationOptions(options.profile, parameters));
  for (const ir::AllocationFailure& failure : allocated.failures) {
    program.errors.push_back(
        fmt::format("{} (the {} profile's Q ranges)", failure.message, options.profile.name));
  }
  if (!program.errors.empty()) {
    return program;
  }
  ProgramPrinter printer(function, allocated.allocation, options, program.errors);
  std::string text = printer.print();
  if (program.errors.empty()) {
    program.text = std::move(text);
    program.lineOrigins = printer.takeLineOrigins();
  }
  return program;
}

} // namespace cncc::backends
