#include "commands.h"

#include "atomic_output_file.h"
#include "dependency_file.h"
#include "diagnostic_output.h"
#include "input_checking.h"
#include "source_map.h"
#include "stats_measurement.h"
#include "targets.h"

#include "cncc/frontend/ast_printer.h"
#include "cncc/frontend/lexer.h"
#include "cncc/ir/printer.h"
#include "cncc/ir/verifier.h"
#include "cncc/lowering/lowering.h"

#include <fmt/format.h>

#include <fstream>
#include <sstream>

namespace cncc::driver {

namespace {

using frontend::DiagnosticEngine;
using frontend::SourceManager;

DiagnosticOutput diagnosticOutputFor(const DriverOptions& options) {
  return DiagnosticOutput(options.diagnosticsFormat, options.colour);
}

void reportWriteFailure(const DiagnosticOutput& output, const std::string& path,
                        std::error_code error) {
  output.driverError(fmt::format("cannot write '{}': {}", path, error.message()));
}

// `--emit=ir`: the selected part as lowered for no target; with -t, as
// that target's backend lowers, optimises and prepares it for printing
// (--print-after shows each pass on standard error; -O0 runs no optimiser).
std::string emittedIr(const DriverOptions& options, SourceManager& sources,
                      DiagnosticEngine& diagnostics) {
  std::optional<frontend::CheckedProgram> program =
      checkInput(options.inputs.front(), options, true, sources, diagnostics);
  if (!program || diagnostics.hasErrors() || program->selectedPart == nullptr) {
    return "";
  }
  const frontend::PartItem& part = *program->selectedPart;
  const backends::TargetInfo* target = options.target.empty() ? nullptr : &optionsTarget(options);
  ir::LoweringOptions lowering =
      target != nullptr ? targetLoweringOptions(*target, part, options) : ir::LoweringOptions{};
  lowering.expandCurveLaps = false; // shown as the first of the target's passes
  lowering.keepLoops = true;        // the same IR for every target
  std::optional<ir::Function> function = ir::lowerPart(*program, part, diagnostics, lowering);
  if (!function) {
    return "";
  }
  std::vector<std::string> problems = ir::verifyFunction(*function);
  if (!problems.empty()) {
    throw InternalError("the lowered IR does not verify: " + problems.front());
  }
  if (target != nullptr) {
    if (!ir::legaliseCurves(*function, diagnostics, printAfterCallback(options))) {
      return "";
    }
    optimise(*function, options);
    runPassesBeforePrinting(*function, lowering, options);
  }
  return ir::printFunction(*function);
}

// The text of `--emit`: the tokens, the tree after semantic checking, or the
// selected part lowered to the IR.
std::string emittedText(const DriverOptions& options, SourceManager& sources,
                        DiagnosticEngine& diagnostics) {
  const std::string& path = options.inputs.front();
  if (options.emit == EmitKind::Tokens) {
    std::optional<frontend::FileId> file = loadInput(path, sources, diagnostics);
    return file ? frontend::dumpTokens(frontend::lex(sources, *file, diagnostics), sources) : "";
  }
  if (options.emit == EmitKind::Ir) {
    return emittedIr(options, sources, diagnostics);
  }
  std::optional<frontend::CheckedProgram> program =
      checkInput(path, options, false, sources, diagnostics);
  return program ? frontend::dumpAst(program->modules.front(), sources) : "";
}

// The source map of the program just written to options.output.
bool writeSourceMap(DiagnosticOutput& output, const DriverOptions& options,
                    const frontend::CheckedProgram& program, const SourceManager& sources,
                    ProgramOrigins origins) {
  std::ifstream written(options.output, std::ios::binary);
  std::ostringstream text;
  text << written.rdbuf();
  std::string programText = text.str();
  SourceMapInput input{options.output,
                       programText,
                       options.target,
                       &program,
                       &sources,
                       std::move(origins.lines),
                       std::move(origins.variables),
                       program.selectedPart != nullptr &&
                           ir::partUnits(*program.selectedPart) == ir::PartUnits::Inches,
                       std::move(origins.deviations)};
  std::error_code error;
  if (!writeFileAtomically(options.sourceMap, sourceMapJson(input), error)) {
    reportWriteFailure(output, options.sourceMap, error);
    return false;
  }
  return true;
}

// The Make/Ninja depfile of the compile: the sources and the machine file.
bool writeDependencyFile(DiagnosticOutput& output, const DriverOptions& options,
                         const SourceManager& sources) {
  std::vector<std::string> inputs = sources.paths();
  if (!options.machineFile.empty()) {
    inputs.push_back(options.machineFile);
  }
  std::error_code error;
  if (!writeFileAtomically(options.dependencyFile,
                           dependencyFileText(options.dependencyTarget, inputs), error)) {
    reportWriteFailure(output, options.dependencyFile, error);
    return false;
  }
  return true;
}

} // namespace

std::string fileName(const std::string& path) {
  std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

int runCompile(const DriverOptions& options) {
  DiagnosticOutput output = diagnosticOutputFor(options);
  SourceManager sources;
  DiagnosticEngine diagnostics(options.errorLimit);
  std::optional<frontend::CheckedProgram> program =
      checkInput(options.inputs.front(), options, true, sources, diagnostics);
  output.print(diagnostics, sources);
  if (!program || diagnostics.hasErrors()) {
    return 1;
  }
  std::error_code error;
  std::optional<AtomicOutputFile> file = AtomicOutputFile::create(options.output, error);
  if (!file) {
    reportWriteFailure(output, options.output, error);
    return 1;
  }
  DiagnosticEngine backendDiagnostics(options.errorLimit);
  backends::LineOrigins lineOrigins;
  std::map<int, backends::VariableMeaning> variables;
  bool mapped = !options.sourceMap.empty();
  compileForTarget({*program, sources, options, backendDiagnostics, *file,
                    mapped ? &lineOrigins : nullptr, mapped ? &variables : nullptr});
  output.print(backendDiagnostics, sources);
  if (backendDiagnostics.hasErrors()) {
    return 1; // the file discards what the backend wrote
  }
  if (!file->commit(error)) {
    reportWriteFailure(output, options.output, error);
    return 1;
  }
  if (!options.dependencyFile.empty() && !writeDependencyFile(output, options, sources)) {
    return 1;
  }
  // --stats before the map, which records the deviations it measured.
  int status = 0;
  std::vector<MeasuredCutDeviation> deviations;
  if (options.stats) {
    BackendRequest measured{*program, sources, options, backendDiagnostics, *file};
    std::vector<MeasuredCutDeviation>* collected = mapped ? &deviations : nullptr;
    status = canMeasure(options.target) ? printStatistics(measured, collected)
                                        : printVerifiedStatistics(measured, collected);
  }
  if (mapped &&
      !writeSourceMap(output, options, *program, sources,
                      {std::move(lineOrigins), std::move(variables), std::move(deviations)})) {
    return 1;
  }
  return status;
}

int runEmit(const DriverOptions& options) {
  DiagnosticOutput output = diagnosticOutputFor(options);
  SourceManager sources;
  DiagnosticEngine diagnostics(options.errorLimit);
  std::string text = emittedText(options, sources, diagnostics);
  output.print(diagnostics, sources);
  // A broken file's dump still helps on the terminal; a file is only written
  // from a clean one.
  if (diagnostics.hasErrors() && options.output != "-") {
    return 1;
  }
  std::error_code error;
  if (!writeFileAtomically(options.output, text, error)) {
    reportWriteFailure(output, options.output, error);
    return 1;
  }
  return diagnostics.hasErrors() ? 1 : 0;
}

// With --machine the file was read (and its errors reported) with the
// command line; `check --machine FILE.toml` alone has nothing more to do.
int runCheck(const DriverOptions& options) {
  DiagnosticOutput output = diagnosticOutputFor(options);
  bool failed = false;
  for (const std::string& path : options.inputs) {
    SourceManager sources;
    DiagnosticEngine diagnostics(options.errorLimit);
    checkInput(path, options, false, sources, diagnostics);
    output.print(diagnostics, sources);
    failed |= diagnostics.hasErrors();
  }
  return failed ? 1 : 0;
}

int runListDiagnostics() {
  for (frontend::DiagnosticKind kind : frontend::allDiagnosticKinds()) {
    fmt::print("{}\n", frontend::diagnosticName(kind));
  }
  return 0;
}

int runCommand(const DriverOptions& options) {
  switch (options.command) {
  case Command::Compile:
    return runCompile(options);
  case Command::Emit:
    return runEmit(options);
  case Command::Check:
    return runCheck(options);
  case Command::ListDiagnostics:
    return runListDiagnostics();
  case Command::Format:
    return runFormat(options);
  case Command::LanguageServer:
    return runLanguageServer();
  case Command::Optimize:
    return runOptimize(options);
  case Command::Plot:
    return runPlot(options);
  case Command::Simulate:
    return runSimulate(options);
  case Command::Verify:
    return runVerify(options);
  case Command::Where:
    return runWhere(options);
  }
  return 2;
}

} // namespace cncc::driver
