#include "cncc/lsp/analysis.h"

#include "cncc/lsp/uri.h"

#include <filesystem>

namespace cncc::lsp {

std::string documentPath(const std::string& uri) {
  return pathFromUri(uri).value_or(uri);
}

namespace {

frontend::CheckOptions checkOptions(const AnalysisOptions& options) {
  frontend::CheckOptions check;
  check.importPaths = options.importPaths;
  check.requirePart = false; // like `cncc check`: every part is checked
  return check;
}

} // namespace

Analysis::Analysis(std::string uri, const std::string& text, const AnalysisOptions& options)
    : uri_(std::move(uri)), file_(sources_.addFile(documentPath(uri_), text)),
      program_(frontend::checkProgram(sources_, file_, checkOptions(options), diagnostics_)),
      positions_(sources_.file(file_).text()) {}

Range Analysis::rangeOf(frontend::SourceSpan span) const {
  return positions_.rangeOf(span.begin, span.end);
}

std::string Analysis::uriOf(frontend::FileId file) const {
  if (file == file_) {
    return uri_;
  }
  std::error_code error;
  std::filesystem::path path = std::filesystem::absolute(sources_.file(file).path(), error);
  return uriFromPath(path.lexically_normal().string());
}

std::optional<Location> Analysis::locationOf(frontend::SourceSpan span) const {
  if (!span.valid()) {
    return std::nullopt;
  }
  if (span.file == file_) {
    return Location{uri_, rangeOf(span)};
  }
  TextPositions positions(sources_.file(span.file).text());
  return Location{uriOf(span.file), positions.rangeOf(span.begin, span.end)};
}

} // namespace cncc::lsp
