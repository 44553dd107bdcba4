#include "driver_options.h"

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

// The command line as CLI11 fills it in, before it is checked.
struct RawOptions {
  std::string input;
  std::vector<std::string> checkInputs;
  std::string target;
  std::string output;
  std::string emit;
  std::vector<std::string> defines;
  std::string partName;
  std::vector<std::string> includeDirectories;
  std::string diagnosticsFormat = "text";
  std::string colour = "auto";
  std::string errorLimit = "50";
  bool listDiagnostics = false;
  std::vector<std::string> formatInputs;
  bool formatCheck = false;
  bool formatInPlace = false;
  bool stats = false;
  bool arcs = false;
  bool subprograms = false;
  std::string splineEnds;
  std::string rapidRate = "10000";
  std::string plotInput;
  std::string optInput;
  std::string passes;
  std::string printAfter;
  std::string optimisationLevel = "1";
  bool macroCall = false;
  std::string parameterStorage = "local";
  std::string profile;
  std::string simulateInput;
  std::string verifyInput;
  std::vector<std::string> macroArguments;
  bool strictReading = false;
  std::vector<std::string> toolRadii;
  std::optional<double> peckRetract;
  std::optional<double> peckClearance;
  double chordError = 1e-4;
  std::string machineFile;
};

// A mistake in how cncc was called: printed, exit code 2.
class UsageError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// A machine file with errors, whose diagnostics are printed: exit code 1.
struct MachineFileError {};

std::string helpFooter() {
  std::string footer = "\nTargets:\n";
  for (const Target& target : allTargets()) {
    footer += fmt::format("  {:<11}{}{}\n", target.name, target.description,
                          target.available() ? "" : " (not in this version)");
  }
  footer += "\nExamples:\n"
            "  cncc examples/s_profile.cdl -t m80 -o O1000\n"
            "  cncc check examples/*.cdl\n"
            "  cncc fmt -i examples/*.cdl\n"
            "  cncc --emit=ast examples/s_profile.cdl\n"
            "  cncc examples/s_profile.cdl -t gcode --stats -o O1\n"
            "  cncc plot examples/s_profile.cdl -o s_profile.svg\n"
            "  cncc examples/s_profile.cdl --machine examples/machines/fanuc-0i-mf-vmc.toml\n"
            "\nExit codes: 0 success, 1 errors in the source, 2 wrong usage.";
  return footer;
}

// Options shared by every command (compiling, emitting, checking).
void addCommonOptions(CLI::App& app, RawOptions& raw) {
  app.add_option("-D", raw.defines, "Override the default of part parameter NAME")
      ->type_name("NAME=VALUE")
      ->allow_extra_args(false);
  app.add_option("-p,--part", raw.partName, "The part to compile when a file holds several")
      ->type_name("PART");
  app.add_option("-I", raw.includeDirectories,
                 "Search DIR for imports (before the standard library)")
      ->type_name("DIR")
      ->allow_extra_args(false);
  app.add_option("--diagnostics-format", raw.diagnosticsFormat,
                 "How diagnostics are printed: text, or json (one object per line)")
      ->type_name("FORMAT")
      ->check(CLI::IsMember({"text", "json"}));
  app.add_option("--color", raw.colour,
                 "Colour diagnostics: auto (when stderr is a terminal), "
                 "always or never")
      ->type_name("WHEN")
      ->check(CLI::IsMember({"auto", "always", "never"}));
  app.add_option("--error-limit", raw.errorLimit, "Stop reporting after N errors (0: no limit)")
      ->type_name("N");
  app.add_option("--machine", raw.machineFile,
                 "The machine's set-up blocks, controller profile and limits from a machine "
                 "file (examples/machines); its target is the default of -t")
      ->type_name("FILE.toml");
  app.add_flag("--list-diagnostics", raw.listDiagnostics,
               "Print the name of every diagnostic and exit")
      ->group("");
}

