#include "driver_options.h"

#include "cncc/backends/tnc_profile.h"

#include "command_line.h"
#include "commands.h"
#include "machine_options.h"
#include "stats_measurement.h"
#include "targets.h"

#include "cncc/ir/passes.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fmt/format.h>
#include <stdexcept>
#include <system_error>
#include <unistd.h>

namespace cncc::driver {

namespace {

// -MD, -MF, -MT: where the depfile goes and what it names.
void setDependencyFile(const RawOptions& raw, DriverOptions& options) {
  bool wanted = raw.writeDependencies || !raw.dependencyFile.empty();
  if (!wanted) {
    if (!raw.dependencyTarget.empty()) {
      throw UsageError("-MT names the target of a depfile; add -MD or -MF FILE");
    }
    return;
  }
  if (options.command != Command::Compile) {
    throw UsageError("-MD and -MF write the depfile of a compile; they do not apply to this "
                     "command");
  }
  bool toStandardOutput = options.output == "-";
  if (toStandardOutput && (raw.dependencyFile.empty() || raw.dependencyTarget.empty())) {
    throw UsageError("the program goes to standard output: a depfile needs -MF FILE and "
                     "-MT TARGET");
  }
  options.dependencyFile = raw.dependencyFile.empty() ? options.output + ".d" : raw.dependencyFile;
  options.dependencyTarget = raw.dependencyTarget.empty() ? options.output : raw.dependencyTarget;
}

bool isIdentifier(std::string_view text) {
  auto isStart = [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
  };
  if (text.empty() || !isStart(text[0])) {
    return false;
  }
  for (char c : text) {
    if (!isStart(c) && !(c >= '0' && c <= '9')) {
      return false;
    }
  }
  return true;
}

std::map<std::string, double, std::less<>> parseDefines(const std::vector<std::string>& defines) {
  std::map<std::string, double, std::less<>> values;
  for (const std::string& define : defines) {
    std::size_t equals = define.find('=');
    std::string name = define.substr(0, equals);
    if (equals == std::string::npos || !isIdentifier(name)) {
      throw UsageError(
          fmt::format("invalid -D '{}': expected NAME=VALUE, as in -D depth=3.5", define));
    }
    std::string_view text = std::string_view(define).substr(equals + 1);
    double value = 0;
    auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (text.empty() || error != std::errc() || end != text.data() + text.size() ||
        !std::isfinite(value)) {
      throw UsageError(
          fmt::format("invalid -D '{}': the value '{}' is not a number", define, text));
    }
    values[name] = value;
  }
  return values;
}

double parseRapidRate(const std::string& text) {
  double rate = 0;
  auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), rate);
  if (text.empty() || error != std::errc() || end != text.data() + text.size() ||
      !std::isfinite(rate) || !(rate > 0)) {
    throw UsageError(
        fmt::format("invalid --rapid-rate '{}': expected a positive number (mm/min)", text));
  }
  return rate;
}

std::size_t parseErrorLimit(const std::string& text) {
  std::size_t limit = 0;
  auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), limit);
  if (text.empty() || error != std::errc() || end != text.data() + text.size()) {
    throw UsageError(fmt::format("invalid --error-limit '{}': expected a whole number "
                                 "(0 for no limit)",
                                 text));
  }
  return limit;
}

std::string standardLibraryDirectory() {
  const char* fromEnvironment = std::getenv("CNCC_STDLIB");
  if (fromEnvironment != nullptr && *fromEnvironment != '\0') {
    return fromEnvironment;
  }
  return CNCC_STDLIB_DIR;
}

