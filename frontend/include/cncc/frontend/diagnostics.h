// The diagnostics engine: every phase reports here and carries on.
// Diagnostics are collected, de-duplicated and capped; nothing is fatal.
#pragma once

#include "cncc/frontend/source_manager.h"

#include <cstddef>
#include <deque>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::frontend {

enum class Severity { Note, Warning, Error };

enum class DiagnosticKind {
#define CNCC_DIAGNOSTIC(identifier, name, severity) identifier,
#include "cncc/frontend/diagnostic_kinds.def"
};

// The stable name printed in brackets, such as "weights-count".
std::string_view diagnosticName(DiagnosticKind kind);
Severity diagnosticSeverity(DiagnosticKind kind);
// Every kind, in declaration order (for the every-kind-is-tested check).
std::vector<DiagnosticKind> allDiagnosticKinds();

struct DiagnosticNote {
  SourceSpan span;
  std::string message;
};

struct Diagnostic {
  DiagnosticKind kind;
  Severity severity;
  SourceSpan span; // may be invalid for command-line problems
  std::string message;
  std::vector<DiagnosticNote> notes;
};

class DiagnosticEngine {
public:
  // Stops recording errors after this many (a "too-many-errors" note is
  // added once); zero means no limit.
  explicit DiagnosticEngine(std::size_t errorLimit = 50) : errorLimit_(errorLimit) {}

  // Records a diagnostic and returns it so a note can be attached, or
  // nullptr when it was dropped (duplicate, or past the error limit).
  Diagnostic* report(DiagnosticKind kind, SourceSpan span, std::string message);
  void addNote(Diagnostic* diagnostic, SourceSpan span, std::string message);
  // Reports `other`'s diagnostics [first, last) here, in order, with their
  // notes.
  void reportRange(const DiagnosticEngine& other, std::size_t first, std::size_t last);

  // A deque, so a Diagnostic* from report() stays valid while more arrive.
  const std::deque<Diagnostic>& diagnostics() const { return diagnostics_; }
  std::size_t errorCount() const { return errorCount_; }
  bool hasErrors() const { return errorCount_ > 0; }
  // Orders diagnostics by file and position (phases report in their own
  // order; users read top to bottom). Ones without a location come first.
  void sortByLocation();
  void clear();

private:
  std::deque<Diagnostic> diagnostics_;
  std::size_t errorLimit_;
  std::size_t errorCount_ = 0;
  bool limitReported_ = false;
};

struct RenderOptions {
  bool colour = false;
};

// `file:line:col: error: message [name]`, the source line, and `^~~~`
// under the span; notes follow the same shape.
std::string renderText(const Diagnostic& diagnostic, const SourceManager& sources,
                       const RenderOptions& options = {});
// One JSON object on one line (for tools and the language server).
std::string renderJson(const Diagnostic& diagnostic, const SourceManager& sources);

} // namespace cncc::frontend
