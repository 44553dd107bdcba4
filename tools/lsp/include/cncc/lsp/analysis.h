// One run of the front end over a document: what the diagnostics, hovers,
// definitions, completions and symbols are computed from. The server makes
// a new one after every change, exactly as `cncc check` would check the
// file, so the editor sees the command line's messages and spans.
#pragma once

#include "cncc/frontend/diagnostics.h"
#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/lsp/text_positions.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace cncc::lsp {

struct AnalysisOptions {
  // Directories searched for imports after the document's own directory;
  // the standard library's last.
  std::vector<std::string> importPaths;
};

// A place in some file, as the protocol's Location.
struct Location {
  std::string uri;
  Range range;
};

class Analysis {
public:
  Analysis(std::string uri, const std::string& text, const AnalysisOptions& options);
  Analysis(const Analysis&) = delete;
  Analysis& operator=(const Analysis&) = delete;

  const std::string& uri() const { return uri_; }
  frontend::FileId file() const { return file_; }
  const frontend::SourceManager& sources() const { return sources_; }
  std::string_view text() const { return sources_.file(file_).text(); }
  const frontend::CheckedProgram& program() const { return program_; }
  const frontend::Module& module() const { return program_.modules.front(); }
  const std::deque<frontend::Diagnostic>& diagnostics() const { return diagnostics_.diagnostics(); }
  const TextPositions& positions() const { return positions_; }

  std::uint32_t offsetOf(Position position) const { return positions_.offsetOf(position); }
  // A span of the document itself.
  Range rangeOf(frontend::SourceSpan span) const;
  // A span in the document or in a file it imports; nullopt for no file.
  std::optional<Location> locationOf(frontend::SourceSpan span) const;
  // The URI the protocol knows a file of this analysis by.
  std::string uriOf(frontend::FileId file) const;

private:
  std::string uri_;
  frontend::SourceManager sources_;
  frontend::FileId file_;
  frontend::DiagnosticEngine diagnostics_;
  frontend::CheckedProgram program_;
  TextPositions positions_;
};

// The path a document is checked under: its file path for a `file:` URI
// (so relative imports resolve beside it), else the URI itself.
std::string documentPath(const std::string& uri);

} // namespace cncc::lsp