// The -I directories, each checked readable, then the standard library.
std::vector<std::string> importPaths(const std::vector<std::string>& includeDirectories) {
  std::vector<std::string> paths;
  for (const std::string& directory : includeDirectories) {
    std::error_code error;
    std::filesystem::file_status status = std::filesystem::status(directory, error);
    if (!error && !std::filesystem::is_directory(status)) {
      error = std::make_error_code(std::filesystem::exists(status)
                                       ? std::errc::not_a_directory
                                       : std::errc::no_such_file_or_directory);
    } else if (!error && ::access(directory.c_str(), R_OK | X_OK) != 0) {
      error = std::error_code(errno, std::generic_category());
    }
    if (error) {
      throw UsageError(
          fmt::format("cannot read include directory '{}': {}", directory, error.message()));
    }
    paths.push_back(directory);
  }
  paths.push_back(standardLibraryDirectory());
  return paths;
}

void checkTarget(const std::string& name) {
  if (backends::findTargetInfo(name) == nullptr) {
    throw UsageError(fmt::format("unknown target '{}'; valid targets are: {}", name,
                                 backends::targetNameList()));
  }
}

// Which command runs, and the inputs and target it needs.
void chooseCommand(const RawOptions& raw, const CLI::App& app, bool checking,
                   DriverOptions& options) {
  if (raw.listDiagnostics) {
    options.command = Command::ListDiagnostics;
    return;
  }
  if (checking) {
    for (const char* name : {"--target", "--output", "--emit", "--stats", "--rapid-rate"}) {
      if (app.count(name) > 0) {
        throw UsageError(fmt::format("option {} does not apply to 'check'", name));
      }
    }
    if (raw.checkInputs.empty() && raw.machineFile.empty()) {
      throw UsageError("FILE is required");
    }
    options.command = Command::Check;
    options.inputs = raw.checkInputs;
    return;
  }
  if (raw.input.empty()) {
    throw UsageError("no input file");
  }
  options.inputs = {raw.input};
  if (!raw.target.empty()) {
    checkTarget(raw.target);
  }
  if (!raw.emit.empty()) {
    options.command = Command::Emit;
    options.emit = raw.emit == "tokens" ? EmitKind::Tokens
                   : raw.emit == "ir"   ? EmitKind::Ir
                                        : EmitKind::Ast;
  } else if (raw.target.empty()) {
    throw UsageError(
        fmt::format("no target; choose one with -t TARGET ({})", backends::targetNameList()));
  }
  if ((raw.stats || app.count("--rapid-rate") > 0) && options.command != Command::Compile) {
    throw UsageError("--stats and --rapid-rate need a target to compile for, not --emit");
  }
  if (app.count("--rapid-rate") > 0 && !raw.stats) {
    throw UsageError("--rapid-rate only sets the time estimate of --stats");
  }
  const backends::TargetInfo* target = backends::findTargetInfo(raw.target);
  // --emit=ir -t TARGET --arcs shows the IR the backend receives.
  bool compiles = options.command == Command::Compile ||
                  (options.command == Command::Emit && options.emit == EmitKind::Ir);
  bool printsArcs = target != nullptr && target->fittedArcs;
  if (raw.arcs && (!compiles || !printsArcs)) {
    throw UsageError(
        fmt::format("--arcs is for the targets {}: it prints cuts as G02/G03 arcs",
                    backends::targetNameList([](const backends::TargetInfo& candidate) {
                      return candidate.fittedArcs;
                    })));
  }
  if ((raw.subprograms || !raw.splineEnds.empty()) &&
      (target == nullptr || !target->splineOptions)) {
    throw UsageError("--subprograms and --spline-ends are for the sinumerik target");
  }
  if (raw.stats && !canMeasure(raw.target) && !canVerify(raw.target)) {
    throw UsageError(
        fmt::format("--stats is not available for target '{}' in this version ({} have it)",
                    raw.target, backends::targetNameList([](const backends::TargetInfo& candidate) {
                      return canMeasure(candidate.name) || canVerify(candidate.name);
                    })));
  }
}

