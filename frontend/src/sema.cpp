#include "cncc/frontend/sema.h"

#include "checker.h"
#include "part_evaluation.h"
#include "part_pipeline.h"
#include "sema_context.h"

#include <algorithm>
#include <cstring>
#include <fmt/format.h>
#include <numbers>

namespace cncc::frontend {

std::string_view declarationKindName(DeclarationKind kind) {
  switch (kind) {
  case DeclarationKind::Constant:
    return "constant";
  case DeclarationKind::Function:
    return "function";
  case DeclarationKind::PartParameter:
    return "part parameter";
  case DeclarationKind::FunctionParameter:
    return "function parameter";
  case DeclarationKind::Let:
    return "let";
  case DeclarationKind::LoopVariable:
    return "loop variable";
  case DeclarationKind::CurveParameter:
    return "curve parameter";
  case DeclarationKind::Builtin:
    return "builtin";
  case DeclarationKind::Part:
    return "part";
  }
  return "name";
}

namespace {

std::uint64_t read8(const char* data) {
  std::uint64_t word;
  std::memcpy(&word, data, sizeof word);
  return word;
}

std::uint64_t read4(const char* data) {
  std::uint32_t word;
  std::memcpy(&word, data, sizeof word);
  return word;
}

// A name's bytes as one number: all of them when it is shorter than 8 (the
// first and the last four overlap, or three of the bytes when shorter
// than 4), else its last 8.
std::uint64_t tailWord(std::string_view name) {
  std::size_t size = name.size();
  const char* data = name.data();
  if (size >= 8) {
    return read8(data + size - 8);
  }
  if (size >= 4) {
    return read4(data) << 32 | read4(data + size - 4);
  }
  if (size == 0) {
    return 0;
  }
  auto byte = [&](std::size_t i) { return std::uint64_t{static_cast<unsigned char>(data[i])}; };
  return byte(0) << 16 | byte(size / 2) << 8 | byte(size - 1);
}

std::uint64_t mix(std::uint64_t hash, std::uint64_t word) {
  hash = (hash ^ word) * 0x9E3779B97F4A7C15u;
  return hash ^ (hash >> 29);
}

} // namespace

// Eight bytes at a time; names are compared in full after a matching hash.
std::uint32_t Scope::hashOf(std::string_view name) {
  std::uint64_t hash = mix(0xC2B2AE3D27D4EB4Fu, name.size());
  std::size_t i = 0;
  for (; i + 8 < name.size(); i += 8) {
    hash = mix(hash, read8(name.data() + i));
  }
  hash = mix(hash, tailWord(name));
  return static_cast<std::uint32_t>(hash ^ (hash >> 32));
}

const Scope::Entry* Scope::scan(std::string_view name) const {
  for (std::size_t i = 0; i < count_; ++i) {
    if (sameName(few_[i].view(), name)) {
      return &few_[i];
    }
  }
  return nullptr;
}

const Scope::Entry* Scope::lookUp(std::string_view name, std::uint32_t hash) const {
  std::size_t mask = slots_.size() - 1;
  for (std::size_t slot = hash & mask;; slot = (slot + 1) & mask) {
    std::uint32_t index = slots_[slot];
    if (index == 0) {
      return nullptr;
    }
    const Entry& entry = many_[index - 1];
    if (entry.hash == hash && sameName(entry.view(), name)) {
      return &entry;
    }
  }
}

const Declaration* Scope::findLocal(std::string_view name) const {
  const Entry* entry = findEntry(name, indexed() ? hashOf(name) : 0);
  return entry == nullptr ? nullptr : entry->declaration;
}

const Declaration* Scope::find(std::string_view name) const {
  std::uint64_t bit = filterBit(name);
  std::uint32_t hash = 0;
  bool hashed = false;
  for (const Scope* scope = this; scope != nullptr; scope = scope->parent_) {
    const Entry* entry = nullptr;
    if (!scope->indexed()) {
      if ((scope->filter_ & bit) != 0) {
        entry = scope->scan(name);
      }
    } else {
      if (!hashed) {
        hash = hashOf(name);
        hashed = true;
      }
      entry = scope->lookUp(name, hash);
    }
    if (entry != nullptr) {
      return entry->declaration;
    }
  }
  return nullptr;
}

// A name added again is bound to the new declaration.
void Scope::add(std::string_view name, const Declaration* declaration) {
  std::uint32_t hash = indexed() ? hashOf(name) : 0;
  if (const Entry* existing = findEntry(name, hash)) {
    Entry* entries = indexed() ? many_.data() : few_.data();
    entries[existing - entries].declaration = declaration;
    return;
  }
  Entry entry{name.data(), static_cast<std::uint32_t>(name.size()), hash, declaration};
  if (!indexed()) {
    if (count_ < fewNames) {
      few_[count_++] = entry;
      filter_ |= filterBit(name);
      return;
    }
    many_.assign(few_.begin(), few_.end());
    many_.push_back(entry);
    ++count_;
    buildIndex(true);
    return;
  }
  many_.push_back(entry);
  ++count_;
  if (count_ * 4 > slots_.size()) {
    buildIndex(false);
  } else {
    insertSlot(static_cast<std::uint32_t>(count_ - 1));
  }
}

void Scope::insertSlot(std::uint32_t entry) {
  std::size_t mask = slots_.size() - 1;
  std::size_t slot = many_[entry].hash & mask;
  while (slots_[slot] != 0) {
    slot = (slot + 1) & mask;
  }
  slots_[slot] = entry + 1;
}

// Sizes the index for the entries in many_ and fills it, hashing the names
// the first time.
void Scope::buildIndex(bool hashNames) {
  std::size_t size = 16;
  while (size < count_ * 4) {
    size *= 2;
  }
  slots_.assign(size, 0);
  for (std::uint32_t i = 0; i < count_; ++i) {
    if (hashNames) {
      many_[i].hash = hashOf(many_[i].view());
    }
    insertSlot(i);
  }
}

std::vector<std::string> Scope::visibleNames() const {
  std::vector<std::string> names;
  for (const Scope* scope = this; scope != nullptr; scope = scope->parent_) {
    // Each scope's names in alphabetical order, so suggestions do not depend
    // on the hashing.
    std::size_t first = names.size();
    for (const Entry& entry : scope->entries()) {
      names.emplace_back(entry.view());
    }
    std::sort(names.begin() + static_cast<std::ptrdiff_t>(first), names.end());
  }
  return names;
}

Declaration& SemaContext::declare(DeclarationKind kind, std::string_view name, SourceSpan span,
                                  Type type) {
  Declaration& declaration = program.declarations.emplace_back();
  declaration.kind = kind;
  declaration.name = name;
  declaration.span = span;
  declaration.type = type;
  if (span.valid()) {
    program.references.push_back({span, &declaration, true});
  }
  return declaration;
}

void SemaContext::adopt(SemaContext& other) {
  CheckedProgram& from = other.program;
  program.declarations.splice(program.declarations.end(), from.declarations);
  program.references.insert(program.references.end(), from.references.begin(),
                            from.references.end());
  program.scopeExtents.insert(program.scopeExtents.end(), from.scopeExtents.begin(),
                              from.scopeExtents.end());
  usedDeclarations.merge(other.usedDeclarations);
}

Diagnostic* SemaContext::report(DiagnosticKind kind, SourceSpan span, std::string message) {
  return diagnostics.report(kind, span, std::move(message));
}

namespace {

std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> previous(b.size() + 1);
  std::vector<std::size_t> current(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) {
    previous[j] = j;
  }
  for (std::size_t i = 1; i <= a.size(); ++i) {
    current[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      std::size_t substitution = previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1);
      current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitution});
    }
    std::swap(previous, current);
  }
  return previous[b.size()];
}

} // namespace

