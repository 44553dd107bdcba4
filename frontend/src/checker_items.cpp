// The checker's file level: declarations of constants and functions, file
// scopes with imported names, and checking items on first use.
#include "checker.h"

#include <algorithm>
#include <deque>
#include <fmt/format.h>
#include <string_view>
#include <unordered_map>

namespace cncc::frontend {

// Constants and functions first, so that parts, which only use them, can be
// checked one by one, on two threads and each just before it is run.
void Checker::checkItems() {
  for (Module& module : context_.program.modules) {
    declareItems(module);
  }
  for (Module& module : context_.program.modules) {
    buildFileScope(module);
  }
  for (Module& module : context_.program.modules) {
    checkConstantsAndFunctions(module);
  }
}

void Checker::checkImportedParts() {
  std::deque<Module>& modules = context_.program.modules;
  for (std::size_t i = 1; i < modules.size(); ++i) {
    Module& module = modules[i];
    const Scope& scope = context_.fileScopes.at(&module);
    for (ItemPtr& item : module.items) {
      if (item->kind == ItemKind::Part) {
        checkPart(as<PartItem>(*item), scope);
      }
    }
  }
}

void Checker::declareItems(Module& module) {
  context_.fileItems.reserve(context_.fileItems.size() + module.items.size());
  for (ItemPtr& item : module.items) {
    if (item->kind == ItemKind::Const) {
      auto& constant = as<ConstItem>(*item);
      if (!constant.name.empty()) {
        Declaration& declaration = context_.declare(DeclarationKind::Constant, constant.name,
                                                    constant.nameSpan, Type::error());
        constant.declaration = &declaration;
        context_.fileItems[&declaration].item = &constant;
      }
    } else if (item->kind == ItemKind::Fn) {
      auto& function = as<FnItem>(*item);
      if (!function.name.empty()) {
        Declaration& declaration = context_.declare(DeclarationKind::Function, function.name,
                                                    function.nameSpan, Type::error());
        declaration.function = &function;
        declaration.signature = functionSignature(function);
        function.declaration = &declaration;
        context_.fileItems[&declaration].item = &function;
      }
    } else if (item->kind == ItemKind::Part && &module == &context_.program.modules.front()) {
      auto& part = as<PartItem>(*item);
      context_.program.parts.push_back(&part);
    }
  }
}

std::string Checker::functionSignature(const FnItem& function) {
  std::size_t length = function.name.size() + 2;
  for (const Parameter& parameter : function.parameters) {
    length += parameter.name.size() + 2;
  }
  std::string text;
  text.reserve(length);
  text.append(function.name).push_back('(');
  for (std::size_t i = 0; i < function.parameters.size(); ++i) {
    if (i != 0) {
      text.append(", ");
    }
    text.append(function.parameters[i].name);
  }
  text.push_back(')');
  return text;
}

const Declaration* Checker::itemDeclaration(const Item& item) {
  if (item.kind == ItemKind::Const) {
    return as<ConstItem>(item).declaration;
  }
  if (item.kind == ItemKind::Fn) {
    return as<FnItem>(item).declaration;
  }
  return nullptr;
}

void Checker::buildFileScope(Module& module) {
  Scope& scope = context_.fileScopes.emplace(&module, Scope(&context_.builtinScope)).first->second;
  // Imported names first, so the file's own definitions take precedence.
  std::map<std::string, const ImportItem*> importedFrom;
  for (ItemPtr& item : module.items) {
    if (item->kind == ItemKind::Import && as<ImportItem>(*item).resolvedFile.valid()) {
      addImportedNames(scope, as<ImportItem>(*item), importedFrom);
    }
  }
  // Views of the items' and declarations' names, which outlive the map.
  std::unordered_map<std::string_view, const Item*> seen;
  seen.reserve(module.items.size());
  for (ItemPtr& item : module.items) {
    const Declaration* declaration = itemDeclaration(*item);
    std::string_view name = item->kind == ItemKind::Part
                                ? std::string_view(as<PartItem>(*item).name)
                            : declaration != nullptr ? std::string_view(declaration->name)
                                                     : std::string_view();
    if (name.empty()) {
      continue;
    }
    SourceSpan nameSpan =
        item->kind == ItemKind::Part ? as<PartItem>(*item).nameSpan : declaration->span;
    if (auto previous = seen.find(name); previous != seen.end()) {
      Diagnostic* diagnostic = context_.report(DiagnosticKind::Redefinition, nameSpan,
                                               fmt::format("'{}' is already defined", name));
      context_.diagnostics.addNote(diagnostic, previous->second->span,
                                   "the first definition is here");
      continue;
    }
    seen.emplace(name, item.get());
    if (declaration == nullptr) {
      continue; // parts are not values
    }
    if (const Declaration* builtin = context_.builtinScope.findLocal(name)) {
      context_.report(DiagnosticKind::Redefinition, nameSpan,
                      fmt::format("'{}' is a builtin {} and cannot be redefined", name,
                                  builtin->name == "pi" ? "constant" : "function"));
      continue;
    }
    scope.add(declaration->name, declaration); // `name` is a copy
    context_.fileItems[declaration].scope = &scope;
  }
}

void Checker::addImportedNames(Scope& scope, const ImportItem& import,
                               std::map<std::string, const ImportItem*>& importedFrom) {
  for (const Module& imported : context_.program.modules) {
    if (imported.file != import.resolvedFile) {
      continue;
    }
    for (const ItemPtr& item : imported.items) {
      const Declaration* declaration = itemDeclaration(*item);
      if (declaration == nullptr) {
        continue;
      }
      if (auto previous = importedFrom.find(declaration->name);
          previous != importedFrom.end() && previous->second != &import) {
        Diagnostic* diagnostic =
            context_.report(DiagnosticKind::Redefinition, import.pathSpan,
                            fmt::format("'{}' is defined by both \"{}\" and \"{}\"",
                                        declaration->name, previous->second->path, import.path));
        context_.diagnostics.addNote(diagnostic, previous->second->pathSpan,
                                     "the first import is here");
        continue;
      }
      importedFrom[declaration->name] = &import;
      scope.add(declaration->name, declaration);
    }
  }
}

void Checker::checkConstantsAndFunctions(Module& module) {
  const Scope& scope = context_.fileScopes.at(&module);
  for (ItemPtr& item : module.items) {
    if (const Declaration* declaration = itemDeclaration(*item)) {
      ensureChecked(declaration);
    } else if (item->kind == ItemKind::Fn || item->kind == ItemKind::Const) {
      checkUnnamedItem(*item, scope);
    }
  }
}

// An item whose name did not parse: still check its body for the editor.
void Checker::checkUnnamedItem(Item& item, const Scope& scope) {
  if (item.kind == ItemKind::Const) {
    checkExpression(*as<ConstItem>(item).value, scope);
  }
}

// Constants and functions are checked on first use, so they may be used
// before the line that defines them; a cycle is an error.
void Checker::ensureChecked(const Declaration* declaration) {
  if (stateOf(declaration) != ItemState::Unchecked) {
    return;
  }
  ItemState& state = states_[declaration];
  state = ItemState::InProgress;
  const SemaContext::FileItem& fileItem = context_.fileItems.at(declaration);
  const Item* item = fileItem.item;
  Scope detached(&context_.builtinScope);
  const Scope& scope = fileItem.scope != nullptr ? *fileItem.scope : detached;
  Declaration& mutableDeclaration = context_.mutableDeclaration(declaration);
  if (item->kind == ItemKind::Const) {
    auto& constant = const_cast<ConstItem&>(as<ConstItem>(*item));
    mutableDeclaration.type = checkExpression(*constant.value, scope);
  } else {
    auto& function = const_cast<FnItem&>(as<FnItem>(*item));
    mutableDeclaration.type = checkFunction(function, scope);
  }
  state = ItemState::Checked;
}

Type Checker::checkFunction(FnItem& function, const Scope& fileScope) {
  Scope scope(&fileScope);
  for (Parameter& parameter : function.parameters) {
    if (scope.findLocal(parameter.name) != nullptr) {
      context_.report(DiagnosticKind::Redefinition, parameter.nameSpan,
                      fmt::format("parameter '{}' is declared twice", parameter.name));
      continue;
    }
    if (parameter.defaultValue) {
      context_.report(DiagnosticKind::TypeMismatch, parameter.defaultValue->span,
                      "function parameters have no defaults; only part parameters do");
    }
    Declaration& declaration = context_.declare(DeclarationKind::FunctionParameter, parameter.name,
                                                parameter.nameSpan, Type::any());
    parameter.declaration = &declaration;
    scope.add(parameter.name, &declaration);
    context_.program.scopeExtents.push_back({function.body->span, &declaration});
  }
  return checkExpression(*function.body, scope);
}

} // namespace cncc::frontend
