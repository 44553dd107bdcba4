#include "cncc/lsp/document_store.h"

#include <algorithm>

namespace cncc::lsp {

void DocumentStore::open(const std::string& uri, std::string text, long long version) {
  documents_[uri] = Document{std::move(text), version};
}

void DocumentStore::close(const std::string& uri) {
  documents_.erase(uri);
}

bool DocumentStore::change(const std::string& uri, const std::vector<TextChange>& changes,
                           long long version) {
  auto found = documents_.find(uri);
  if (found == documents_.end()) {
    return false;
  }
  for (const TextChange& change : changes) {
    applyChange(found->second.text, change);
  }
  found->second.version = version;
  return true;
}

const Document* DocumentStore::find(const std::string& uri) const {
  auto found = documents_.find(uri);
  return found == documents_.end() ? nullptr : &found->second;
}

void applyChange(std::string& text, const TextChange& change) {
  if (!change.range) {
    text = change.text;
    return;
  }
  TextPositions positions(text);
  std::uint32_t begin = positions.offsetOf(change.range->start);
  std::uint32_t end = std::max(begin, positions.offsetOf(change.range->end));
  text.replace(begin, end - begin, change.text);
}

} // namespace cncc::lsp
