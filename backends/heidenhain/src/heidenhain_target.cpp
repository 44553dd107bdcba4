// The `heidenhain` target: the part as a Heidenhain TNC conversational
// program whose labels and FN jumps evaluate the curve on the control, its
// parameters Q1.. set at the top.
#include "registered_targets.h"

#include "cncc/backends/heidenhain_controller.h"
#include "cncc/backends/heidenhain_program.h"
#include "cncc/ir/interpreter.h"

#include <fmt/format.h>

#include <cmath>

namespace cncc::backends {

namespace {

// The host run that finds the blank takes a second or so at most (its
// events are not kept): a part whose loops (over parameters, run by the TNC)
// take more steps at the values it is compiled with gets no BLK FORM rather
// than a compile of minutes.
constexpr std::size_t maximumBlankSteps = 20'000'000;

// The blank of BLK FORM: the part run on the host with its defaults; a part
// that cannot run there gets no BLK FORM (its compile reports why elsewhere).
std::optional<HeidenhainBlank> blankOf(const ir::Function& function) {
  HeidenhainBlankFinder finder;
  ir::InterpreterOptions options;
  options.maximumSteps = maximumBlankSteps;
  try {
    ir::interpret(function, finder, options);
  } catch (const ir::InterpreterError&) {
    return std::nullopt;
  }
  return finder.blank();
}

ir::LoweringOptions heidenhainLowering(const TargetSettings& settings) {
  ir::LoweringOptions lowering = heidenhainLoweringOptions(*settings.tncProfile, settings.inches);
  lowering.arcsOnEveryCut = settings.arcs;
  return lowering;
}

PrintedProgram printHeidenhainProgram(const PrintInput& input) {
  HeidenhainProgramOptions options;
  options.sourceName = input.settings.sourceName;
  options.partName = input.settings.partName;
  options.inches = input.settings.inches;
  options.profile = *input.settings.tncProfile;
  options.blank = blankOf(input.function);
  HeidenhainProgram program = writeHeidenhainProgram(input.function, options);
  PrintedProgram printed;
  printed.problems = doesNotFit("the TNC", program.errors);
  printed.text = std::move(program.text);
  printed.lineOrigins = std::move(program.lineOrigins);
  return printed;
}

// The Q parameter each of `count` part parameters is set in (verify edits them).
std::vector<int> parameterQ(std::size_t count, const TargetSettings& settings) {
  std::vector<std::string> errors;
  return heidenhainParameterVariables(count, *settings.tncProfile, errors);
}

// The virtual TNC's run, for `sim`.
OwnProgramRun runTncForSim(const std::string& text, const OwnReaderSettings& settings) {
  heidenhain::TncRunOptions options;
  if (settings.tncProfile != nullptr) {
    options.profile = *settings.tncProfile;
  }
  options.toolRadii = settings.toolRadii;
  heidenhain::TncRun run = heidenhain::runTncProgram(text, options);
  OwnProgramRun result;
  if (run.error) {
    result.failure = ControllerFailure{run.error->line, run.error->message, run.error->lineText};
  } else {
    result.path = std::move(run.path);
  }
  return result;
}

// A Heidenhain program in the virtual TNC, the -D values edited into the
// `FN 0` blocks that set its Q parameters.
ProgramExecution runHeidenhain(const ExecutionRequest& request) {
  heidenhain::TncRunOptions options;
  if (!request.profile.empty()) {
    const TncProfile* profile = findTncProfile(request.profile);
    if (profile == nullptr) {
      return failedExecution(request.text, 0,
                             fmt::format("unknown TNC profile '{}'", request.profile));
    }
    options.profile = *profile;
  }
  options.toolRadii = request.radiiOfTools;
  std::string text = request.text;
  for (const ParameterValue& parameter : request.parameters) {
    std::optional<std::string> edited =
        heidenhain::withEditedParameter(text, parameter.variable, parameter.value);
    if (!edited) {
      return failedExecution(request.text, 0,
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
  double sagitta = run.inches ? controllerArcSagitta / 25.4 : controllerArcSagitta;
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

} // namespace

const TargetInfo heidenhainTarget = {
    .name = "heidenhain",
    .description = "Heidenhain TNC conversational program with Q parameters (parameters stay "
                   "editable)",
    .lowering = heidenhainLowering,
    .print = printHeidenhainProgram,
    .tncProfiles = true,
    .cutterCompensation = true,
    .execute = runHeidenhain,
    .parameterVariables = parameterQ,
    .runOwnProgram = runTncForSim,
};

} // namespace cncc::backends