// --profile names a TNC profile for the heidenhain target, a macro
// controller's for the others.
void checkProfileFitsTarget(const RawOptions& raw) {
  bool tnc = backends::findTncProfile(raw.profile) != nullptr;
  const backends::TargetInfo* target = backends::findTargetInfo(raw.target);
  if (!raw.profile.empty() && tnc != (target != nullptr && target->tncProfiles)) {
    throw UsageError(fmt::format("--profile {} is {}", raw.profile,
                                 tnc ? "a TNC profile, for -t heidenhain"
                                     : "no TNC profile: -t heidenhain takes tnc640 or itnc530"));
  }
}

// How diagnostics are printed: the same options for every command.
void setDiagnosticOutput(const RawOptions& raw, DriverOptions& options) {
  options.diagnosticsFormat =
      raw.diagnosticsFormat == "json" ? DiagnosticsFormat::Json : DiagnosticsFormat::Text;
  options.colour = raw.colour == "always"  ? ColourMode::Always
                   : raw.colour == "never" ? ColourMode::Never
                                           : ColourMode::Auto;
  options.errorLimit = parseErrorLimit(raw.errorLimit);
}

// The pass names of --passes and --print-after, checked.
void setOptimisation(const RawOptions& raw, DriverOptions& options) {
  options.optimise = raw.optimisationLevel != "0";
  std::string_view list = raw.passes;
  while (!list.empty()) {
    std::size_t comma = list.find(',');
    options.passes.emplace_back(list.substr(0, comma));
    list = comma == std::string_view::npos ? "" : list.substr(comma + 1);
  }
  std::vector<std::string> named = options.passes;
  if (!raw.printAfter.empty() && raw.printAfter != "all") {
    named.push_back(raw.printAfter);
  }
  for (const std::string& name : named) {
    if (ir::findPass(name) == nullptr) {
      std::string known;
      for (const ir::Pass& pass : ir::allPasses()) {
        known += fmt::format("{}{}", known.empty() ? "" : ", ", pass.name);
      }
      throw UsageError(fmt::format("unknown IR pass '{}'; the passes are: {}", name, known));
    }
  }
  options.printAfter = raw.printAfter;
}

DriverOptions validatedOptions(const RawOptions& raw, const CLI::App& app, bool checking) {
  DriverOptions options;
  chooseCommand(raw, app, checking, options);
  options.target = raw.target;
  options.output = raw.output.empty() ? "-" : raw.output;
  options.defines = parseDefines(raw.defines);
  options.partName = raw.partName;
  options.stats = raw.stats;
  options.arcs = raw.arcs;
  options.subprograms = raw.subprograms;
  options.splineEnds = raw.splineEnds.empty() ? "tangent" : raw.splineEnds;
  options.macroCall = raw.macroCall;
  options.parametersInCommon = raw.parameterStorage == "common";
  checkProfileFitsTarget(raw);
  options.profile = raw.profile;
  options.rapidRate = parseRapidRate(raw.rapidRate);
  setOptimisation(raw, options);
  setDependencyFile(raw, options);
  if (!raw.sourceMap.empty() && options.command != Command::Compile) {
    throw UsageError("--source-map writes the map of a compiled program; it does not apply "
                     "to this command");
  }
  if (!raw.sourceMap.empty() && (options.output == "-" || options.target == "jit")) {
    throw UsageError("--source-map maps the lines of a program file: it needs -o FILE and a "
                     "target that prints a program (not jit)");
  }
  options.sourceMap = raw.sourceMap;
  if (raw.annotate && (options.command != Command::Compile || options.target == "jit")) {
    throw UsageError("--annotate comments a compiled program; it does not apply here");
  }
  options.annotate = raw.annotate;
  if (options.command != Command::ListDiagnostics) {
    options.importPaths = importPaths(raw.includeDirectories);
  }
  setDiagnosticOutput(raw, options);
  return options;
}