std::string suggestion(const std::string& name, const std::vector<std::string>& candidates) {
  const std::string* best = nullptr;
  std::size_t bestDistance = name.size() / 3 + 1;
  for (const std::string& candidate : candidates) {
    std::size_t distance = editDistance(name, candidate);
    if (candidate != name && distance <= bestDistance &&
        (best == nullptr || distance < editDistance(name, *best))) {
      best = &candidate;
    }
  }
  return best == nullptr ? "" : fmt::format("; did you mean '{}'?", *best);
}

namespace {

void declareBuiltins(SemaContext& context) {
  for (const BuiltinInfo& builtin : builtinFunctions()) {
    Declaration& declaration =
        context.declare(DeclarationKind::Builtin, builtin.name, {}, Type::any());
    declaration.signature = builtin.signature;
    declaration.description = builtin.description;
    context.builtinScope.add(builtin.name, &declaration);
  }
  Declaration& pi = context.declare(DeclarationKind::Builtin, "pi", {}, Type::num());
  pi.value = Value::ofNumber(std::numbers::pi);
  pi.signature = "pi";
  pi.description = "the ratio of a circle's circumference to its diameter, 3.14159265...";
  context.builtinScope.add("pi", &pi);
}

void selectPart(SemaContext& context) {
  CheckedProgram& program = context.program;
  const CheckOptions& options = context.options;
  if (!options.partName.empty()) {
    for (const PartItem* part : program.parts) {
      if (part->name == options.partName) {
        program.selectedPart = part;
        return;
      }
    }
    std::vector<std::string> names;
    for (const PartItem* part : program.parts) {
      names.emplace_back(part->name);
    }
    context.report(DiagnosticKind::UnknownPart, {},
                   fmt::format("no part named '{}' in this file{}", options.partName,
                               suggestion(options.partName, names)));
    return;
  }
  if (program.parts.size() == 1) {
    program.selectedPart = program.parts.front();
    return;
  }
  if (!options.requirePart) {
    return;
  }
  if (program.parts.empty()) {
    const Module& main = program.modules.front();
    context.report(DiagnosticKind::NoPart, {main.file, 0, 0}, "this file has no 'part' to compile");
    return;
  }
  Diagnostic* diagnostic = context.report(
      DiagnosticKind::AmbiguousPart, program.parts[1]->nameSpan,
      fmt::format("this file has {} parts; choose one with -p NAME", program.parts.size()));
  for (const PartItem* part : program.parts) {
    context.diagnostics.addNote(diagnostic, part->nameSpan,
                                fmt::format("part '{}' is defined here", part->name));
  }
}

void checkDefines(SemaContext& context) {
  const CheckedProgram& program = context.program;
  for (const auto& [name, value] : context.options.defines) {
    bool found = false;
    for (const PartItem* part : program.parts) {
      if (program.selectedPart != nullptr && part != program.selectedPart) {
        continue;
      }
      for (const Parameter& parameter : part->parameters) {
        found |= parameter.name == name;
      }
    }
    if (!found) {
      context.report(DiagnosticKind::UnknownDefine, {},
                     fmt::format("-D {}={:g} names no parameter of the part", name, value));
    }
  }
}

} // namespace

