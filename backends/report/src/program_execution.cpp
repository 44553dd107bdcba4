#include "cncc/backends/program_execution.h"

#include "cncc/backends/controller_profile.h"
#include "cncc/backends/gcode_writer.h"
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

} // namespace

ProgramExecution failedExecution(std::string text, int line, std::string message) {
  ProgramExecution execution;
  execution.text = std::move(text);
  execution.failure = ControllerFailure{line, std::move(message), ""};
  return execution;
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
    return failedExecution(request.text, 0, problem);
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
    return failedExecution(request.text, 0, fmt::format("unknown controller profile '{}'", name));
  }
  return runOnController(request, *profile);
}

std::map<int, double> compensationRadii(const ir::ToolPath& path, bool byTool) {
  std::map<int, double> radii;
  int tool = 0;
  for (const ir::MachineEvent& event : path.events) {
    if (event.kind == ir::MachineEvent::Kind::Tool) {
      tool = static_cast<int>(std::lround(event.number));
    } else if (event.kind == ir::MachineEvent::Kind::Compensation && event.number != 0) {
      radii[byTool ? tool : static_cast<int>(event.offsetRegister)] = std::fabs(event.number);
    }
  }
  return radii;
}

std::string programLine(std::string_view text, int number) {
  for (int line = 1; line < number && !text.empty(); ++line) {
    std::size_t newline = text.find('\n');
    text = newline == std::string_view::npos ? std::string_view() : text.substr(newline + 1);
  }
  return std::string(text.substr(0, text.find('\n')));
}

} // namespace cncc::backends
