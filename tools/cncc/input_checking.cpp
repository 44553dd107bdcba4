#include "input_checking.h"

#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <system_error>

namespace cncc::driver {

namespace {

// Why `path` cannot be read, in the system's words.
std::string readFailureReason(const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) {
    return std::make_error_code(std::errc::is_a_directory).message();
  }
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file == nullptr) {
    return std::error_code(errno, std::generic_category()).message();
  }
  std::fclose(file);
  return "not a regular file";
}

} // namespace

std::optional<frontend::FileId> loadInput(const std::string& path, frontend::SourceManager& sources,
                                          frontend::DiagnosticEngine& diagnostics) {
  std::optional<frontend::FileId> file = sources.loadFile(path);
  if (!file) {
    diagnostics.report(frontend::DiagnosticKind::FileNotReadable, {},
                       fmt::format("cannot read '{}': {}", path, readFailureReason(path)));
  }
  return file;
}

std::optional<frontend::CheckedProgram> checkInput(const std::string& path,
                                                   const DriverOptions& options, bool requirePart,
                                                   frontend::SourceManager& sources,
                                                   frontend::DiagnosticEngine& diagnostics) {
  std::optional<frontend::FileId> file = loadInput(path, sources, diagnostics);
  if (!file) {
    return std::nullopt;
  }
  frontend::CheckOptions checkOptions;
  checkOptions.importPaths = options.importPaths;
  checkOptions.defines = options.defines;
  checkOptions.partName = options.partName;
  checkOptions.requirePart = requirePart;
  return frontend::checkProgram(sources, *file, checkOptions, diagnostics);
}

} // namespace cncc::driver
