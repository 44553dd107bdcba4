// cncc verify: compiles the part for a target as `cncc FILE -t TARGET` does,
// runs the program as the controller would (backends/report's executor
// table) and measures it against the true curves of the part with the -D
// values. A target whose programs keep the parameters as variables (m80,
// fanuc) is compiled once with the defaults and given the -D values as the
// operator gives them; the other targets compute on the host, so the -D
// values are compiled in. Also the --stats of those targets.
#include "atomic_output_file.h"
#include "commands.h"
#include "diagnostic_output.h"
#include "input_checking.h"
#include "machine_options.h"

#include "cncc/backends/controller_profile.h"
#include "cncc/backends/macro_program.h"
#include "cncc/backends/verification.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/tool_centre_path.h"
#include "cncc/ir/verifier.h"
#include "cncc/lowering/lowering.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>

namespace cncc::driver {

namespace {

using frontend::CheckedProgram;
using frontend::DiagnosticEngine;
using frontend::SourceManager;

// A checked input; kept whole because analytic cut curves evaluate the
// program's expressions.
struct CheckedInput {
  SourceManager sources;
  DiagnosticEngine diagnostics;
  std::optional<CheckedProgram> program;

  explicit CheckedInput(std::size_t errorLimit) : diagnostics(errorLimit) {}
};

std::unique_ptr<CheckedInput> checkedInput(const DriverOptions& options,
                                           const DiagnosticOutput& output) {
  auto input = std::make_unique<CheckedInput>(options.errorLimit);
  input->program =
      checkInput(options.inputs.front(), options, true, input->sources, input->diagnostics);
  output.print(input->diagnostics, input->sources);
  if (!input->program || input->diagnostics.hasErrors() ||
      input->program->selectedPart == nullptr) {
    return nullptr;
  }
  return input;
}

// The program text the target's backend writes, exactly as a compile would.
std::optional<std::string> compiledText(const CheckedProgram& program, const SourceManager& sources,
                                        const DriverOptions& options,
                                        const DiagnosticOutput& output) {
  DiagnosticEngine diagnostics(options.errorLimit);
  AtomicOutputFile memory = AtomicOutputFile::inMemory();
  DriverOptions compile = options; // what a compile with --stats adds is printed once, before
  compile.stats = false;
  compileForTarget({program, sources, compile, diagnostics, memory});
  output.print(diagnostics, sources);
  if (diagnostics.hasErrors()) {
    return std::nullopt;
  }
  return memory.contents();
}

struct HostReference {
  std::vector<ir::CutGeometry> cuts;
  backends::ExecutedPath path;
  // The tool radius of each register the program's cutter radius
  // compensation reads, as it was compiled with.
  std::map<int, double> toolRadii;
  // And of each tool that compensates, by its number (a Sinumerik's cutting
  // edge, a TNC's tool table).
  std::map<int, double> radiiOfTools;
};

// The part run on the host with the checked parameter values.
std::optional<HostReference> hostReference(const CheckedProgram& program,
                                           const SourceManager& sources,
                                           const DriverOptions& options,
                                           const DiagnosticOutput& output) {
  const frontend::PartItem& part = *program.selectedPart;
  DiagnosticEngine diagnostics(options.errorLimit);
  // The reference is the chord path whatever the target interpolates: the
  // target's own compile has already warned about spline methods it lacks.
  ir::LoweringOptions reference;
  reference.reportSplineAsChords = false;
  reference.fittedArcs = false;
  // Nor does it refuse the machine settings the target's compile accepted.
  reference.maximumExtendedWorkOffset = std::numeric_limits<int>::max();
  reference.throughSpindleCoolant = true;
  reference.cutterCompensation = true;
  std::optional<ir::LoweredPart> lowered =
      ir::lowerPartWithCuts(program, part, diagnostics, reference);
  output.print(diagnostics, sources);
  if (!lowered || diagnostics.hasErrors()) {
    return std::nullopt;
  }
  std::vector<std::string> problems = ir::verifyFunction(lowered->function);
  if (!problems.empty()) {
    throw InternalError("the lowered IR does not verify: " + problems.front());
  }
  try {
    ir::ToolPath programmed = ir::interpret(lowered->function);
    // Where the tool's centre goes, as the controller compensates the path.
    ir::ToolPath path = ir::toolCentrePath(programmed);
    // The reference only tells the cuts apart (within twice their
    // tolerance): its arcs need not be finer than a tenth of the smallest.
    double sagitta = std::numeric_limits<double>::infinity();
    for (const ir::CutGeometry& cut : lowered->function.cuts) {
      sagitta = std::min(sagitta, cut.tolerance / 10); // NaN (samples=) is left out
    }
    sagitta = std::isfinite(sagitta) ? std::max(sagitta, backends::executedArcSagitta)
                                     : backends::executedArcSagitta;
    // The program's arcs are the part's own (every target prints them as
    // arcs), measured as chords of controllerArcSagitta: refused here,
    // before the program runs, when those alone pass the limit.
    double executedSagitta = ir::partUnits(part) == ir::PartUnits::Inches
                                 ? backends::controllerArcSagitta / 25.4
                                 : backends::controllerArcSagitta;
    for (double chordError : {sagitta, executedSagitta}) {
      if (!(ir::flattenedEventCount(path, chordError) <= backends::maximumMeasuredPoints)) {
        output.driverError(
            fmt::format("the part cannot be verified: its path has more than {:.0f} points to "
                        "measure (arcs as chords within {:g}); verify a smaller part, or fewer "
                        "turns",
                        backends::maximumMeasuredPoints, chordError));
        return std::nullopt;
      }
    }
    return HostReference{std::move(lowered->function.cuts),
                         backends::executedPathOfToolPath(path, sagitta),
                         backends::compensationRadii(programmed, false),
                         backends::compensationRadii(programmed, true)};
  } catch (const ir::InterpreterError& error) {
    output.driverError(fmt::format("the part cannot be run on the host: {}", error.what()));
    return std::nullopt;
  }
}

std::vector<std::string> cutNames(const std::vector<ir::CutGeometry>& cuts,
                                  const SourceManager& sources) {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < cuts.size(); ++i) {
    const frontend::SourceSpan& span = cuts[i].span;
    std::string where;
    if (span.valid()) {
      const frontend::SourceFile& file = sources.file(span.file);
      where = fmt::format(" ({}:{})", fileName(file.path()), file.lineColumn(span.begin).line);
    }
    names.push_back(fmt::format("cut {}{}", i + 1, where));
  }
  return names;
}

backends::ParameterPassing parameterPassing(const DriverOptions& options) {
  if (options.parametersInCommon) {
    return backends::ParameterPassing::CommonVariables;
  }
  return options.macroCall ? backends::ParameterPassing::MacroArguments
                           : backends::ParameterPassing::EditedDefaults;
}

// The -D values, each with the variable the program reads its parameter from.
std::vector<backends::ParameterValue> definedValues(const frontend::PartItem& part,
                                                    const DriverOptions& options,
                                                    const std::vector<int>& variables) {
  std::vector<backends::ParameterValue> values;
  for (std::size_t i = 0; i < part.parameters.size() && i < variables.size(); ++i) {
    auto define = options.defines.find(part.parameters[i].name);
    if (define != options.defines.end()) {
      values.push_back({define->first, variables[i], define->second});
    }
  }
  return values;
}

// The -D values and the variables the program reads them from.
std::optional<std::vector<backends::ParameterValue>>
parameterValues(const frontend::PartItem& part, const DriverOptions& options,
                std::string_view defaultProfile, const DiagnosticOutput& output) {
  const backends::ControllerProfile* profile = &controllerProfile(options, defaultProfile);
  std::vector<std::string> errors;
  std::vector<int> variables = backends::macroParameterVariables(
      part.parameters.size(), *profile, options.parametersInCommon, errors);
  if (!errors.empty()) {
    output.driverError(errors.front());
    return std::nullopt;
  }
  return definedValues(part, options, variables);
}

// The -D values in the variables the target's own kind of program sets at its top.
std::vector<backends::ParameterValue> ownParameterValues(const frontend::PartItem& part,
                                                         const DriverOptions& options,
                                                         const backends::TargetInfo& target) {
  std::vector<int> variables =
      target.parameterVariables(part.parameters.size(), targetSettings(target, options, part));
  return definedValues(part, options, variables);
}

backends::StatisticsOptions statisticsOptions(const CheckedProgram& program,
                                              const SourceManager& sources,
                                              const HostReference& reference) {
  backends::StatisticsOptions options;
  options.unit = ir::partUnits(*program.selectedPart) == ir::PartUnits::Inches ? "in" : "mm";
  options.cutNames = cutNames(reference.cuts, sources);
  return options;
}

std::string parameterLine(const DriverOptions& options) {
  std::string line;
  for (const auto& [name, value] : options.defines) {
    line += fmt::format("{}{}={:g}", line.empty() ? "" : " ", name, value);
  }
  return line.empty() ? "the defaults" : line;
}

void reportFailure(const backends::VerificationReport& report, const DriverOptions& options) {
  if (report.failure && report.failure->line == 0) { // no block of the program
    fmt::print(stderr, "cncc: error: the {} program cannot be verified: {}\n", options.target,
               report.failure->message);
  } else if (report.failure) {
    fmt::print(stderr, "cncc: error: the {} program fails on the controller at line {}: {}\n",
               options.target, report.failure->line, report.failure->message);
  } else if (!report.passed()) {
    fmt::print(stderr, "cncc: error: the {} program does not keep to the part's tolerances\n",
               options.target);
  }
}

} // namespace

