// libFuzzer entry point for the front end: the lexer, the parser and the
// semantic checker (imports, names, types, compile-time evaluation) run on
// arbitrary bytes, and the diagnostics they report are rendered as text and
// JSON.
//
// The contract under test (LANGUAGE.md, "Errors"): no input, however
// malformed, crashes the compiler. With AddressSanitizer and
// UndefinedBehaviorSanitizer any memory error, overflow or leak is a crash;
// the checks below add the front end's own invariants (spans inside their
// file, a token stream that ends in EndOfFile, the error cap honoured).
//
// Imports stay inside the repository: the input is placed, in memory, in the
// standard library's directory and the standard library is the only import
// path, and an input whose imports are absolute or climb with ".." skips the
// semantic checker (it is still lexed and parsed), so a run never reads
// files of the machine it runs on.
#include "cncc/frontend/diagnostics.h"
#include "cncc/frontend/lexer.h"
#include "cncc/frontend/parser.h"
#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"
#include "contained_imports.h"

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

namespace {

using namespace cncc::frontend;

// Where the input pretends to live; no file of this name exists, so an
// input that imports itself by name finds nothing.
constexpr const char* inputPath = CNCC_STDLIB_DIR "/fuzz-input.cdl";
constexpr std::size_t errorLimit = 50;

[[noreturn]] void fail(const char* what) {
  std::fprintf(stderr, "frontend_fuzzer: invariant broken: %s\n", what);
  std::abort();
}

// A span is either invalid (no file) or lies inside its file's text.
void checkSpan(const SourceManager& sources, SourceSpan span, const char* what) {
  if (!span.valid()) {
    return;
  }
  const SourceFile& file = sources.file(span.file);
  if (span.begin > span.end || span.end > file.text().size()) {
    fail(what);
  }
}

void checkTokens(const SourceManager& sources, const std::vector<Token>& tokens) {
  if (tokens.empty() || tokens.back().kind != TokenKind::EndOfFile) {
    fail("the token stream does not end in EndOfFile");
  }
  std::uint32_t previousEnd = 0;
  for (const Token& token : tokens) {
    checkSpan(sources, token.span, "token span outside its file");
    if (token.span.begin < previousEnd) {
      fail("tokens overlap or go backwards");
    }
    previousEnd = token.span.end;
  }
}

void checkDiagnostics(const SourceManager& sources, const DiagnosticEngine& diagnostics) {
  std::size_t errors = 0;
  for (const Diagnostic& diagnostic : diagnostics.diagnostics()) {
    checkSpan(sources, diagnostic.span, "diagnostic span outside its file");
    for (const DiagnosticNote& note : diagnostic.notes) {
      checkSpan(sources, note.span, "note span outside its file");
    }
    errors += diagnostic.severity == Severity::Error ? 1 : 0;
    // Rendering reads the quoted line and draws the caret from the span.
    std::string text = renderText(diagnostic, sources);
    std::string json = renderJson(diagnostic, sources);
    if (text.empty() || json.empty()) {
      fail("a diagnostic rendered as nothing");
    }
  }
  if (errors > errorLimit) {
    fail("more errors recorded than the engine's limit");
  }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size);

  // Lexer and parser on their own, with comments kept as the formatter asks.
  bool importsContained = true;
  {
    SourceManager sources;
    FileId file = sources.addFile(inputPath, text);
    DiagnosticEngine diagnostics(errorLimit);
    std::vector<SourceSpan> comments;
    std::vector<Token> tokens = lex(sources, file, diagnostics, &comments);
    checkTokens(sources, tokens);
    for (SourceSpan comment : comments) {
      checkSpan(sources, comment, "comment span outside its file");
    }
    for (std::size_t i = 0; i + 1 < tokens.size(); ++i) {
      if (tokens[i].kind == TokenKind::KwImport && tokens[i + 1].kind == TokenKind::String &&
          !cncc::fuzz::isContainedImport(tokens[i + 1].text)) {
        importsContained = false;
      }
    }
    Module module = parse(std::move(tokens), file, diagnostics);
    for (const ItemPtr& item : module.items) {
      checkSpan(sources, item->span, "item span outside its file");
    }
    checkDiagnostics(sources, diagnostics);
  }
  if (!importsContained) {
    return 0;
  }

  // The whole front end, as `cncc check` runs it or, for inputs of odd
  // length, as compiling one part does (a part must be chosen); then the
  // editor's queries.
  SourceManager sources;
  FileId file = sources.addFile(inputPath, text);
  DiagnosticEngine diagnostics(errorLimit);
  CheckOptions options;
  options.importPaths = {CNCC_STDLIB_DIR};
  options.requirePart = size % 2 == 1;
  CheckedProgram program = checkProgram(sources, file, options, diagnostics);
  checkDiagnostics(sources, diagnostics);
  if (program.modules.empty() || program.modules.front().file != file) {
    fail("the checked program does not start with the main module");
  }
  for (std::uint32_t offset :
       {std::uint32_t{0}, static_cast<std::uint32_t>(size / 2), static_cast<std::uint32_t>(size)}) {
    if (const Reference* reference = program.referenceAt(file, offset)) {
      checkSpan(sources, reference->span, "reference span outside its file");
    }
    for (const Declaration* declaration : program.visibleAt(file, offset)) {
      checkSpan(sources, declaration->span, "declaration span outside its file");
    }
  }
  return 0;
}
