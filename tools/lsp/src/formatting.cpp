// Formatting: the front end's formatter (the one `cncc fmt` runs), as one
// edit that replaces the document.
#include "cncc/frontend/formatter.h"
#include "cncc/lsp/features.h"
#include "cncc/lsp/protocol_json.h"

namespace cncc::lsp {

Json formatting(const std::string& uri, const std::string& text) {
  frontend::SourceManager sources;
  frontend::FileId file = sources.addFile(documentPath(uri), text);
  frontend::DiagnosticEngine diagnostics(0);
  std::optional<std::string> formatted = frontend::formatFile(sources, file, diagnostics);
  if (!formatted || *formatted == text) {
    return Json::array(); // nothing to change, or syntax errors (shown as diagnostics)
  }
  TextPositions positions(text);
  Range whole{{0, 0}, positions.positionOf(static_cast<std::uint32_t>(text.size()))};
  return Json::array({{{"range", toJson(whole)}, {"newText", std::move(*formatted)}}});
}

} // namespace cncc::lsp
