// Front-end diagnostics as the protocol's Diagnostic objects: the same
// message, span and stable name (as the `code`) that `cncc check` prints.
#include "cncc/lsp/features.h"
#include "cncc/lsp/protocol_json.h"

#include <fmt/format.h>

namespace cncc::lsp {

namespace {

using frontend::Diagnostic;
using frontend::SourceSpan;

int severityCode(frontend::Severity severity) {
  switch (severity) {
  case frontend::Severity::Error:
    return 1;
  case frontend::Severity::Warning:
    return 2;
  case frontend::Severity::Note:
    return 3; // Information
  }
  return 1;
}

// Where a diagnostic from an imported file is shown in the document: the
// import that loads that file, or failing that the first import.
SourceSpan importSpanFor(const Analysis& analysis, frontend::FileId file) {
  SourceSpan first;
  for (const frontend::ItemPtr& item : analysis.module().items) {
    if (item->kind != frontend::ItemKind::Import) {
      continue;
    }
    const auto& import = frontend::as<frontend::ImportItem>(*item);
    if (import.resolvedFile == file) {
      return import.pathSpan;
    }
    if (!first.valid()) {
      first = import.pathSpan;
    }
  }
  return first.valid() ? first : SourceSpan{analysis.file(), 0, 0};
}

Json relatedInformation(const Analysis& analysis, const Diagnostic& diagnostic) {
  Json related = Json::array();
  for (const frontend::DiagnosticNote& note : diagnostic.notes) {
    if (std::optional<Location> location = analysis.locationOf(note.span)) {
      related.push_back({{"location", toJson(*location)}, {"message", note.message}});
    }
  }
  return related;
}

Json diagnosticJson(const Analysis& analysis, const Diagnostic& diagnostic) {
  SourceSpan span = diagnostic.span;
  std::string message = diagnostic.message;
  Json related = relatedInformation(analysis, diagnostic);
  if (!span.valid()) {
    span = {analysis.file(), 0, 0};
  } else if (span.file != analysis.file()) {
    const frontend::SourceFile& source = analysis.sources().file(span.file);
    frontend::LineColumn where = source.lineColumn(span.begin);
    message = fmt::format("in {}:{}:{}: {}", source.path(), where.line, where.column, message);
    if (std::optional<Location> location = analysis.locationOf(span)) {
      related.insert(related.begin(),
                     Json{{"location", toJson(*location)}, {"message", diagnostic.message}});
    }
    span = importSpanFor(analysis, span.file);
  }
  Json result = {{"range", toJson(analysis.rangeOf(span))},
                 {"severity", severityCode(diagnostic.severity)},
                 {"code", std::string(frontend::diagnosticName(diagnostic.kind))},
                 {"source", "cncc"},
                 {"message", message}};
  if (!related.empty()) {
    result["relatedInformation"] = std::move(related);
  }
  return result;
}

} // namespace

Json publishDiagnosticsParams(const Analysis& analysis, long long version) {
  Json diagnostics = Json::array();
  for (const Diagnostic& diagnostic : analysis.diagnostics()) {
    diagnostics.push_back(diagnosticJson(analysis, diagnostic));
  }
  return {{"uri", analysis.uri()}, {"version", version}, {"diagnostics", std::move(diagnostics)}};
}

} // namespace cncc::lsp
