#include "cncc/backends/linuxcnc_program.h"

#include "cncc/backends/gcode_writer.h"
#include "cncc/backends/line_spans.h"
#include "cncc/backends/program_format.h"
#include "cncc/ir/interpreter.h"
#include "linuxcnc_expressions.h"
#include "linuxcnc_moves.h"
#include "macro_simplify.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <map>
#include <set>

namespace cncc::backends {

namespace {

using ir::Opcode;
using ir::ValueId;

// LinuxCNC's read-only predefined named parameters (LinuxCNC 2.9): a part
// parameter of one of these names would be refused at run time.
constexpr std::array predefinedNames = {
    "_x",
    "_y",
    "_z",
    "_a",
    "_b",
    "_c",
    "_u",
    "_v",
    "_w",
    "_abs_x",
    "_abs_y",
    "_abs_z",
    "_abs_a",
    "_abs_b",
    "_abs_c",
    "_abs_u",
    "_abs_v",
    "_abs_w",
    "_line",
    "_motion_mode",
    "_plane",
    "_ccomp",
    "_metric",
    "_imperial",
    "_absolute",
    "_incremental",
    "_inverse_time",
    "_units_per_minute",
    "_units_per_rev",
    "_coord_system",
    "_tool_offset",
    "_retract_r_plane",
    "_retract_old_z",
    "_spindle_rpm_mode",
    "_spindle_css_mode",
    "_ijk_absolute_mode",
    "_lathe_diameter_mode",
    "_lathe_radius_mode",
    "_spindle_on",
    "_spindle_cw",
    "_mist",
    "_flood",
    "_speed_override",
    "_feed_override",
    "_adaptive_feed",
    "_feed_hold",
    "_feed",
    "_rpm",
    "_current_tool",
    "_current_pocket",
    "_selected_tool",
    "_selected_pocket",
    "_value",
    "_value_returned",
    "_task",
    "_call_level",
    "_remap_level",
};

bool isPredefined(const std::string& name) {
  return std::find(predefinedNames.begin(), predefinedNames.end(), name) != predefinedNames.end();
}

// A comment line: `;` comments have no special meaning (`(MSG,..)` would).
std::string commentLine(std::string_view text) {
  std::string body;
  for (char c : text) {
    unsigned char u = static_cast<unsigned char>(c);
    body += std::isprint(u) ? c : ' ';
  }
  std::string line = "; " + body;
  line.resize(std::min(line.size(), static_cast<std::size_t>(linuxcncMaximumLineLength)));
  return line;
}

class ProgramPrinter {
public:
  ProgramPrinter(const ir::Function& function, const ir::Allocation& allocation,
                 const LinuxcncProgramOptions& options, std::vector<std::string>& errors)
      : function_(function), allocation_(allocation), options_(options), errors_(errors),
        names_(linuxcncParameterNames(function.parameters)),
        expressions_(function, allocation, names_, {12, coordinateDecimals()}, errors),
        moves_(expressions_, lines_) {}

  std::string print() {
    printHeader();
    if (options_.callable) {
      line(fmt::format("o<{}> sub", subroutineName()));
    }
    printParameters();
    for (std::string& block : startBlocks(options_.setup, options_.inches,
                                          expressions_.constant(options_.blendTolerance))) {
      line(std::move(block));
    }
    printTables();
    printRegion(function_.body);
    if (spindleOn_) {
      line("M5");
    }
    for (const std::string& block : options_.setup.end) {
      line(block);
    }
    if (options_.callable) {
      line(fmt::format("o<{}> endsub", subroutineName()));
    }
    line("M2");
    return joinLines();
  }

  // The CDL span of each line of the program print() returned.
  std::vector<frontend::SourceSpan> takeLineSpans() { return std::move(printedSpans_); }

private:
  void line(std::string text) { lines_.push_back(std::move(text)); }

