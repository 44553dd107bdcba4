#include "cncc/backends/virtual_controller.h"

#include "sim_machine.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>

namespace cncc::backends::sim {

namespace {

bool isCommon(const ControllerProfile& profile, int variable) {
  for (const VariableRange& range : profile.volatileCommon) {
    if (range.contains(variable)) {
      return true;
    }
  }
  for (const VariableRange& range : profile.retainedCommon) {
    if (range.contains(variable)) {
      return true;
    }
  }
  return false;
}

// System variables a program may set without changing the path: single
// block and feed hold suppression, the part counters, the message stop.
bool isHarmlessSystemVariable(int variable) {
  return variable == 3003 || variable == 3004 || variable == 3006 || variable == 3901 ||
         variable == 3902;
}

} // namespace

Machine::Machine(const ProgramText& program, const ControllerProfile& profile,
                 const SimulationOptions& options, ExecutedPath& path)
    : program_(program), profile_(profile), options_(options), path_(path) {
  Frame main;
  for (const MacroArgument& argument : options.arguments) {
    if (std::optional<int> local = profile.localForLetter(argument.letter)) {
      main.arguments[*local] = Value::of(argument.value);
    }
  }
  main.locals = main.arguments;
  frames_.push_back(main);
  for (const auto& [variable, value] : options.commonVariables) {
    commons_[variable] = Value::of(value);
  }
  blockExecutions_.assign(program.blocks.size(), 0);
}

std::map<int, std::optional<double>> Machine::commonVariables() const {
  std::map<int, std::optional<double>> values;
  for (const auto& [variable, value] : commons_) {
    values[variable] = value.vacant ? std::nullopt : std::optional<double>(value.number);
  }
  return values;
}

Machine::Frame& Machine::localFrame() {
  auto frame = std::find_if(frames_.rbegin(), frames_.rend(),
                            [](const Frame& candidate) { return !candidate.subprogram; });
  return *frame; // the main program's frame is never a subprogram's
}

const Machine::Frame& Machine::localFrame() const {
  return const_cast<Machine*>(this)->localFrame();
}

Value Machine::read(int variable, const Block& block) const {
  if (variable == 0) {
    return Value::vacantValue();
  }
  if (profile_.locals.contains(variable) && variable < localCount) {
    return localFrame().locals[variable];
  }
  if (isCommon(profile_, variable)) {
    auto found = commons_.find(variable);
    return found == commons_.end() ? Value::vacantValue() : found->second;
  }
  if (variable >= 5001 && variable <= 5003) { // the position at the end of the last block
    if (!modal_.coordinates.isPlain()) {
      failInBlock(block, fmt::format("#{} while G52, G68 or G16 is on is not simulated: which "
                                     "coordinate system it reads differs",
                                     variable));
    }
    const Point3& position = modal_.position;
    return Value::of(variable == 5001 ? position.x : variable == 5002 ? position.y : position.z);
  }
  if (std::optional<Value> modal = modalInformation(variable, block)) {
    return *modal;
  }
  if (isHarmlessSystemVariable(variable)) {
    auto found = systemVariables_.find(variable);
    return found == systemVariables_.end() ? Value::of(0) : found->second;
  }
  failInBlock(block, variable < 1000
                         ? fmt::format("#{} does not exist on {}", variable, profile_.name)
                         : fmt::format("the system variable #{} is not simulated", variable));
}

void Machine::write(int variable, Value value, const Block& block) {
  if (variable == 0) {
    failInBlock(block, "#0 is always vacant and cannot be assigned");
  }
  if (profile_.locals.contains(variable) && variable < localCount) {
    localFrame().locals[variable] = value;
    return;
  }
  if (isCommon(profile_, variable)) {
    commons_[variable] = value;
    return;
  }
  if (variable == 3000) {
    failInBlock(block, fmt::format("alarm {} raised by #3000: {}",
                                   3000 + static_cast<long long>(value.number), block.comment));
  }
  if (isHarmlessSystemVariable(variable)) {
    systemVariables_[variable] = value;
    return;
  }
  failInBlock(block, variable < 1000
                         ? fmt::format("#{} does not exist on {}", variable, profile_.name)
                         : fmt::format("the system variable #{} is not simulated", variable));
}

std::size_t Machine::findSequenceNumber(int number, const Block& from,
                                        std::size_t fromIndex) const {
  const ProgramUnit& unit = program_.programs[frames_.back().program];
  std::optional<std::size_t> found;
  for (std::size_t index = unit.first; index < unit.end; ++index) {
    if (program_.blocks[index].sequenceNumber != number) {
      continue;
    }
    if (found) {
      failInBlock(from, fmt::format("GOTO {}: N{} appears on lines {} and {}", number, number,
                                    program_.blocks[*found].line, program_.blocks[index].line));
    }
    found = index;
  }
  if (!found) {
    failInBlock(from,
                fmt::format("GOTO {}: there is no block N{} in this program", number, number));
  }
  // A jump may leave loops but not enter one: the target's loops must be
  // loops the GOTO is already in.
  const std::vector<std::size_t>& targetLoops = program_.blocks[*found].loops;
  const std::vector<std::size_t>& ownLoops = program_.blocks[fromIndex].loops;
  bool entersLoop = targetLoops.size() > ownLoops.size() ||
                    !std::equal(targetLoops.begin(), targetLoops.end(), ownLoops.begin());
  if (entersLoop) {
    failInBlock(from, fmt::format("GOTO {} jumps into the loop DO{} of line {}", number,
                                  program_.blocks[targetLoops.back()].loopIdentifier,
                                  program_.blocks[targetLoops.back()].line));
  }
  return *found;
}

void Machine::runOutOfProgram(std::size_t index) const {
  bool inMacro = frames_.size() > 1 || options_.runAsMacroCall;
  std::string message =
      inMacro ? "the macro ends without M99" : "the program ends without M30 or M02";
  if (index < program_.blocks.size()) {
    failInBlock(program_.blocks[index], message);
  }
  const Block& last = program_.blocks.back();
  throw SimulationError(last.line, last.text, message);
}

Machine::Next Machine::executeBlock(const Block& block, std::size_t& next) {
  switch (block.kind) {
  case Block::Kind::Empty:
  case Block::Kind::ProgramName:
  case Block::Kind::EndOfRecord:
    return Next::Continue;
  case Block::Kind::Assignment:
    write(evaluateVariableNumber(block.variable, *this, block), evaluate(block.value, *this, block),
          block);
    return Next::Continue;
  case Block::Kind::IfThen:
    if (evaluate(block.condition, *this, block).number != 0) {
      write(evaluateVariableNumber(block.variable, *this, block),
            evaluate(block.value, *this, block), block);
    }
    return Next::Continue;
  case Block::Kind::IfGoto:
    if (evaluate(block.condition, *this, block).number == 0) {
      return Next::Continue;
    }
    [[fallthrough]];
  case Block::Kind::Goto: {
    int number = evaluateWholeNumber(block.target, *this, block, "the GOTO target");
    next = findSequenceNumber(number, block, next - 1);
    return Next::Jump;
  }
  case Block::Kind::While:
    if (block.hasCondition && evaluate(block.condition, *this, block).number == 0) {
      next = block.partner + 1;
      return Next::Jump;
    }
    return Next::Continue;
  case Block::Kind::End:
    next = block.partner;
    return Next::Jump;
  case Block::Kind::Words:
    return executeWords(block, next);
  }
  return Next::Continue;
}

void Machine::run() {
  if (program_.programs.empty()) {
    throw SimulationError(0, "", "the file holds no program");
  }
  std::size_t index = program_.programs.front().first;
  while (true) {
    const ProgramUnit& unit = program_.programs[frames_.back().program];
    if (index >= unit.end) {
      runOutOfProgram(index);
    }
    const Block& block = program_.blocks[index];
    if (++blocksExecuted_ > options_.stepLimit) {
      failInBlock(
          block, fmt::format("more than {} blocks executed: an endless loop?", options_.stepLimit));
    }
    ++blockExecutions_[index];
    std::size_t next = index + 1;
    Next decision = executeBlock(block, next);
    if (decision == Next::Stop) {
      return;
    }
    index = next;
  }
}

SimulationResult simulateProgram(std::string_view text, const ControllerProfile& profile,
                                 const SimulationOptions& options) {
  SimulationResult result;
  try {
    ProgramText program = readProgram(text, profile, options.reading);
    Machine machine(program, profile, options, result.path);
    try {
      machine.run();
    } catch (const SimulationError& error) {
      result.error = error;
    }
    result.blocksExecuted = machine.blocksExecuted();
    result.blockExecutions = machine.blockExecutions();
    result.commonVariables = machine.commonVariables();
  } catch (const SimulationError& error) {
    result.error = error;
  }
  return result;
}

std::optional<MacroArgument>
parseMacroArgument(std::string_view text, const ControllerProfile& profile, std::string& problem) {
  if (text.size() < 2 || !profile.localForLetter(text[0])) {
    problem = fmt::format("'{}' is not a G65 argument: expected a letter of {} and a number, "
                          "as in A3.",
                          text, profile.name);
    return std::nullopt;
  }
  std::string_view number = text.substr(1);
  MacroArgument argument;
  argument.letter = text[0];
  auto [end, error] = std::from_chars(number.data(), number.data() + number.size(), argument.value);
  if (error != std::errc() || end != number.data() + number.size() ||
      number.find('.') == std::string_view::npos ||
      number.find_first_of("eE") != std::string_view::npos) {
    problem = fmt::format("'{}' is not a G65 argument: the number needs a decimal point, as in "
                          "A3.",
                          text);
    return std::nullopt;
  }
  return argument;
}

} // namespace cncc::backends::sim
