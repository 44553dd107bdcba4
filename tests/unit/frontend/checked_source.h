// A CDL text checked by the front end, for the unit tests: the program, its
// diagnostics by name, and the declarations by name.
#pragma once

#include "cncc/frontend/sema.h"

#include <memory>
#include <string>
#include <vector>

namespace cncc::frontend::test_support {

struct Checked {
  SourceManager sources;
  DiagnosticEngine diagnostics{0};
  CheckedProgram program;
  FileId file;

  std::vector<std::string> names() const {
    std::vector<std::string> result;
    for (const Diagnostic& diagnostic : diagnostics.diagnostics()) {
      result.emplace_back(diagnosticName(diagnostic.kind));
    }
    return result;
  }
  const Declaration* find(const std::string& name) const {
    for (const Declaration& declaration : program.declarations) {
      if (declaration.name == name && declaration.kind != DeclarationKind::Builtin) {
        return &declaration;
      }
    }
    return nullptr;
  }
};

// `text` checked as test.cdl, the standard library on the import path.
inline std::unique_ptr<Checked> check(const std::string& text, CheckOptions options = {}) {
  auto checked = std::make_unique<Checked>();
  checked->file = checked->sources.addFile("test.cdl", text);
  options.importPaths.push_back(CNCC_STDLIB_DIR);
  checked->program = checkProgram(checked->sources, checked->file, options, checked->diagnostics);
  return checked;
}

// A part around one body, with a tool and a feed so cuts are complete.
inline std::string part(const std::string& body, const std::string& parameters = "") {
  return "part p(" + parameters + ") {\n  tool 1 diameter=6 feed=200\n  safe z=5\n" + body +
         "\n}\n";
}

} // namespace cncc::frontend::test_support