  std::string joinLines() {
    std::string text;
    std::size_t longest = 0;
    int tooLong = 0;
    std::vector<frontend::SourceSpan> spans = lineSpans_.spans(lines_.size());
    FormattedProgram formatted = formatProgram(std::move(lines_), options_.setup, errors_);
    printedSpans_ = LineSpans::kept(spans, formatted.printedLine);
    for (const std::string& block : formatted.lines) {
      if (static_cast<int>(block.size()) > linuxcncMaximumLineLength) {
        longest = std::max(longest, block.size());
        ++tooLong;
      }
      text += block;
      text += '\n';
    }
    if (tooLong > 0) {
      errors_.push_back(fmt::format("{} lines exceed LinuxCNC's {} characters, the longest has {}",
                                    tooLong, linuxcncMaximumLineLength, longest));
    }
    return text;
  }

  std::string subroutineName() const {
    std::string name;
    for (char c : options_.partName) {
      name += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
    return name;
  }

  // ---- header ------------------------------------------------------------

  std::string parameterDefault(std::size_t index) const {
    return expressions_.constant(function_.parameters[index].defaultValue);
  }

  void printHeader() {
    line(commentLine(fmt::format("{} - part {}", options_.sourceName, options_.partName)));
    if (options_.callable) {
      std::string call = fmt::format("call: o<{}> call", subroutineName());
      for (std::size_t i = 0; i < function_.parameters.size(); ++i) {
        call += fmt::format(" [{}]", parameterDefault(i));
      }
      line(commentLine(call));
    }
    for (std::size_t i = 0; i < function_.parameters.size(); ++i) {
      std::string where = options_.callable ? fmt::format("#{} = ", i + 1) : "";
      line(commentLine(fmt::format(
          "{}#<{}> {}, {} {}", where, names_[i], function_.parameters[i].name,
          function_.parameters[i].fixed ? "fixed at" : "default", parameterDefault(i))));
    }
    for (const auto& [base, tables] : ir::tablesByBase(function_, allocation_)) {
      int count = static_cast<int>(function_.tables[tables.front()].size());
      line(commentLine(fmt::format("#{}-#{} table {}, {} values", base, base + count - 1,
                                   fmt::join(tables, " and "), count)));
    }
  }

  void printParameters() {
    if (options_.callable &&
        function_.parameters.size() > static_cast<std::size_t>(linuxcncMaximumCallArguments)) {
      errors_.push_back(fmt::format("the part has {} parameters, a LinuxCNC call takes up to {} "
                                    "arguments",
                                    function_.parameters.size(), linuxcncMaximumCallArguments));
    }
    for (std::size_t i = 0; i < function_.parameters.size(); ++i) {
      std::string value = options_.callable ? fmt::format("#{}", i + 1) : parameterDefault(i);
      line(fmt::format("#<{}> = {}", names_[i], value));
    }
    printFixedParameterChecks();
  }

  // A parameter whose default the compiler built into the program (a loop
  // bound, a curve's points): any other value aborts the program rather
  // than cutting a part the operator did not ask for. The value is compared
  // with the literal the defaults assign, so the test is exact.
  void printFixedParameterChecks() {
    for (std::size_t i = 0; i < function_.parameters.size(); ++i) {
      if (!function_.parameters[i].fixed) {
        continue;
      }
      int label = newLabel();
      line(fmt::format("o{} if [#<{}> NE {}]", label, names_[i], parameterDefault(i)));
      line(fmt::format("(abort, {} is fixed at {})", function_.parameters[i].name,
                       parameterDefault(i)));
      line(fmt::format("o{} endif", label));
    }
  }

  void printTables() {
    for (const auto& [base, tables] : ir::tablesByBase(function_, allocation_)) {
      const std::vector<double>& values = function_.tables[tables.front()];
      for (std::size_t i = 0; i < values.size(); ++i) {
        line(fmt::format("#{} = {}", base + static_cast<int>(i), expressions_.constant(values[i])));
      }
    }
  }

  // ---- statements ----------------------------------------------------------

  int newLabel() { return nextLabel_++; }

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
      moves_.rapid(instruction.operands[0], instruction.operands[1], instruction.operands[2]);
      return;
    case Opcode::Feed:
      moves_.feed(instruction.operands[0], instruction.operands[1], instruction.operands[2],
                  instruction.operands[3]);
      return;
    case Opcode::Arc:
      moves_.arc(instruction.index == static_cast<std::uint32_t>(ir::ArcTurn::Clockwise),
                 instruction.operands);
      return;
    case Opcode::Nurbs: // lowered only for targets with NURBS blocks
      errors_.push_back("LinuxCNC has no NURBS blocks of the G06.2 kind (move.nurbs)");
      return;
    case Opcode::Spline: // lowered only for the sinumerik target
      errors_.push_back("LinuxCNC has no Sinumerik spline blocks (move.spline)");
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
      for (std::string& block : setupBlocks(options_.setup, instruction,
                                            expressions_.coordinateLiteral(instruction.number))) {
        line(std::move(block));
      }
      if (instruction.opcode == Opcode::Home) { // Z is at the machine's reference
        moves_.forget();
      }
      return;
    case Opcode::Alarm:
      line(fmt::format("(abort, {})", gcodeCommentText(instruction.text)));
      return;
    case Opcode::Comment:
      line(commentLine(instruction.text));
      return;
    case Opcode::CutBegin: // the cut's own comment says it
    case Opcode::Param:
      return;
    default:
      break;
    }
    if (instruction.result.valid() && allocation_.inVariable(instruction.result)) {
      printAssignment(instruction);
    }
  }

