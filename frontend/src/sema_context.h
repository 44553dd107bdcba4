// State shared by the phases of semantic analysis (private to the front end).
#pragma once

#include "cncc/frontend/sema.h"

#include <map>
#include <set>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace cncc::frontend {

// A lexical scope: names to declarations, with a parent. The names are
// views: of the declarations' names and the syntax trees' (and builtins'),
// which the program keeps for longer than any scope.
class Scope {
public:
  explicit Scope(const Scope* parent = nullptr) : parent_(parent) {}
  const Declaration* find(std::string_view name) const;
  const Declaration* findLocal(std::string_view name) const;
  void add(std::string_view name, const Declaration* declaration) { names_[name] = declaration; }
  const Scope* parent() const { return parent_; }
  // Every name visible from here, innermost first (for suggestions).
  std::vector<std::string> visibleNames() const;

private:
  const Scope* parent_;
  // Hashed: a file scope holds thousands of names.
  std::unordered_map<std::string_view, const Declaration*> names_;
};

struct SemaContext {
  SemaContext(SourceManager& sources, DiagnosticEngine& diagnostics, CheckedProgram& program,
              const CheckOptions& options)
      : sources(sources), diagnostics(diagnostics), program(program), options(options) {}

  SourceManager& sources;
  DiagnosticEngine& diagnostics;
  CheckedProgram& program;
  const CheckOptions& options;

  Scope builtinScope;
  std::map<const Module*, Scope> fileScopes;
  // Functions that must not be evaluated (recursive, or broken).
  std::unordered_set<const Declaration*> invalidFunctions;
  // Declarations whose name was used somewhere (for unused-let).
  std::unordered_set<const Declaration*> usedDeclarations;
  // The constant or function item behind a declaration, and the file scope
  // it is checked in.
  std::unordered_map<const Declaration*, const Item*> itemOf;
  std::unordered_map<const Declaration*, const Scope*> itemScope;

  Declaration& declare(DeclarationKind kind, std::string name, SourceSpan span, Type type);
  // Takes what a context for part of the work on another thread collected:
  // its declarations, references, scopes and uses, and reports its
  // diagnostics here after this context's own.
  void adopt(SemaContext& other);
  void reference(SourceSpan span, const Declaration* declaration, bool isDefinition);
  Diagnostic* report(DiagnosticKind kind, SourceSpan span, std::string message);
  Declaration& mutableDeclaration(const Declaration* declaration) {
    return const_cast<Declaration&>(*declaration);
  }
};

// "; did you mean 'sweep'?" when a candidate is close to `name`, else "".
std::string suggestion(const std::string& name, const std::vector<std::string>& candidates);

// Loads the main module and, recursively, its imports (cycles reported).
void loadModules(SemaContext& context, FileId mainFile);

// Names, scopes and types of every module; records references.
void checkNamesAndTypes(SemaContext& context);

// Evaluates constants and, for each part, the body with its parameters at
// their defaults (or -D values), reporting what evaluation finds.
void evaluateProgram(SemaContext& context);

} // namespace cncc::frontend
