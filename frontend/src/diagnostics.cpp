#include "cncc/frontend/diagnostics.h"

#include <algorithm>
#include <fmt/format.h>

namespace cncc::frontend {

namespace {

struct KindInfo {
  std::string_view name;
  Severity severity;
};

constexpr KindInfo kindTable[] = {
#define CNCC_DIAGNOSTIC(identifier, name, severity) {name, Severity::severity},
#include "cncc/frontend/diagnostic_kinds.def"
};

std::string_view severityWord(Severity severity) {
  switch (severity) {
  case Severity::Note:
    return "note";
  case Severity::Warning:
    return "warning";
  case Severity::Error:
    return "error";
  }
  return "error";
}

bool sameDiagnostic(const Diagnostic& a, DiagnosticKind kind, SourceSpan span,
                    const std::string& message) {
  return a.kind == kind && a.span == span && a.message == message;
}

} // namespace

std::string_view diagnosticName(DiagnosticKind kind) {
  return kindTable[static_cast<int>(kind)].name;
}

Severity diagnosticSeverity(DiagnosticKind kind) {
  return kindTable[static_cast<int>(kind)].severity;
}

std::vector<DiagnosticKind> allDiagnosticKinds() {
  std::vector<DiagnosticKind> kinds;
  for (std::size_t i = 0; i < std::size(kindTable); ++i) {
    kinds.push_back(static_cast<DiagnosticKind>(i));
  }
  return kinds;
}

Diagnostic* DiagnosticEngine::report(DiagnosticKind kind, SourceSpan span, std::string message) {
  Severity severity = diagnosticSeverity(kind);
  if (severity == Severity::Error && errorLimit_ != 0 && errorCount_ >= errorLimit_) {
    if (!limitReported_) {
      limitReported_ = true;
      diagnostics_.push_back({DiagnosticKind::TooManyErrors,
                              Severity::Note,
                              {},
                              fmt::format("too many errors; stopping after {}", errorLimit_),
                              {}});
    }
    return nullptr;
  }
  auto duplicate = std::find_if(diagnostics_.begin(), diagnostics_.end(), [&](const auto& d) {
    return sameDiagnostic(d, kind, span, message);
  });
  if (duplicate != diagnostics_.end()) {
    return nullptr;
  }
  if (severity == Severity::Error) {
    ++errorCount_;
  }
  diagnostics_.push_back({kind, severity, span, std::move(message), {}});
  return &diagnostics_.back();
}

void DiagnosticEngine::addNote(Diagnostic* diagnostic, SourceSpan span, std::string message) {
  if (diagnostic != nullptr) {
    diagnostic->notes.push_back({span, std::move(message)});
  }
}

void DiagnosticEngine::reportRange(const DiagnosticEngine& other, std::size_t first,
                                   std::size_t last) {
  for (std::size_t i = first; i < last; ++i) {
    const Diagnostic& reported = other.diagnostics()[i];
    Diagnostic* diagnostic = report(reported.kind, reported.span, reported.message);
    for (const DiagnosticNote& note : reported.notes) {
      addNote(diagnostic, note.span, note.message);
    }
  }
}

void DiagnosticEngine::sortByLocation() {
  std::stable_sort(diagnostics_.begin(), diagnostics_.end(), [](const auto& a, const auto& b) {
    if (a.kind == DiagnosticKind::TooManyErrors || b.kind == DiagnosticKind::TooManyErrors) {
      return b.kind == DiagnosticKind::TooManyErrors && a.kind != DiagnosticKind::TooManyErrors;
    }
    return std::pair(a.span.file.index, a.span.begin) < std::pair(b.span.file.index, b.span.begin);
  });
}

void DiagnosticEngine::clear() {
  diagnostics_.clear();
  errorCount_ = 0;
  limitReported_ = false;
}

namespace {

const char* severityColour(Severity severity) {
  switch (severity) {
  case Severity::Note:
    return "\033[1;36m";
  case Severity::Warning:
    return "\033[1;35m";
  case Severity::Error:
    return "\033[1;31m";
  }
  return "";
}

// Expands tabs so the caret line lines up with the quoted source line.
std::string expandTabs(std::string_view line) {
  std::string result;
  for (char c : line) {
    if (c == '\t') {
      result.append(4 - result.size() % 4, ' ');
    } else {
      result.push_back(c);
    }
  }
  return result;
}

std::size_t displayColumn(std::string_view line, std::size_t byteColumn) {
  std::size_t column = 0;
  for (std::size_t i = 0; i < byteColumn && i < line.size(); ++i) {
    column = line[i] == '\t' ? column + 4 - column % 4 : column + 1;
  }
  return column;
}

void renderOne(std::string& out, Severity severity, SourceSpan span, std::string_view message,
               std::string_view name, const SourceManager& sources, const RenderOptions& options) {
  const char* bold = options.colour ? "\033[1m" : "";
  const char* reset = options.colour ? "\033[0m" : "";
  const char* colour = options.colour ? severityColour(severity) : "";
  std::string suffix = name.empty() ? "" : fmt::format(" [{}]", name);
  if (!span.valid()) {
    out += fmt::format("{}cncc:{} {}{}:{} {}{}{}\n", bold, reset, colour, severityWord(severity),
                       reset, bold, message, reset + suffix);
    return;
  }
  const SourceFile& file = sources.file(span.file);
  LineColumn begin = file.lineColumn(span.begin);
  out +=
      fmt::format("{}{}:{}:{}:{} {}{}:{} {}{}{}{}\n", bold, file.path(), begin.line, begin.column,
                  reset, colour, severityWord(severity), reset, bold, message, reset, suffix);
  std::string_view line = file.lineText(begin.line);
  out += expandTabs(line);
  out += '\n';
  std::size_t caretColumn = displayColumn(line, begin.column - 1);
  LineColumn end = file.lineColumn(span.end);
  std::size_t endByte = end.line == begin.line ? end.column - 1 : line.size();
  std::size_t endColumn = displayColumn(line, endByte);
  std::size_t width = endColumn > caretColumn ? endColumn - caretColumn : 1;
  out += std::string(caretColumn, ' ');
  out += options.colour ? "\033[1;32m" : "";
  out += '^';
  out += std::string(width - 1, '~');
  out += reset;
  out += '\n';
}

void appendJsonString(std::string& out, std::string_view text) {
  out += '"';
  for (unsigned char c : text) {
    switch (c) {
    case '"':
      out += "\\\"";
      break;
    case '\\':
      out += "\\\\";
      break;
    case '\n':
      out += "\\n";
      break;
    case '\t':
      out += "\\t";
      break;
    case '\r':
      out += "\\r";
      break;
    default:
      if (c < 0x20) {
        out += fmt::format("\\u{:04x}", c);
      } else {
        out += static_cast<char>(c);
      }
    }
  }
  out += '"';
}

void appendJsonRange(std::string& out, SourceSpan span, const SourceManager& sources) {
  if (!span.valid()) {
    out += "null";
    return;
  }
  const SourceFile& file = sources.file(span.file);
  LineColumn begin = file.lineColumn(span.begin);
  LineColumn end = file.lineColumn(span.end);
  out += "{\"file\":";
  appendJsonString(out, file.path());
  out += fmt::format(",\"line\":{},\"column\":{},\"endLine\":{},\"endColumn\":{},\"offset\":{},"
                     "\"endOffset\":{}}}",
                     begin.line, begin.column, end.line, end.column, span.begin, span.end);
}

} // namespace

std::string renderText(const Diagnostic& diagnostic, const SourceManager& sources,
                       const RenderOptions& options) {
  std::string out;
  renderOne(out, diagnostic.severity, diagnostic.span, diagnostic.message,
            diagnosticName(diagnostic.kind), sources, options);
  for (const DiagnosticNote& note : diagnostic.notes) {
    renderOne(out, Severity::Note, note.span, note.message, "", sources, options);
  }
  return out;
}

std::string renderJson(const Diagnostic& diagnostic, const SourceManager& sources) {
  std::string out = "{\"severity\":";
  appendJsonString(out, severityWord(diagnostic.severity));
  out += ",\"name\":";
  appendJsonString(out, diagnosticName(diagnostic.kind));
  out += ",\"message\":";
  appendJsonString(out, diagnostic.message);
  out += ",\"range\":";
  appendJsonRange(out, diagnostic.span, sources);
  out += ",\"notes\":[";
  for (std::size_t i = 0; i < diagnostic.notes.size(); ++i) {
    out += i == 0 ? "{\"message\":" : ",{\"message\":";
    appendJsonString(out, diagnostic.notes[i].message);
    out += ",\"range\":";
    appendJsonRange(out, diagnostic.notes[i].span, sources);
    out += '}';
  }
  out += "]}";
  return out;
}

} // namespace cncc::frontend