void addCompileOptions(CLI::App& app, RawOptions& raw) {
  app.add_option("FILE", raw.input, "The .cdl file to compile")->type_name("");
  app.add_option("-t,--target", raw.target, "The controller to compile for (see Targets below)")
      ->type_name("TARGET");
  app.add_option("-o,--output", raw.output, "Where to write the program ('-': standard output)")
      ->type_name("OUT");
  app.add_option("--emit", raw.emit,
                 "Print a stage instead of compiling: tokens, ast (after checking), or ir "
                 "(the part lowered)")
      ->type_name("STAGE")
      ->check(CLI::IsMember({"tokens", "ast", "ir"}));
  app.add_flag("--macro", raw.macroCall,
               "m80/fanuc: print a macro called with G65 P.. and arguments, ending M99; "
               "linuxcnc: an o<part> sub taking the parameters as call arguments");
  app.add_option("--params", raw.parameterStorage,
                 "m80/fanuc: part parameters as G65 argument locals, or in common variables")
      ->type_name("local|common")
      ->check(CLI::IsMember({"local", "common"}));
  app.add_option("--profile", raw.profile,
                 "m80/fanuc: the controller profile (fanuc, fanuc-0i-small, m80)")
      ->type_name("NAME")
      ->check(CLI::IsMember({"fanuc", "fanuc-0i-small", "m80"}));
  app.add_flag(
      "--arcs", raw.arcs,
      "gcode, linuxcnc, m80, fanuc: cut planar curves as G02/G03 arcs within their tolerance "
      "(as arcs=true on every cut)");
  app.add_flag("--subprograms", raw.subprograms,
               "sinumerik: each cut's spline blocks in a subprogram NAME_CUTn.SPF called at "
               "every pass (after the main program, in archive form)");
  app.add_option("--spline-ends", raw.splineEnds,
                 "sinumerik: how A and C splines start and end: BTAN after a move in XY and "
                 "BNAT otherwise (tangent, the default), BNAT ENAT, or BAUTO EAUTO")
      ->type_name("tangent|natural|auto")
      ->check(CLI::IsMember({"tangent", "natural", "auto"}));
  app.add_flag("--stats", raw.stats,
               "Also print, on stderr, the program's size, path length, time estimate and "
               "largest deviation from the true curves");
  app.add_option("--rapid-rate", raw.rapidRate,
                 "The rapid rate the --stats time estimate assumes (default 10000)")
      ->type_name("MM/MIN");
}

CLI::App* addCheckCommand(CLI::App& app, RawOptions& raw) {
  CLI::App* check =
      app.add_subcommand("check", "Check files and report every problem without compiling");
  check->add_option("FILE", raw.checkInputs, "The .cdl files to check")->type_name("");
  // The common options belong to the main command and fall through to here.
  check->fallthrough();
  check->footer("\nAlso takes -D, -p, -I, --diagnostics-format, --color and --error-limit "
                "(see 'cncc --help'); with --machine FILE.toml it checks the machine file too, "
                "or alone.\nExit codes: 0 no errors, 1 errors in some file, 2 wrong "
                "usage.");
  return check;
}

CLI::App* addFormatCommand(CLI::App& app, RawOptions& raw) {
  CLI::App* format = app.add_subcommand(
      "fmt",
      "Print files in the canonical layout (see frontend/include/cncc/frontend/formatter.h)");
  format->add_option("FILE", raw.formatInputs, "The .cdl files ('-': standard input)")
      ->type_name("")
      ->required();
  format->add_flag("--check", raw.formatCheck,
                   "Write nothing; list the files that are not formatted (exit code 1 if any)");
  format->add_flag("-i,--in-place", raw.formatInPlace, "Rewrite the files that are not formatted");
  format->fallthrough();
  format->footer("\nExit codes: 0 done, 1 syntax errors (such a file is left as it is) or, with "
                 "--check, unformatted files, 2 wrong usage.");
  return format;
}

