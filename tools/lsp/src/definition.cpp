// Go to definition: where a name is declared, in the document or in a file
// it imports (the stdlib included); on an import, the module it loads.
#include "cncc/lsp/features.h"
#include "cncc/lsp/protocol_json.h"

namespace cncc::lsp {

namespace {

bool contains(frontend::SourceSpan span, std::uint32_t offset) {
  return span.begin <= offset && offset <= span.end;
}

std::optional<Location> importedModule(const Analysis& analysis, std::uint32_t offset) {
  for (const frontend::ItemPtr& item : analysis.module().items) {
    if (item->kind != frontend::ItemKind::Import) {
      continue;
    }
    const auto& import = frontend::as<frontend::ImportItem>(*item);
    if (contains(import.pathSpan, offset) && import.resolvedFile.valid()) {
      return Location{analysis.uriOf(import.resolvedFile), {}};
    }
  }
  return std::nullopt;
}

} // namespace

Json definition(const Analysis& analysis, Position position) {
  std::uint32_t offset = analysis.offsetOf(position);
  if (std::optional<Location> module = importedModule(analysis, offset)) {
    return toJson(*module);
  }
  const frontend::Reference* reference = analysis.program().referenceAt(analysis.file(), offset);
  if (reference == nullptr || reference->declaration == nullptr) {
    return nullptr;
  }
  std::optional<Location> location = analysis.locationOf(reference->declaration->span);
  return location ? toJson(*location) : Json(nullptr);
}

} // namespace cncc::lsp