DriverOptions formatOptions(const RawOptions& raw, const CLI::App& app) {
  for (const char* name : {"--target", "--output", "--emit"}) {
    if (app.count(name) > 0) {
      throw UsageError(fmt::format("option {} does not apply to 'fmt'", name));
    }
  }
  if (raw.formatCheck && raw.formatInPlace) {
    throw UsageError("'fmt' takes --check or -i, not both");
  }
  bool readsStandardInput =
      std::find(raw.formatInputs.begin(), raw.formatInputs.end(), "-") != raw.formatInputs.end();
  if (raw.formatInPlace && readsStandardInput) {
    throw UsageError("'fmt -i' cannot rewrite standard input");
  }
  DriverOptions options;
  options.command = Command::Format;
  options.inputs = raw.formatInputs;
  options.formatMode = raw.formatCheck     ? FormatMode::Check
                       : raw.formatInPlace ? FormatMode::InPlace
                                           : FormatMode::Print;
  setDiagnosticOutput(raw, options);
  return options;
}

// cncc plot: the compile options, gcode as the default target.
DriverOptions plotOptions(const RawOptions& raw, const CLI::App& app) {
  for (const char* name : {"--emit", "--stats", "--rapid-rate"}) {
    if (app.count(name) > 0) {
      throw UsageError(fmt::format("option {} does not apply to 'plot'", name));
    }
  }
  RawOptions compile = raw;
  compile.input = raw.plotInput;
  compile.target = raw.target.empty() ? "gcode" : raw.target;
  DriverOptions options = validatedOptions(compile, app, false);
  if (!canMeasure(options.target)) {
    throw UsageError(fmt::format(
        "'plot' is not available for target '{}' in this version ({} have it)", options.target,
        backends::targetNameList(
            [](const backends::TargetInfo& candidate) { return canMeasure(candidate.name); })));
  }
  options.command = Command::Plot;
  options.plotPng = raw.plotFormat == "png";
  return options;
}

DriverOptions optOptions(const RawOptions& raw, const CLI::App& app) {
  for (const char* name : {"--target", "--emit", "--stats", "--rapid-rate"}) {
    if (app.count(name) > 0) {
      throw UsageError(fmt::format("option {} does not apply to 'opt'", name));
    }
  }
  DriverOptions options;
  options.command = Command::Optimize;
  options.inputs = {raw.optInput};
  options.output = raw.output.empty() ? "-" : raw.output;
  setDiagnosticOutput(raw, options);
  setOptimisation(raw, options);
  return options;
}

DriverOptions verifyOptions(const RawOptions& raw, const CLI::App& app) {
  for (const char* name : {"--emit", "--stats", "--rapid-rate", "--output"}) {
    if (app.count(name) > 0) {
      throw UsageError(fmt::format("option {} does not apply to 'verify'", name));
    }
  }
  if (raw.target.empty()) {
    throw UsageError(
        fmt::format("'verify' needs a target: -t TARGET ({})", backends::targetNameList()));
  }
  RawOptions compile = raw;
  compile.input = raw.verifyInput;
  DriverOptions options = validatedOptions(compile, app, false);
  if (!canVerify(options.target)) {
    throw UsageError(
        fmt::format("'verify' is not available for target '{}' in this version", options.target));
  }
  options.command = Command::Verify;
  return options;
}

DriverOptions whereOptions(const RawOptions& raw) {
  DriverOptions options;
  options.command = Command::Where;
  options.inputs = {raw.whereProgram};
  options.whereLocation = raw.whereLocation;
  options.sourceMap = raw.sourceMap.empty() ? raw.whereProgram + ".map.json" : raw.sourceMap;
  setDiagnosticOutput(raw, options);
  return options;
}