CLI::App* addPlotCommand(CLI::App& app, RawOptions& raw) {
  CLI::App* plot = app.add_subcommand(
      "plot", "Draw the part's true curves and emitted path, coloured by deviation, as SVG");
  plot->add_option("FILE", raw.plotInput, "The .cdl file to plot")->type_name("")->required();
  plot->fallthrough();
  plot->footer("\nTakes -o OUT.svg ('-': standard output), -t TARGET (gcode or jit; gcode by "
               "default), -D, -p, -I and the diagnostic options (see 'cncc --help').");
  return plot;
}

// cncc opt: IR passes on a textual IR file; -O and --print-after are
// options of the main command that fall through to it.
CLI::App* addOptCommand(CLI::App& app, RawOptions& raw) {
  app.add_option("--print-after", raw.printAfter,
                 "Print the IR to stderr after each run of IR pass NAME (or all)")
      ->type_name("NAME");
  app.add_option("-O", raw.optimisationLevel, "-O0: skip the IR optimiser (-O1, the default)")
      ->type_name("LEVEL")
      ->check(CLI::IsMember({"0", "1"}));
  CLI::App* opt = app.add_subcommand("opt", "Run IR passes on a textual IR file and print it");
  opt->add_option("FILE", raw.optInput, "The .ir file")->type_name("")->required();
  opt->add_option("--passes", raw.passes, "Comma-separated pass names (default: the pipeline)")
      ->type_name("A,B");
  opt->fallthrough();
  return opt;
}

// cncc sim: -t, -o and --profile are the main command's options.
CLI::App* addSimulateCommand(CLI::App& app, RawOptions& raw) {
  CLI::App* simulate = app.add_subcommand(
      "sim", "Run an m80/fanuc/sinumerik program on a virtual controller and print its path as "
             "CSV");
  simulate->add_option("PROGRAM", raw.simulateInput, "The program file")->type_name("")->required();
  simulate
      ->add_option("-a", raw.macroArguments,
                   "Run the program as if called by G65 with this argument (A3.)")
      ->type_name("ARG")
      ->allow_extra_args(false);
  simulate->add_flag("--strict", raw.strictReading,
                     "Read the program as the compiler prints it: ( ) comments in upper case, "
                     "no ';', macro words in full");
  simulate
      ->add_option("--tool-radius", raw.toolRadii,
                   "The radius in offset register N, read by D N for G41/G42 (1=5.)")
      ->type_name("N=R")
      ->allow_extra_args(false);
  simulate
      ->add_option("--peck-retract", raw.peckRetract,
                   "G73's retract after each peck (Fanuc parameter 5114)")
      ->type_name("D")
      ->check(CLI::NonNegativeNumber);
  simulate
      ->add_option("--peck-clearance", raw.peckClearance,
                   "G83's clearance above the last depth (Fanuc parameter 5115)")
      ->type_name("D")
      ->check(CLI::NonNegativeNumber);
  simulate
      ->add_option("--chord-error", raw.chordError,
                   "The largest distance between an arc and the chords printed for it "
                   "(default 0.0001)")
      ->type_name("MM")
      ->check(CLI::Range(1e-6, 10.0));
  simulate->fallthrough();
  simulate->footer(
      "\nTakes -t fanuc|m80|sinumerik, --profile NAME and -o OUT ('-': standard output).");
  return simulate;
}

// cncc verify: the compile options (-t, -D, -p, --profile, --macro,
// --params) are the main command's.
CLI::App* addVerifyCommand(CLI::App& app, RawOptions& raw) {
  CLI::App* verify = app.add_subcommand(
      "verify", "Compile for a target, run the program as its controller would and check it "
                "against the true curves");
  verify->add_option("FILE", raw.verifyInput, "The .cdl file")->type_name("")->required();
  verify->fallthrough();
  verify->footer("\nTakes -t TARGET, -D NAME=VALUE (m80/fanuc: set on the controller, as G65 "
                 "arguments with --macro, common variables with --params common, else in the "
                 "program's parameter lines), -p, -I, --profile, --macro, --params and the "
                 "diagnostic options.\nExit codes: 0 every cut within its tolerance, 1 a cut "
                 "exceeds it, the controller refuses the program or the source has errors, 2 "
                 "wrong usage.");
  return verify;
}

