#include "cncc/backends/program_execution.h"

#include "cncc/backends/controller_profile.h"
#include "cncc/backends/gcode_writer.h"
#include "cncc/backends/heidenhain_controller.h"
#include "cncc/backends/linuxcnc_canon.h"
#include "cncc/backends/linuxcnc_program.h"
#include "cncc/backends/rs274.h"
#include "cncc/backends/sinumerik_controller.h"
#include "cncc/backends/virtual_controller.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <set>

namespace cncc::backends {

namespace {

constexpr double kArcSagitta = controllerArcSagitta;

ProgramExecution failed(std::string text, int line, std::string message) {
  ProgramExecution execution;
  execution.text = std::move(text);
  execution.failure = ControllerFailure{line, std::move(message), ""};
  return execution;
}

// The text with the first block `#n=...` given `value` instead: what the
// operator edits in a program whose parameters are set near its top.
std::optional<std::string> withEditedDefault(const std::string& text, int variable, double value) {
  std::string prefix = fmt::format("#{}=", variable);
  std::size_t begin = 0;
  while (begin < text.size()) {
    std::size_t end = text.find('\n', begin);
    end = end == std::string::npos ? text.size() : end;
    if (text.compare(begin, prefix.size(), prefix) == 0) {
      std::string edited = text.substr(0, begin + prefix.size());
      edited += formatGcodeNumber(value, 8);
      edited += text.substr(end);
      return edited;
    }
    begin = end + 1;
  }
  return std::nullopt;
}

void addNamedVariables(const sim::Expression& expression, std::set<int>& variables) {
  if (expression.kind == sim::Expression::Kind::Variable &&
      expression.operands.front().kind == sim::Expression::Kind::Number &&
      expression.operands.front().number > 0) {
    variables.insert(static_cast<int>(expression.operands.front().number));
  }
  for (const sim::Expression& operand : expression.operands) {
    addNamedVariables(operand, variables);
  }
}

std::size_t namedVariableCount(const sim::ProgramText& program) {
  std::set<int> variables;
  for (const sim::Block& block : program.blocks) {
    bool assigns =
        block.kind == sim::Block::Kind::Assignment || block.kind == sim::Block::Kind::IfThen;
    if (assigns && block.variable.kind == sim::Expression::Kind::Number) {
      variables.insert(static_cast<int>(block.variable.number));
    }
    for (const sim::Expression* expression :
         {&block.condition, &block.target, &block.variable, &block.value}) {
      addNamedVariables(*expression, variables);
    }
    for (const sim::Word& word : block.words) {
      addNamedVariables(word.value, variables);
    }
  }
  return variables.size();
}

// Sets the parameters as `request.passing` says; nullopt (and `problem`)
// when the program gives no way to.
std::optional<std::string> applyParameters(const ExecutionRequest& request,
                                           const ControllerProfile& profile,
                                           sim::SimulationOptions& options, std::string& problem) {
  std::string text = request.text;
  for (const ParameterValue& parameter : request.parameters) {
    switch (request.passing) {
    case ParameterPassing::None:
      break;
    case ParameterPassing::EditedDefaults: {
      std::optional<std::string> edited =
          withEditedDefault(text, parameter.variable, parameter.value);
      if (!edited) {
        problem = fmt::format("the program sets no #{} for parameter {}", parameter.variable,
                              parameter.name);
        return std::nullopt;
      }
      text = std::move(*edited);
      break;
    }
    case ParameterPassing::MacroArguments: {
      std::optional<char> letter = profile.letterForLocal(parameter.variable);
      if (!letter) {
        problem = fmt::format("no G65 argument reaches #{} (parameter {})", parameter.variable,
                              parameter.name);
        return std::nullopt;
      }
      options.arguments.push_back({*letter, parameter.value});
      break;
    }
    case ParameterPassing::CommonVariables:
      options.commonVariables[parameter.variable] = parameter.value;
      break;
    }
  }
  return text;
}

ProgramExecution runOnController(const ExecutionRequest& request,
                                 const ControllerProfile& profile) {
  sim::SimulationOptions options;
  options.runAsMacroCall = request.callable;
  options.reading.lowerCaseComments = request.lowerCaseComments;
  options.toolRadii = request.toolRadii;
  std::string problem;
  std::optional<std::string> text = applyParameters(request, profile, options, problem);
  if (!text) {
    return failed(request.text, 0, problem);
  }
  ProgramExecution execution;
  execution.text = std::move(*text);
  sim::SimulationResult result = sim::simulateProgram(execution.text, profile, options);
  execution.increment =
      result.path.inches ? profile.leastInputIncrement / 10.0 : profile.leastInputIncrement;
  if (result.error) {
    execution.failure =
        ControllerFailure{result.error->line(), result.error->what(), result.error->lineText()};
    return execution;
  }
  double sagitta = result.path.inches ? kArcSagitta / 25.4 : kArcSagitta;
  ir::ToolPath moves = sim::executedToolPath(result.path);
  try {
    checkMeasurablePath(moves, sagitta);
  } catch (const PathTooLargeToMeasure& error) {
    execution.failure = ControllerFailure{0, error.what(), ""};
    return execution;
  }
  execution.path = executedPathOfToolPath(ir::flattenArcs(moves, sagitta));
  sim::ProgramText program = sim::readProgram(execution.text, profile, options.reading);
  sim::LoopOperationCounts operations = sim::countLoopOperations(program, result);
  if (operations.feedMoves > 0) {
    execution.operations = operations;
  }
  execution.variables = namedVariableCount(program);
  return execution;
}

ProgramExecution runMacroProgram(const ExecutionRequest& request, std::string_view profileName) {
  if (request.machineProfile) {
    return runOnController(request, *request.machineProfile);
  }
  std::string_view name = request.profile.empty() ? profileName : request.profile;
  const ControllerProfile* profile = findControllerProfile(name);
  if (profile == nullptr) {
    return failed(request.text, 0, fmt::format("unknown controller profile '{}'", name));
  }
  return runOnController(request, *profile);
}

ProgramExecution runM80(const ExecutionRequest& request) {
  return runMacroProgram(request, "m80");
}

ProgramExecution runFanuc(const ExecutionRequest& request) {
  return runMacroProgram(request, "fanuc");
}

// Plain G-code on a controller that takes the 4 decimals the gcode target
// prints (0.0001 mm).
ProgramExecution runGcode(const ExecutionRequest& request) {
  ControllerProfile profile = *findControllerProfile("fanuc");
  profile.coordinateDecimals = 4;
  profile.leastInputIncrement = 0.0001;
  ExecutionRequest plain = request;
  plain.passing = ParameterPassing::None;
  return runOnController(plain, profile);
}

std::optional<double> csvNumber(std::string_view text) {
  double value = 0;
  auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size()) {
    return std::nullopt;
  }
  return value;
}

// One `x,y,z,feed,rapid` row; nullopt when it is not one.
std::optional<ir::MachineEvent> csvMove(std::string_view row) {
  std::array<double, 5> fields{};
  for (std::size_t i = 0; i < fields.size(); ++i) {
    std::size_t comma = row.find(',');
    if ((comma == std::string_view::npos) != (i + 1 == fields.size())) {
      return std::nullopt;
    }
    std::optional<double> value = csvNumber(row.substr(0, comma));
    if (!value) {
      return std::nullopt;
    }
    fields[i] = *value;
    row = comma == std::string_view::npos ? "" : row.substr(comma + 1);
  }
  ir::MachineEvent event;
  event.kind = fields[4] != 0 ? ir::MachineEvent::Kind::Rapid : ir::MachineEvent::Kind::Feed;
  event.x = fields[0];
  event.y = fields[1];
  event.z = fields[2];
  event.feed = fields[3];
  return event;
}

// The jit target's program is its tool path as CSV: read back, it is the path.
ProgramExecution runJit(const ExecutionRequest& request) {
  ProgramExecution execution;
  execution.text = request.text;
  execution.increment = 1e-6; // the CSV's 6 decimals
  ir::ToolPath toolPath;
  std::string_view text = request.text;
  int line = 0;
  while (!text.empty()) {
    std::size_t newline = text.find('\n');
    std::string_view row = text.substr(0, newline);
    text = newline == std::string_view::npos ? "" : text.substr(newline + 1);
    if (++line == 1 || row.empty()) {
      continue; // the header
    }
    std::optional<ir::MachineEvent> event = csvMove(row);
    if (!event) {
      return failed(request.text, line, "not a row x,y,z,feed,rapid");
    }
    toolPath.events.push_back(*event);
  }
  execution.path = executedPathOfToolPath(toolPath);
  return execution;
}

// A Sinumerik program in the virtual Sinumerik; it prints 5 decimals.
// The line `number` (1-based) of the text; empty past its end.
std::string lineOf(std::string_view text, int number) {
  for (int line = 1; line < number && !text.empty(); ++line) {
    std::size_t newline = text.find('\n');
    text = newline == std::string_view::npos ? std::string_view() : text.substr(newline + 1);
  }
  return std::string(text.substr(0, text.find('\n')));
}

ProgramExecution runSinumerik(const ExecutionRequest& request) {
  ProgramExecution execution;
  execution.text = request.text;
  execution.increment = 1e-5;
  sinumerik::SinumerikRunOptions options;
  options.toolRadii = request.radiiOfTools;
  sinumerik::SinumerikRun run = sinumerik::runSinumerikProgram(request.text, options);
  if (run.error) {
    execution.failure = ControllerFailure{run.error->line(), run.error->what(),
                                          lineOf(request.text, run.error->line())};
    return execution;
  }
  execution.path = sinumerik::executedPathOf(run, {});
  return execution;
}

constexpr int kLinuxcncSeconds = 60;

// The path from LinuxCNC's canonical calls, `increment` the least increment
// of what was read.
ProgramExecution linuxcncPath(const ExecutionRequest& request, std::string_view canon,
                              double increment, std::string_view reader) {
  ProgramExecution execution;
  execution.text = request.text;
  execution.increment = increment;
  try {
    execution.path = readLinuxcncCanon(canon, kArcSagitta, maximumMeasuredPoints);
  } catch (const ExecutionMismatch& error) {
    return failed(request.text, 0, fmt::format("{}'s output: {}", reader, error.what()));
  } catch (const PathTooLargeToMeasure& error) {
    return failed(request.text, 0, error.what());
  }
  return execution;
}

// A LinuxCNC program through LinuxCNC's interpreter as a library (the
// Python module `gcode`): every coordinate as the double it computed. The
// path is read within the program's own decimals.
ProgramExecution runGcodeModuleExecution(const ExecutionRequest& request, const GcodeModuleRun& run,
                                         bool inches) {
  if (run.tooManyCalls) {
    return failed(request.text, 0,
                  PathTooLargeToMeasure(maximumMeasuredPoints, kArcSagitta).what());
  }
  if (run.exitCode < 0) {
    return failed(
        request.text, 0,
        fmt::format("LinuxCNC's interpreter did not finish within {} s", kLinuxcncSeconds));
  }
  std::string_view errors = run.errors;
  errors = errors.substr(0, errors.find('\n'));
  if (run.exitCode == 1) {
    // `line N: message`, N the program's line the interpreter stopped at.
    int line = 0;
    std::string_view message = errors;
    if (errors.rfind("line ", 0) == 0) {
      std::size_t colon = errors.find(": ");
      std::from_chars(errors.data() + 5, errors.data() + std::min(colon, errors.size()), line);
      message = colon == std::string_view::npos ? errors : errors.substr(colon + 2);
    }
    ProgramExecution execution =
        failed(request.text, line, fmt::format("LinuxCNC's interpreter: {}", message));
    execution.failure->lineText = line > 0 ? lineOf(request.text, line) : "";
    return execution;
  }
  if (run.exitCode != 0) {
    return failed(request.text, 0,
                  fmt::format("LinuxCNC's gcode module stopped (status {}): {}", run.exitCode,
                              errors.empty() ? "no message" : errors));
  }
  return linuxcncPath(request, run.canon, std::pow(10.0, -linuxcncCoordinateDecimals(inches)),
                      "LinuxCNC's interpreter");
}

// What rs274 says on standard error, after its `executing`: the message,
// then the block it stopped at.
std::string rs274Error(std::string_view errors) {
  std::vector<std::string_view> lines;
  while (!errors.empty()) {
    std::size_t newline = errors.find('\n');
    std::string_view line = errors.substr(0, newline);
    errors = newline == std::string_view::npos ? std::string_view() : errors.substr(newline + 1);
    if (!line.empty() && line != "executing") {
      lines.push_back(line);
    }
  }
  if (lines.empty()) {
    return "it stopped with an error and no message";
  }
  return lines.size() == 1 ? std::string(lines[0])
                           : fmt::format("{}, at the block `{}`", lines[0], lines[1]);
}

// A LinuxCNC program through LinuxCNC's standalone interpreter, rs274,
// which prints 4 decimals.
ProgramExecution runRs274Execution(const ExecutionRequest& request, const std::string& toolTable) {
  std::optional<std::string> rs274 = findRs274();
  if (!rs274) {
    return failed(request.text, 0,
                  "verifying a LinuxCNC program needs LinuxCNC's interpreter rs274 on the PATH "
                  "(Debian package linuxcnc-uspace)");
  }
  Rs274Run run = runRs274(*rs274, request.text, toolTable, kLinuxcncSeconds);
  if (run.exitCode != 0) {
    std::string message = run.exitCode < 0
                              ? fmt::format("rs274 did not finish within {} s", kLinuxcncSeconds)
                              : rs274Error(run.errors);
    return failed(request.text, 0, "rs274: " + message);
  }
  return linuxcncPath(request, run.canon, 1e-4, "rs274");
}

// Whether a block compensates with a diameter from the tool table (`G41
// D5`, `G42 D5`; not G41.1/G42.1, which give it). The module, run with the
// tool table as here, comes out with such moves uncompensated, so these
// programs run in rs274.
bool compensatesFromToolTable(std::string_view text) {
  while (!text.empty()) {
    std::size_t newline = text.find('\n');
    std::string block;
    bool comment = false;
    for (char c : text.substr(0, newline)) {
      comment = c == '(' || (comment && c != ')');
      if (c == ';') {
        break;
      }
      if (!comment && c != ' ' && c != '\t') {
        block += static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
      }
    }
    text = newline == std::string_view::npos ? std::string_view() : text.substr(newline + 1);
    for (std::size_t at = block.find("G4"); at != std::string::npos;
         at = block.find("G4", at + 2)) {
      bool compensation = at + 2 < block.size() && (block[at + 2] == '1' || block[at + 2] == '2');
      bool whole =
          at + 3 >= block.size() ||
          (block[at + 3] != '.' && !std::isdigit(static_cast<unsigned char>(block[at + 3])));
      if (compensation && whole && block.find('D') != std::string::npos) {
        return true;
      }
    }
  }
  return false;
}

// A LinuxCNC program through LinuxCNC's own interpreter: its Python module
// `gcode` where the Python that runs it can import it, else the program
// rs274, whose 4 decimals the output then notes. The program's parameters
// are the values it sets.
ProgramExecution runLinuxcnc(const ExecutionRequest& request) {
  // The tool table holds the diameters that `G41 D<n>` reads.
  bool inches = request.text.find("G20") != std::string::npos;
  std::string toolTable = rs274ToolTable(request.text, request.toolRadii, inches);
  if (compensatesFromToolTable(request.text)) {
    ProgramExecution execution = runRs274Execution(request, toolTable);
    execution.notes.push_back("the program compensates with the tool table's diameters (G41/G42 "
                              "D), which LinuxCNC's Python module gcode is not given: the path is "
                              "read from rs274, which prints 4 decimals");
    return execution;
  }
  GcodeModuleRun module = runGcodeModule(request.text, toolTable, inches, kLinuxcncSeconds,
                                         static_cast<std::size_t>(maximumMeasuredPoints));
  if (!module.missing) {
    return runGcodeModuleExecution(request, module, inches);
  }
  std::string_view why = module.errors;
  why = why.substr(0, why.find('\n'));
  ProgramExecution execution = runRs274Execution(request, toolTable);
  execution.notes.push_back(
      fmt::format("{} cannot import LinuxCNC's Python module gcode ({}): the path is read from "
                  "rs274, which prints 4 decimals",
                  gcodeModulePython(), why));
  return execution;
}

// A Heidenhain program in the virtual TNC, the -D values edited into the
// `FN 0` blocks that set its Q parameters.
ProgramExecution runHeidenhain(const ExecutionRequest& request) {
  heidenhain::TncRunOptions options;
  if (!request.profile.empty()) {
    const TncProfile* profile = findTncProfile(request.profile);
    if (profile == nullptr) {
      return failed(request.text, 0, fmt::format("unknown TNC profile '{}'", request.profile));
    }
    options.profile = *profile;
  }
  options.toolRadii = request.radiiOfTools;
  std::string text = request.text;
  for (const ParameterValue& parameter : request.parameters) {
    std::optional<std::string> edited =
        heidenhain::withEditedParameter(text, parameter.variable, parameter.value);
    if (!edited) {
      return failed(request.text, 0,
                    fmt::format("the program sets no {} for parameter {}",
                                tncParameterName(parameter.variable), parameter.name));
    }
    text = std::move(*edited);
  }
  heidenhain::TncRun run = heidenhain::runTncProgram(text, options);
  ProgramExecution execution;
  execution.text = std::move(text);
  execution.increment =
      std::pow(10.0, -(options.profile.coordinateDecimals + (run.inches ? 1 : 0)));
  if (run.error) {
    execution.failure = ControllerFailure{run.error->line, run.error->message, run.error->lineText};
    return execution;
  }
  double sagitta = run.inches ? kArcSagitta / 25.4 : kArcSagitta;
  try {
    checkMeasurablePath(run.path, sagitta);
  } catch (const PathTooLargeToMeasure& error) {
    execution.failure = ControllerFailure{0, error.what(), ""};
    return execution;
  }
  execution.path = executedPathOfToolPath(run.path, sagitta);
  if (run.loopOperations.feedMoves > 0) {
    execution.operations = run.loopOperations;
  }
  execution.variables = run.parametersNamed;
  return execution;
}

constexpr TargetExecutor executorTable[] = {
    {"m80", runM80},
    {"fanuc", runFanuc},
    {"gcode", runGcode},
    {"jit", runJit},
    {"sinumerik", runSinumerik},
    {"linuxcnc", runLinuxcnc},
    {"heidenhain", runHeidenhain},
};

} // namespace

std::span<const TargetExecutor> targetExecutors() {
  return executorTable;
}

const TargetExecutor* findTargetExecutor(std::string_view name) {
  for (const TargetExecutor& executor : executorTable) {
    if (executor.target == name) {
      return &executor;
    }
  }
  return nullptr;
}

} // namespace cncc::backends
