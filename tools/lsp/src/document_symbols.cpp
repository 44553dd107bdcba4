// Document symbols: the parts (with their parameters and lets), functions
// and constants of the document, for the editor's outline.
#include "cncc/lsp/features.h"
#include "cncc/lsp/protocol_json.h"

namespace cncc::lsp {

namespace {

using namespace frontend;

// The protocol's SymbolKind values used here.
enum class SymbolKind { Class = 5, Property = 7, Function = 12, Variable = 13, Constant = 14 };

Json symbol(const Analysis& analysis, std::string_view name, SymbolKind kind, SourceSpan range,
            SourceSpan selection, const std::string& detail) {
  Json result = {{"name", name},
                 {"kind", static_cast<int>(kind)},
                 {"range", toJson(analysis.rangeOf(range.to(selection)))},
                 {"selectionRange", toJson(analysis.rangeOf(selection))}};
  if (!detail.empty()) {
    result["detail"] = detail;
  }
  return result;
}

std::string valueDetail(const Declaration* declaration) {
  if (declaration == nullptr || !declaration->value || declaration->value->isError()) {
    return "";
  }
  return describeValue(*declaration->value);
}

void addLets(const Analysis& analysis, const Block& block, Json& children) {
  for (const StmtPtr& statement : block.statements) {
    if (statement->kind == StmtKind::Let) {
      const auto& let = as<LetStmt>(*statement);
      if (!let.name.empty()) {
        children.push_back(symbol(analysis, let.name, SymbolKind::Variable, let.span, let.nameSpan,
                                  valueDetail(let.declaration)));
      }
    } else if (statement->kind == StmtKind::For) {
      addLets(analysis, as<ForStmt>(*statement).body, children);
    } else if (statement->kind == StmtKind::If) {
      addLets(analysis, as<IfStmt>(*statement).thenBlock, children);
      addLets(analysis, as<IfStmt>(*statement).elseBlock, children);
    }
  }
}

Json partSymbol(const Analysis& analysis, const PartItem& part) {
  Json children = Json::array();
  for (const Parameter& parameter : part.parameters) {
    if (!parameter.name.empty()) {
      SourceSpan span = parameter.defaultValue ? parameter.nameSpan.to(parameter.defaultValue->span)
                                               : parameter.nameSpan;
      children.push_back(symbol(analysis, parameter.name, SymbolKind::Property, span,
                                parameter.nameSpan, valueDetail(parameter.declaration)));
    }
  }
  addLets(analysis, part.body, children);
  Json result = symbol(analysis, part.name, SymbolKind::Class, part.span, part.nameSpan, "part");
  result["children"] = std::move(children);
  return result;
}

std::optional<Json> itemSymbol(const Analysis& analysis, const Item& item) {
  switch (item.kind) {
  case ItemKind::Part: {
    const auto& part = as<PartItem>(item);
    return part.name.empty() ? std::nullopt : std::optional(partSymbol(analysis, part));
  }
  case ItemKind::Fn: {
    const auto& function = as<FnItem>(item);
    if (function.name.empty()) {
      return std::nullopt;
    }
    std::string signature = function.declaration ? function.declaration->signature : "";
    return symbol(analysis, function.name, SymbolKind::Function, function.span, function.nameSpan,
                  signature);
  }
  case ItemKind::Const: {
    const auto& constant = as<ConstItem>(item);
    if (constant.name.empty()) {
      return std::nullopt;
    }
    return symbol(analysis, constant.name, SymbolKind::Constant, constant.span, constant.nameSpan,
                  valueDetail(constant.declaration));
  }
  default:
    return std::nullopt;
  }
}

} // namespace

Json documentSymbols(const Analysis& analysis) {
  Json symbols = Json::array();
  for (const ItemPtr& item : analysis.module().items) {
    if (std::optional<Json> found = itemSymbol(analysis, *item)) {
      symbols.push_back(std::move(*found));
    }
  }
  return symbols;
}

} // namespace cncc::lsp