CLI::App* addLanguageServerCommand(CLI::App& app) {
  CLI::App* lsp = app.add_subcommand(
      "lsp", "Run the language server (Language Server Protocol on standard input and output)");
  lsp->add_flag_function(
      "--stdio", [](std::int64_t) {},
      "Use standard input and output (the default; editors pass it)");
  return lsp;
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
  if (findTarget(name) == nullptr) {
    throw UsageError(
        fmt::format("unknown target '{}'; valid targets are: {}", name, targetNameList()));
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
    throw UsageError(fmt::format("no target; choose one with -t TARGET ({})", targetNameList()));
  }
  if ((raw.stats || app.count("--rapid-rate") > 0) && options.command != Command::Compile) {
    throw UsageError("--stats and --rapid-rate need a target to compile for, not --emit");
  }
  if (app.count("--rapid-rate") > 0 && !raw.stats) {
    throw UsageError("--rapid-rate only sets the time estimate of --stats");
  }
  const Target* target = findTarget(raw.target);
  bool printsArcs = target != nullptr && target->fittedArcs;
  // --emit=ir -t TARGET --arcs shows the IR the backend receives.
  bool compiles = options.command == Command::Compile ||
                  (options.command == Command::Emit && options.emit == EmitKind::Ir);
  if (raw.arcs && (!compiles || !printsArcs)) {
    throw UsageError(
        fmt::format("--arcs is for the targets {}: it prints cuts as G02/G03 arcs",
                    targetNameList([](const Target& candidate) { return candidate.fittedArcs; })));
  }
  if ((raw.subprograms || !raw.splineEnds.empty()) &&
      (target == nullptr || !target->splineOptions)) {
    throw UsageError("--subprograms and --spline-ends are for the sinumerik target");
  }
  if (raw.stats && !canMeasure(raw.target) && !canVerify(raw.target)) {
    throw UsageError(
        fmt::format("--stats is not available for target '{}' in this version ({} have it)",
                    raw.target, targetNameList([](const Target& candidate) {
                      return canMeasure(candidate.name) || canVerify(candidate.name);
                    })));
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
  options.profile = raw.profile;
  options.rapidRate = parseRapidRate(raw.rapidRate);
  setOptimisation(raw, options);
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
        targetNameList([](const Target& candidate) { return canMeasure(candidate.name); })));
  }
  options.command = Command::Plot;
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
    throw UsageError(fmt::format("'verify' needs a target: -t TARGET ({})", targetNameList()));
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
  const Target* target = findTarget(raw.target);
  bool sinumerik = raw.target == "sinumerik";
  if (!sinumerik && (target == nullptr || target->controllerProfile.empty())) {
    throw UsageError("'sim' needs -t fanuc, -t m80 or -t sinumerik");
  }
  if (sinumerik && (!raw.macroArguments.empty() || raw.strictReading || !raw.toolRadii.empty() ||
                    raw.peckRetract || raw.peckClearance || !raw.profile.empty())) {
    throw UsageError("-a, --strict, --tool-radius, --peck-retract, --peck-clearance and "
                     "--profile apply to 'sim -t fanuc' and '-t m80', not to sinumerik");
  }
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
      raw.machineFile,
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
  try {
    app.parse(argc, argv);
    bool takesMachine = !format->parsed() && !opt->parsed() && !lsp->parsed();
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
    } else if (lsp->parsed()) {
      options.command = Command::LanguageServer;
    } else {
      options = validatedOptions(raw, app, check->parsed());
    }
    options.machineFile = raw.machineFile;
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
