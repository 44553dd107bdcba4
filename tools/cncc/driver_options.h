// The command line of `cncc`, parsed into one plain struct that the commands
// read. Parsing checks everything that is a usage error (exit code 2), so a
// command never has to.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace cncc::driver {

enum class Command {
  Compile,         // cncc FILE -t TARGET [-o OUT]
  Emit,            // cncc FILE --emit=tokens|ast|ir [-o OUT]
  Check,           // cncc check FILE...
  ListDiagnostics, // cncc --list-diagnostics (hidden; for the coverage test)
  Format,          // cncc fmt FILE... [--check | -i]
  LanguageServer,  // cncc lsp
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
  std::string target;              // a name from the target table
  std::string output = "-";        // "-" is standard output
  EmitKind emit = EmitKind::Ast;
  std::map<std::string, double> defines; // -D name=value
  std::string partName;                  // -p NAME
  // -I directories in order, then the standard library directory.
  std::vector<std::string> importPaths;
  DiagnosticsFormat diagnosticsFormat = DiagnosticsFormat::Text;
  ColourMode colour = ColourMode::Auto;
  std::size_t errorLimit = 50; // 0 means no limit
  FormatMode formatMode = FormatMode::Print;
};

// What parsing the command line decided: options to run with, or an exit
// code when parsing already did all there was to do (--help, --version, a
// usage error, which it has printed).
struct ParsedCommandLine {
  std::optional<DriverOptions> options;
  int exitCode = 0;
};

ParsedCommandLine parseCommandLine(int argc, const char* const* argv);

} // namespace cncc::driver