  void printSpindle(const ir::Instruction& instruction) {
    ValueId speed = instruction.operands[0];
    std::optional<double> literal = expressions_.constantOf(speed);
    line(fmt::format("S{} M3", literal ? fmt::format("{}", std::llround(*literal))
                                       : expressions_.operand(speed)));
    spindleOn_ = true;
  }

  void printTool(const ir::Instruction& instruction) {
    if (spindleOn_) {
      line("M5");
      spindleOn_ = false;
    }
    for (std::string& block :
         toolChangeBlocks(options_.setup, std::llround(instruction.number), "")) {
      line(std::move(block));
    }
    std::optional<double> diameter = expressions_.constantOf(instruction.operands[0]);
    if (diameter) {
      line(commentLine(fmt::format("tool diameter {}", expressions_.coordinateLiteral(*diameter))));
    }
    moves_.forget();
    moves_.beforeNextZ(lengthOffsetWords(
        options_.setup, static_cast<int>(std::llround(instruction.number)), instruction.index));
  }

  // `o<n> if [c]` .. `o<n> else` .. `o<n> endif` around single assignments.
  void chooseAssignment(const std::string& condition, const std::string& target,
                        const std::string& whenTrue, const std::string& whenFalse) {
    int label = newLabel();
    line(fmt::format("o{} if {}", label, condition));
    line(fmt::format("{} = {}", target, whenTrue));
    line(fmt::format("o{} else", label));
    line(fmt::format("{} = {}", target, whenFalse));
    line(fmt::format("o{} endif", label));
  }

  void printAssignment(const ir::Instruction& instruction) {
    std::string target = expressions_.variable(instruction.result);
    auto operand = [&](std::size_t i) { return expressions_.operand(instruction.operands[i]); };
    auto bare = [&](std::size_t i) {
      return bracketedUnlessTighter(expressions_.value(instruction.operands[i]),
                                    LinuxcncForm::Additive);
    };
    switch (instruction.opcode) {
    case Opcode::Min: // as std::min and std::max: the first unless the second is beyond it
      chooseAssignment(fmt::format("[{} LT {}]", bare(1), bare(0)), target, operand(1), operand(0));
      return;
    case Opcode::Max:
      chooseAssignment(fmt::format("[{} LT {}]", bare(0), bare(1)), target, operand(1), operand(0));
      return;
    case Opcode::Select:
      chooseAssignment(expressions_.condition(instruction.operands[0]), target, operand(1),
                       operand(2));
      return;
    case Opcode::Rem: { // fmod: LinuxCNC's MOD is never negative, the sign comes from a
      std::string magnitude =
          fmt::format("ABS[{}] MOD ABS[{}]", expressions_.value(instruction.operands[0]).text,
                      expressions_.value(instruction.operands[1]).text);
      chooseAssignment(fmt::format("[{} LT 0]", bare(0)), target, fmt::format("-[{}]", magnitude),
                       fmt::format("[{}]", magnitude));
      return;
    }
    default:
      line(fmt::format(
          "{} = {}", target,
          bracketedUnlessTighter(expressions_.definition(instruction.result), LinuxcncForm::Atom)));
      return;
    }
  }

  // ---- control flow --------------------------------------------------------