CheckedProgram checkProgram(SourceManager& sources, FileId mainFile, const CheckOptions& options,
                            DiagnosticEngine& diagnostics) {
  CheckedProgram program;
  SemaContext context(sources, diagnostics, program, options);
  declareBuiltins(context);
  loadModules(context, mainFile);
  Checker checker(context);
  checker.checkItems();
  selectPart(context);
  checkDefines(context);
  Evaluator evaluator(context);
  evaluateConstants(evaluator);
  checkAndEvaluateParts(context, checker, evaluator);
  checker.checkImportedParts();
  diagnostics.sortByLocation();
  return program;
}

namespace {

bool contains(SourceSpan span, FileId file, std::uint32_t offset) {
  return span.file == file && span.begin <= offset && offset <= span.end;
}

} // namespace

const Reference* CheckedProgram::referenceAt(FileId file, std::uint32_t offset) const {
  const Reference* best = nullptr;
  for (const Reference& reference : references) {
    if (contains(reference.span, file, offset) &&
        (best == nullptr ||
         reference.span.end - reference.span.begin < best->span.end - best->span.begin)) {
      best = &reference;
    }
  }
  return best;
}

std::vector<const Declaration*> CheckedProgram::visibleAt(FileId file, std::uint32_t offset) const {
  std::vector<const Declaration*> visible;
  for (const Declaration& declaration : declarations) {
    bool fileLevel = declaration.kind == DeclarationKind::Constant ||
                     declaration.kind == DeclarationKind::Function;
    if (declaration.kind == DeclarationKind::Builtin ||
        (fileLevel && declaration.span.file == file)) {
      visible.push_back(&declaration);
    }
  }
  for (const ScopeExtent& extent : scopeExtents) {
    if (contains(extent.span, file, offset)) {
      visible.push_back(extent.declaration);
    }
  }
  return visible;
}

} // namespace cncc::frontend
