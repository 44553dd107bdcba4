// `cncc fmt` (the front end's formatter over files) and `cncc lsp` (the
// language server of tools/lsp over standard input and output).
#include "commands.h"

#include "atomic_output_file.h"
#include "diagnostic_output.h"
#include "input_checking.h"

#include "cncc/frontend/formatter.h"
#include "cncc/lsp/server_loop.h"

#include <fmt/format.h>
#include <iostream>
#include <iterator>

namespace cncc::driver {

namespace {

using frontend::DiagnosticEngine;
using frontend::FileId;
using frontend::SourceManager;

std::optional<FileId> loadFormatInput(const std::string& path, SourceManager& sources,
                                      DiagnosticEngine& diagnostics) {
  if (path != "-") {
    return loadInput(path, sources, diagnostics);
  }
  std::string text{std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>()};
  return sources.addFile("<stdin>", std::move(text));
}

// Formats one file as the mode says; false when it could not (syntax
// errors, an unreadable or unwritable file) or, for --check, would change.
bool formatOne(const std::string& path, const DriverOptions& options,
               const DiagnosticOutput& output) {
  SourceManager sources;
  DiagnosticEngine diagnostics(options.errorLimit);
  std::optional<FileId> file = loadFormatInput(path, sources, diagnostics);
  std::optional<std::string> text =
      file ? frontend::formatFile(sources, *file, diagnostics) : std::nullopt;
  output.print(diagnostics, sources);
  if (!text) {
    return false;
  }
  bool changes = *text != sources.file(*file).text();
  switch (options.formatMode) {
  case FormatMode::Print:
    fmt::print("{}", *text);
    return true;
  case FormatMode::Check:
    if (changes) {
      fmt::print("{}\n", path);
    }
    return !changes;
  case FormatMode::InPlace: {
    std::error_code error;
    if (changes && !writeFileAtomically(path, *text, error)) {
      output.driverError(fmt::format("cannot write '{}': {}", path, error.message()));
      return false;
    }
    return true;
  }
  }
  return false;
}

} // namespace

int runFormat(const DriverOptions& options) {
  DiagnosticOutput output(options.diagnosticsFormat, options.colour);
  bool allDone = true;
  for (const std::string& path : options.inputs) {
    allDone &= formatOne(path, options, output);
  }
  std::fflush(stdout);
  return allDone ? 0 : 1;
}

int runLanguageServer() {
  std::ios::sync_with_stdio(false);
  lsp::Server server({lsp::defaultStdlibDirectory()});
  return lsp::runServer(server, std::cin, std::cout, std::cerr);
}

} // namespace cncc::driver