  void printLoop(const ir::Instruction& instruction) {
    int label = newLabel();
    std::string index = expressions_.variable(instruction.result);
    line(fmt::format("{} = {}", index, expressions_.operand(instruction.operands[0])));
    line(fmt::format("o{} while [{} LE {}]", label, index,
                     bracketedUnlessTighter(expressions_.value(instruction.operands[1]),
                                            LinuxcncForm::Additive)));
    moves_.forget();
    printRegion(instruction.regions[0]);
    line(fmt::format("{} = [{}+1]", index, index));
    line(fmt::format("o{} endwhile", label));
    moves_.forget();
  }

  void printIf(const ir::Instruction& instruction) {
    int label = newLabel();
    line(fmt::format("o{} if {}", label, expressions_.condition(instruction.operands[0])));
    moves_.forget();
    printRegion(instruction.regions[0]);
    if (instruction.regions.size() > 1 && !instruction.regions[1].instructions.empty()) {
      line(fmt::format("o{} else", label));
      moves_.forget();
      printRegion(instruction.regions[1]);
    }
    line(fmt::format("o{} endif", label));
    moves_.forget();
  }

  int coordinateDecimals() const { return options_.inches ? 6 : 5; }

  const ir::Function& function_;
  const ir::Allocation& allocation_;
  const LinuxcncProgramOptions& options_;
  std::vector<std::string>& errors_;
  std::vector<std::string> names_;
  LinuxcncExpressionWriter expressions_;
  std::vector<std::string> lines_;
  LineSpans lineSpans_;
  frontend::SourceSpan currentSpan_;
  std::vector<frontend::SourceSpan> printedSpans_;
  LinuxcncMoveWriter moves_;
  int nextLabel_ = 100;
  bool spindleOn_ = false;
};

ir::AllocationOptions allocationOptions(std::size_t parameterCount) {
  ir::AllocationOptions options;
  options.variables.push_back({linuxcncFirstGlobal, linuxcncLastGlobal});
  // Part parameters are named, not numbered: the allocator is given numbers
  // beyond the globals for them, which the printer never writes.
  for (std::size_t i = 0; i < parameterCount; ++i) {
    options.parameterVariables.push_back(linuxcncLastGlobal + 1 + static_cast<int>(i));
  }
  options.maximumBracketDepth = 12;
  // About ten characters an operation, room for the address and `#n = `.
  options.maximumInlineOperations = (linuxcncMaximumLineLength - 24) / 12;
  options.shape = linuxcncInlineShape;
  options.statementOpcodes = linuxcncStatementOpcodes();
  return options;
}

} // namespace

std::vector<std::string> linuxcncParameterNames(const std::vector<ir::Parameter>& parameters) {
  std::vector<std::string> names;
  std::set<std::string> taken;
  for (const ir::Parameter& parameter : parameters) {
    std::string name = "_";
    for (char c : parameter.name) {
      name += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
    while (isPredefined(name) || taken.contains(name)) {
      name += '_';
    }
    taken.insert(name);
    names.push_back(name);
  }
  return names;
}

double linuxcncBlendTolerance(const std::vector<ir::CutGeometry>& cuts) {
  std::optional<double> smallest;
  for (const ir::CutGeometry& cut : cuts) {
    if (!std::isnan(cut.tolerance) && cut.tolerance > 0) {
      smallest = std::min(smallest.value_or(cut.tolerance), cut.tolerance);
    }
  }
  return smallest.value_or(ir::LoweringOptions().defaultTolerance);
}

LinuxcncProgram writeLinuxcncProgram(const ir::Function& function,
                                     const LinuxcncProgramOptions& options) {
  LinuxcncProgram program;
  ir::Function simplified = simplifyForMacroProgram(function);
  ir::AllocationResult allocated =
      ir::allocateVariables(simplified, allocationOptions(simplified.parameters.size()));
  for (const ir::AllocationFailure& failure : allocated.failures) {
    program.errors.push_back(failure.message);
  }
  if (!program.errors.empty()) {
    return program;
  }
  ProgramPrinter printer(simplified, allocated.allocation, options, program.errors);
  std::string text = printer.print();
  if (program.errors.empty()) {
    program.text = std::move(text);
    program.lineSpans = printer.takeLineSpans();
  }
  return program;
}

} // namespace cncc::backends
