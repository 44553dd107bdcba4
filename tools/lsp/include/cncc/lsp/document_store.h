// The documents the client has open, kept in step with its edits: whole
// replacements and incremental range changes (positions in UTF-16).
#pragma once

#include "cncc/lsp/text_positions.h"

#include <map>
#include <optional>
#include <string>

namespace cncc::lsp {

struct Document {
  std::string text;
  long long version = 0;
};

// One change of `textDocument/didChange`: a range and its new text, or the
// whole new text when `range` is absent.
struct TextChange {
  std::optional<Range> range;
  std::string text;
};

class DocumentStore {
public:
  void open(const std::string& uri, std::string text, long long version);
  void close(const std::string& uri);
  // Applies changes in order; false when the document is not open.
  bool change(const std::string& uri, const std::vector<TextChange>& changes, long long version);

  const Document* find(const std::string& uri) const;

private:
  std::map<std::string, Document> documents_;
};

// Replaces `range` of `text` (clamped like TextPositions::offsetOf; a
// reversed range is taken as empty at its start) with `replacement`.
void applyChange(std::string& text, const TextChange& change);

} // namespace cncc::lsp