bool canVerify(std::string_view name) {
  const backends::TargetInfo* target = backends::findTargetInfo(name);
  return target != nullptr && target->execute != nullptr;
}

int runVerify(const DriverOptions& options) {
  DiagnosticOutput output(options.diagnosticsFormat, options.colour);
  std::unique_ptr<CheckedInput> truth = checkedInput(options, output);
  if (!truth) {
    return 1;
  }
  const backends::TargetInfo* target = &optionsTarget(options);
  bool symbolic = !target->controllerProfile.empty() || target->parameterVariables != nullptr;
  backends::ExecutionRequest execution;
  std::optional<std::string> text;
  if (symbolic) {
    // Compiled once with the defaults, as the program is kept; the -D
    // values are set on the controller.
    DriverOptions defaults = options;
    defaults.defines.clear();
    std::unique_ptr<CheckedInput> compiled = checkedInput(defaults, output);
    if (!compiled ||
        !(text = compiledText(*compiled->program, compiled->sources, defaults, output))) {
      return 1;
    }
    std::optional<std::vector<backends::ParameterValue>> values =
        target->parameterVariables != nullptr
            ? ownParameterValues(*truth->program->selectedPart, options, *target)
            : parameterValues(*truth->program->selectedPart, options, target->controllerProfile,
                              output);
    if (!values) {
      return 1;
    }
    execution.parameters = std::move(*values);
    execution.passing = parameterPassing(options);
  } else if (!(text = compiledText(*truth->program, truth->sources, options, output))) {
    return 1;
  }
  std::optional<HostReference> reference =
      hostReference(*truth->program, truth->sources, options, output);
  if (!reference) {
    return 1;
  }
  execution.text = std::move(*text);
  execution.profile = options.profile;
  execution.machineProfile = machineProfile(options);
  execution.lowerCaseComments =
      machineSetup(options).commentCase == backends::CommentCase::AsWritten;
  execution.callable = options.macroCall;
  execution.toolRadii = reference->toolRadii;
  execution.radiiOfTools = reference->radiiOfTools;
  backends::StatisticsOptions statistics =
      statisticsOptions(*truth->program, truth->sources, *reference);
  backends::VerificationReport report =
      backends::verifyProgram({options.target, optionsTarget(options).execute, std::move(execution),
                               reference->path, reference->cuts},
                              statistics);
  fmt::print("verification of part {} ({}) with {}:\n{}", truth->program->selectedPart->name,
             fileName(options.inputs.front()), parameterLine(options),
             backends::formatVerification(report, statistics));
  reportFailure(report, options);
  return report.passed() ? 0 : 1;
}