// --tool-radius N=R: offset register N (1..9999) holds radius R.
std::map<int, double> toolRadiiOf(const std::vector<std::string>& texts) {
  std::map<int, double> radii;
  for (const std::string& text : texts) {
    std::size_t equals = text.find('=');
    int number = 0;
    double radius = 0;
    bool valid = equals != std::string::npos;
    if (valid) {
      auto [numberEnd, numberError] = std::from_chars(text.data(), text.data() + equals, number);
      auto [radiusEnd, radiusError] =
          std::from_chars(text.data() + equals + 1, text.data() + text.size(), radius);
      valid = numberError == std::errc() && numberEnd == text.data() + equals &&
              radiusError == std::errc() && radiusEnd == text.data() + text.size() && number >= 1 &&
              number <= 9999 && std::isfinite(radius);
    }
    if (!valid) {
      throw UsageError(fmt::format("--tool-radius '{}': expected N=R, a register from 1 to 9999 "
                                   "and its radius, as in 1=5.",
                                   text));
    }
    radii[number] = radius;
  }
  return radii;
}

DriverOptions simulateOptions(const RawOptions& raw) {
  const backends::TargetInfo* target = backends::findTargetInfo(raw.target);
  // Sinumerik, LinuxCNC and Heidenhain programs run in readers of their own;
  // only the Heidenhain one takes a --profile (tnc640, itnc530). On those,
  // --tool-radius N gives the tool whose radius is R (its cutting edges,
  // its row of the tool table).
  bool ownReader = target != nullptr && target->runOwnProgram;
  if (!ownReader && (target == nullptr || target->controllerProfile.empty())) {
    throw UsageError(
        fmt::format("'sim' needs -t with one of: {}",
                    backends::targetNameList([](const backends::TargetInfo& candidate) {
                      return candidate.runOwnProgram || !candidate.controllerProfile.empty();
                    })));
  }
  if (ownReader && (!raw.macroArguments.empty() || raw.strictReading || raw.peckRetract ||
                    raw.peckClearance || (!raw.profile.empty() && !target->tncProfiles))) {
    throw UsageError(fmt::format("-a, --strict, --peck-retract, --peck-clearance and --profile "
                                 "apply to 'sim -t fanuc' and '-t m80' (--profile also to "
                                 "-t heidenhain), not to {}",
                                 raw.target));
  }
  checkProfileFitsTarget(raw);
  DriverOptions options;
  options.command = Command::Simulate;
  options.inputs = {raw.simulateInput};
  options.target = raw.target;
  options.profile = raw.profile;
  options.output = raw.output.empty() ? "-" : raw.output;
  options.macroArguments = raw.macroArguments;
  options.strictReading = raw.strictReading;
  options.toolRadii = toolRadiiOf(raw.toolRadii);
  options.peckRetract = raw.peckRetract;
  options.peckClearance = raw.peckClearance;
  options.chordError = raw.chordError;
  setDiagnosticOutput(raw, options);
  return options;
}

// --machine NAME, a bare name that is not a file: the shipped machine
// stdlib/machines/NAME.toml (the built-in defaults of each target).
std::string machineFilePath(const std::string& argument) {
  if (argument.find('/') != std::string::npos || argument.ends_with(".toml") ||
      std::filesystem::exists(argument)) {
    return argument;
  }
  std::filesystem::path shipped =
      std::filesystem::path(standardLibraryDirectory()) / "machines" / (argument + ".toml");
  if (!std::filesystem::exists(shipped)) {
    throw UsageError(fmt::format("--machine {}: no such file, and no shipped machine of that "
                                 "name (fanuc, m80, linuxcnc, sinumerik, gcode)",
                                 argument));
  }
  return shipped.string();
}

// --machine: the file read (its diagnostics printed when it has errors), its
// target the default of -t, its profile in place of --profile's.
std::shared_ptr<const backends::MachineDescription> applyMachineFile(RawOptions& raw,
                                                                     bool applies) {
  if (raw.machineFile.empty()) {
    return nullptr;
  }
  if (!applies) {
    throw UsageError("option --machine does not apply to 'fmt', 'opt' or 'lsp'");
  }
  if (!raw.profile.empty()) {
    throw UsageError("--profile and --machine together: the machine file's [profile] is the "
                     "controller profile");
  }
  std::shared_ptr<const backends::MachineDescription> machine = loadMachineFile(
      machineFilePath(raw.machineFile),
      raw.diagnosticsFormat == "json" ? DiagnosticsFormat::Json : DiagnosticsFormat::Text,
      raw.colour == "always" ? ColourMode::Always : ColourMode::Never);
  if (machine == nullptr) {
    throw MachineFileError{};
  }
  if (raw.target.empty()) {
    raw.target = machine->target;
  } else if (raw.target != machine->target) {
    throw UsageError(fmt::format("-t {} is not the target of machine file '{}', which is '{}'",
                                 raw.target, raw.machineFile, machine->target));
  }
  return machine;
}

