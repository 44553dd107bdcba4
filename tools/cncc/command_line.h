// The command line as CLI11 reads it (the options of each command, before
// they are checked: driver_options.cpp turns them into DriverOptions).
#pragma once

#include <CLI/CLI.hpp>

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace cncc::driver {

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
  std::string plotFormat = "svg";
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
  bool writeDependencies = false; // -MD
  std::string dependencyFile;     // -MF
  std::string dependencyTarget;   // -MT
  std::string sourceMap;          // --source-map
  bool annotate = false;          // --annotate
  std::string whereProgram;
  std::string whereLocation;
};

// A mistake in how cncc was called: printed, exit code 2.
class UsageError : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

// A machine file with errors, whose diagnostics are printed: exit code 1.
struct MachineFileError {};

// The help's footer: the targets and an example.
std::string helpFooter();
// The options every command takes, and those of compiling.
void addCommonOptions(CLI::App& app, RawOptions& raw);
void addCompileOptions(CLI::App& app, RawOptions& raw);
// The subcommands, each with its options.
CLI::App* addCheckCommand(CLI::App& app, RawOptions& raw);
CLI::App* addFormatCommand(CLI::App& app, RawOptions& raw);
CLI::App* addPlotCommand(CLI::App& app, RawOptions& raw);
CLI::App* addOptCommand(CLI::App& app, RawOptions& raw);
CLI::App* addSimulateCommand(CLI::App& app, RawOptions& raw);
CLI::App* addVerifyCommand(CLI::App& app, RawOptions& raw);
CLI::App* addWhereCommand(CLI::App& app, RawOptions& raw);
CLI::App* addLanguageServerCommand(CLI::App& app);

} // namespace cncc::driver