int printVerifiedStatistics(const BackendRequest& request,
                            std::vector<MeasuredCutDeviation>* deviations) {
  const DriverOptions& options = request.options;
  // The compile before --stats printed the warnings.
  DiagnosticOutput output =
      DiagnosticOutput(options.diagnosticsFormat, options.colour).errorsOnly();
  std::optional<std::string> text = compiledText(request.program, request.sources, options, output);
  std::optional<HostReference> reference =
      text ? hostReference(request.program, request.sources, options, output) : std::nullopt;
  if (!reference) {
    return 1;
  }
  backends::ExecutionRequest execution;
  execution.text = std::move(*text);
  execution.profile = options.profile;
  execution.machineProfile = machineProfile(options);
  execution.lowerCaseComments =
      machineSetup(options).commentCase == backends::CommentCase::AsWritten;
  execution.callable = options.macroCall;
  execution.toolRadii = reference->toolRadii;
  execution.radiiOfTools = reference->radiiOfTools;
  backends::StatisticsOptions statistics =
      statisticsOptions(request.program, request.sources, *reference);
  backends::VerificationReport report =
      backends::verifyProgram({options.target, optionsTarget(options).execute, std::move(execution),
                               reference->path, reference->cuts},
                              statistics);
  collectCutDeviations(report.statistics, reference->cuts, deviations);
  fmt::print(stderr, "statistics of part {} for target {}:\n{}", request.program.selectedPart->name,
             options.target, backends::formatVerification(report, statistics));
  return report.failure ? 1 : 0;
}

} // namespace cncc::driver
