// State shared by the phases of semantic analysis (private to the front end).
#pragma once

#include "cncc/frontend/sema.h"

#include <array>
#include <cstdint>
#include <cstring>
#include <map>
#include <set>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <vector>

namespace cncc::frontend {

// Whether two names are spelt the same: names are short, so this compares
// them eight or four bytes at a time (overlapping at the end) rather than
// calling memcmp.
inline bool sameName(std::string_view a, std::string_view b) {
  std::size_t size = a.size();
  if (size != b.size()) {
    return false;
  }
  const char* x = a.data();
  const char* y = b.data();
  auto same = [&]<typename Word>(Word, std::size_t at) {
    Word first;
    Word second;
    std::memcpy(&first, x + at, sizeof(Word));
    std::memcpy(&second, y + at, sizeof(Word));
    return first == second;
  };
  if (size >= 8) {
    for (std::size_t at = 0; at + 8 < size; at += 8) {
      if (!same(std::uint64_t{}, at)) {
        return false;
      }
    }
    return same(std::uint64_t{}, size - 8);
  }
  if (size >= 4) {
    return same(std::uint32_t{}, 0) && same(std::uint32_t{}, size - 4);
  }
  for (std::size_t at = 0; at < size; ++at) {
    if (x[at] != y[at]) {
      return false;
    }
  }
  return true;
}

// A lexical scope: names to declarations, with a parent. The names are
// views: of the declarations' names and the syntax trees' (and builtins'),
// which the program keeps for longer than any scope.
//
// Most scopes (a part's parameters, a block's lets, a loop variable, `t`)
// hold a few names: they are kept in the scope itself and searched in order.
// A scope with more (a file, the builtins) moves them to the heap with a hash
// index. A search through the scopes outwards hashes the name at most once.
class Scope {
public:
  explicit Scope(const Scope* parent = nullptr) : parent_(parent) {}
  const Declaration* find(std::string_view name) const;
  const Declaration* findLocal(std::string_view name) const;
  void add(std::string_view name, const Declaration* declaration);
  const Scope* parent() const { return parent_; }
  // Every name visible from here, innermost first (for suggestions).
  std::vector<std::string> visibleNames() const;

private:
  struct Entry {
    const char* name;
    std::uint32_t size;
    std::uint32_t hash; // set once the scope is indexed
    const Declaration* declaration;
    std::string_view view() const { return {name, size}; }
  };
  // Up to this many names a scope keeps them in itself, unindexed.
  static constexpr std::size_t fewNames = 8;
  static std::uint32_t hashOf(std::string_view name);
  // One of 64 bits, by a name's first letter and length: a scope of a few
  // names is searched only when its filter has the bit of the name.
  static std::uint64_t filterBit(std::string_view name) {
    unsigned first = name.empty() ? 0 : static_cast<unsigned char>(name[0]);
    return std::uint64_t{1} << ((first * 8 + name.size()) & 63);
  }
  bool indexed() const { return count_ > fewNames; }
  std::span<const Entry> entries() const {
    return indexed() ? std::span<const Entry>(many_) : std::span<const Entry>(few_.data(), count_);
  }
  const Entry* scan(std::string_view name) const;
  const Entry* lookUp(std::string_view name, std::uint32_t hash) const;
  // `hash` is used only when the scope is indexed.
  const Entry* findEntry(std::string_view name, std::uint32_t hash) const {
    if (indexed()) {
      return lookUp(name, hash);
    }
    return (filter_ & filterBit(name)) != 0 ? scan(name) : nullptr;
  }
  void insertSlot(std::uint32_t entry);
  void buildIndex(bool hashNames);

  const Scope* parent_;
  std::size_t count_ = 0;
  std::uint64_t filter_ = 0; // the filter bits of the names in few_
  std::array<Entry, fewNames> few_{};
  std::vector<Entry> many_;
  // Open addressing with linear probing: each slot holds an index in many_
  // plus one, or 0 when free; a power of two in size, at most a quarter full
  // (a search for a name not there, the common case, stops sooner).
  std::vector<std::uint32_t> slots_;
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
  // Lets whose name was used somewhere (for unused-let).
  std::unordered_set<const Declaration*> usedDeclarations;
  // The constant or function item behind a declaration, and the file scope
  // it is checked in (none when its name redefines another).
  struct FileItem {
    const Item* item = nullptr;
    const Scope* scope = nullptr;
  };
  std::unordered_map<const Declaration*, FileItem> fileItems;

  Declaration& declare(DeclarationKind kind, std::string_view name, SourceSpan span, Type type);
  // Takes what a context for part of the work on another thread collected:
  // its declarations, references, scopes and uses (its diagnostics are the
  // caller's to report, in the order the work would have reported them).
  void adopt(SemaContext& other);
  void reference(SourceSpan span, const Declaration* declaration, bool isDefinition) {
    // Only a let can be reported unused.
    if (declaration->kind == DeclarationKind::Let) {
      usedDeclarations.insert(declaration);
    }
    if (span.valid()) {
      program.references.push_back({span, declaration, isDefinition});
    }
  }
  Diagnostic* report(DiagnosticKind kind, SourceSpan span, std::string message);
  Declaration& mutableDeclaration(const Declaration* declaration) {
    return const_cast<Declaration&>(*declaration);
  }
};

// "; did you mean 'sweep'?" when a candidate is close to `name`, else "".
std::string suggestion(const std::string& name, const std::vector<std::string>& candidates);

// Loads the main module and, recursively, its imports (cycles reported).
void loadModules(SemaContext& context, FileId mainFile);

} // namespace cncc::frontend