int reportUsageError(std::string_view message) {
  fmt::print(stderr, "cncc: error: {}\nRun 'cncc --help' for usage.\n", message);
  return 2;
}

} // namespace

// -MD, -MF and -MT as C compilers spell them, for the parser's --MD...
std::vector<std::string> compilerStyleArguments(int argc, const char* const* argv) {
  std::vector<std::string> arguments;
  for (int i = 0; i < argc; ++i) {
    std::string_view argument = argv[i];
    bool dependencyOption = argument == "-MD" || argument == "-MF" || argument == "-MT";
    arguments.push_back(dependencyOption ? "-" + std::string(argument) : std::string(argument));
  }
  return arguments;
}

ParsedCommandLine parseCommandLine(int argc, const char* const* argv) {
  RawOptions raw;
  CLI::App app("cncc: compiles CDL part descriptions for CNC controllers", "cncc");
  app.set_version_flag("--version", "cncc " CNCC_VERSION);
  app.footer(helpFooter());
  app.require_subcommand(0, 1);
  addCompileOptions(app, raw);
  addCommonOptions(app, raw);
  CLI::App* check = addCheckCommand(app, raw);
  CLI::App* format = addFormatCommand(app, raw);
  CLI::App* lsp = addLanguageServerCommand(app);
  CLI::App* plot = addPlotCommand(app, raw);
  CLI::App* opt = addOptCommand(app, raw);
  CLI::App* simulate = addSimulateCommand(app, raw);
  CLI::App* verify = addVerifyCommand(app, raw);
  CLI::App* where = addWhereCommand(app, raw);
  try {
    std::vector<std::string> arguments = compilerStyleArguments(argc, argv);
    std::vector<const char*> pointers;
    for (const std::string& argument : arguments) {
      pointers.push_back(argument.c_str());
    }
    app.parse(static_cast<int>(pointers.size()), pointers.data());
    bool takesMachine = !format->parsed() && !opt->parsed() && !lsp->parsed() && !where->parsed();
    std::shared_ptr<const backends::MachineDescription> machine =
        applyMachineFile(raw, takesMachine);
    DriverOptions options;
    if (format->parsed()) {
      options = formatOptions(raw, app);
    } else if (opt->parsed()) {
      options = optOptions(raw, app);
    } else if (plot->parsed()) {
      options = plotOptions(raw, app);
    } else if (simulate->parsed()) {
      options = simulateOptions(raw);
    } else if (verify->parsed()) {
      options = verifyOptions(raw, app);
    } else if (where->parsed()) {
      options = whereOptions(raw);
    } else if (lsp->parsed()) {
      options.command = Command::LanguageServer;
    } else {
      options = validatedOptions(raw, app, check->parsed());
    }
    options.machineFile = raw.machineFile.empty() ? "" : machineFilePath(raw.machineFile);
    options.machine = std::move(machine);
    return {std::move(options), 0};
  } catch (const CLI::ParseError& error) {
    if (error.get_exit_code() == 0) {
      return {std::nullopt, app.exit(error)};
    }
    return {std::nullopt, reportUsageError(error.what())};
  } catch (const UsageError& error) {
    return {std::nullopt, reportUsageError(error.what())};
  } catch (const MachineFileError&) {
    return {std::nullopt, 1};
  }
}

} // namespace cncc::driver
