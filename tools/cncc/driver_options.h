// The command line of `cncc`, parsed into one plain struct that the commands
// read. Parsing checks everything that is a usage error (exit code 2), so a
// command never has to.
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace cncc::backends {
struct MachineDescription;
}

namespace cncc::driver {

enum class Command {
  Compile,         // cncc FILE -t TARGET [-o OUT]
  Emit,            // cncc FILE --emit=tokens|ast|ir [-o OUT]
  Check,           // cncc check FILE... | cncc check --machine FILE.toml
  ListDiagnostics, // cncc --list-diagnostics (hidden; for the coverage test)
  Format,          // cncc fmt FILE... [--check | -i]
  LanguageServer,  // cncc lsp
  Optimize,        // cncc opt FILE.ir [--passes=a,b]
  Plot,            // cncc plot FILE -o OUT.svg [-t TARGET]
  Simulate,        // cncc sim PROGRAM -t fanuc|m80 [-a A3.] [--profile NAME] [-o OUT]
  Verify,          // cncc verify FILE -t TARGET [-D NAME=VALUE ...]
  Where,           // cncc where PROGRAM LINE|Nnnnn [--source-map FILE.json]
};

enum class EmitKind { Tokens, Ast, Ir };
enum class DiagnosticsFormat { Text, Json };
enum class ColourMode { Auto, Always, Never };
// What `cncc fmt` does with the formatted text: print it, list the files it
// would change (--check), or rewrite them (-i).
enum class FormatMode { Print, Check, InPlace };

struct DriverOptions {
  Command command = Command::Compile;
  std::vector<std::string> inputs; // one, except for `check`
  std::string target;              // a registered target's name (target_info.h)
  std::string output = "-";        // "-" is standard output
  EmitKind emit = EmitKind::Ast;
  std::map<std::string, double, std::less<>> defines; // -D name=value
  std::string partName;                               // -p NAME
  // -I directories in order, then the standard library directory.
  std::vector<std::string> importPaths;
  DiagnosticsFormat diagnosticsFormat = DiagnosticsFormat::Text;
  ColourMode colour = ColourMode::Auto;
  std::size_t errorLimit = 50; // 0 means no limit
  FormatMode formatMode = FormatMode::Print;
  // IR passes: -O0 turns the default pipeline off; `opt --passes=a,b` runs
  // these instead of it (empty: the default pipeline); --print-after=NAME
  // (or all) prints the IR after that pass to stderr.
  bool optimise = true;
  std::vector<std::string> passes;
  std::string printAfter;
  bool stats = false; // --stats: measure the program, report on stderr
  bool arcs = false;  // --arcs: G02/G03 arcs on every planar cut (gcode)
  // Sinumerik: --subprograms (spline blocks in NAME_CUTn.SPF), --spline-ends.
  bool subprograms = false;
  std::string splineEnds = "tangent";
  double rapidRate = 1e4; // --rapid-rate, mm/min, for the time estimate
  // Macro targets: --macro (a G65-callable macro ending M99), --params=common
  // (parameters in common variables), --profile=NAME (a controller profile).
  bool macroCall = false;
  bool parametersInCommon = false;
  std::string profile;
  std::vector<std::string> macroArguments; // sim -a A3.: run as if called by G65
  bool strictReading = false;              // sim --strict: the compiler's conservative reading
  std::map<int, double> toolRadii;         // sim --tool-radius N=R: offset registers
  std::optional<double> peckRetract;       // sim --peck-retract: G73 (parameter 5114)
  std::optional<double> peckClearance;     // sim --peck-clearance: G83 (parameter 5115)
  double chordError = 1e-4;                // sim --chord-error: arcs printed as chords
  // --machine FILE.toml: the machine read from it (machine_options.h), whose
  // set-up, profile and limits replace the target's built-in ones.
  std::string machineFile;
  std::shared_ptr<const backends::MachineDescription> machine;
  // -MD, -MF FILE, -MT TARGET: after a compile, a Make/Ninja depfile at
  // `dependencyFile` (empty: none) naming `dependencyTarget`'s inputs.
  std::string dependencyFile;
  std::string dependencyTarget;
  // --source-map FILE.json: after a compile, where each program line comes
  // from (source_map.h). `where`: the map to read (default PROGRAM.map.json)
  // and the program line asked about (a line number or Nnnnn).
  std::string sourceMap;
  std::string whereLocation;
  bool plotPng = false;  // plot --format=png
  bool annotate = false; // --annotate: (file.cdl:12) before each cut
};

// What parsing the command line decided: options to run with, or an exit
// code when parsing already did all there was to do (--help, --version, a
// usage error or a bad machine file, which it has printed).
struct ParsedCommandLine {
  std::optional<DriverOptions> options;
  int exitCode = 0;
};

ParsedCommandLine parseCommandLine(int argc, const char* const* argv);

} // namespace cncc::driver
