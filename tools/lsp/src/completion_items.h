// The completion items of each context (private to the language server):
// completion.cpp decides the context from the text before the cursor, these
// build the items.
#pragma once

#include "cncc/lsp/features.h"

#include <string>
#include <vector>

namespace cncc::lsp {

// The protocol's CompletionItemKind values used here.
enum class ItemKind {
  Function = 3,
  Variable = 6,
  Module = 9,
  Property = 10,
  Keyword = 14,
  Snippet = 15,
  EnumMember = 20,
  Constant = 21,
};

// Builds CompletionItems; snippet text falls back to plain text for clients
// that do not expand snippets.
class ItemBuilder {
public:
  explicit ItemBuilder(bool snippets) : snippets_(snippets) {}

  void add(std::string label, ItemKind kind, std::string detail = {},
           std::string documentation = {});
  // `snippet` uses ${1:placeholder}; `plain` is inserted without snippets.
  void addSnippet(std::string label, ItemKind kind, std::string snippet, std::string plain,
                  std::string detail = {}, std::string documentation = {});
  // An item that replaces `range` with `text` (used inside import strings).
  void addReplacement(std::string label, ItemKind kind, Range range, std::string text);

  Json list() const;

private:
  bool snippets_;
  Json items_ = Json::array();
};

// `units`, `tool`, `let`, `curve`, ... at the start of a statement.
void addStatementKeywords(ItemBuilder& items);
// `part`, `fn`, `const`, `import` at the start of an item.
void addItemKeywords(ItemBuilder& items);
// `if`, `then`, `else`, `true`, `false` inside an expression.
void addExpressionKeywords(ItemBuilder& items);
// The modifiers of `curve` not yet written in `written` (the cut so far).
void addModifiers(ItemBuilder& items, std::string_view written);
// The choices of `method=` or `entry=`.
void addModifierChoices(ItemBuilder& items, std::string_view modifier);
// The settings of `tool N` not yet in `written`.
void addToolSettings(ItemBuilder& items, std::string_view written);
// After `origin `: G54 .. G59 and G54.1 P1.
void addOriginOffsets(ItemBuilder& items);
// After `coolant `: flood, mist, through, off.
void addCoolantModes(ItemBuilder& items);
// Builtins (with named-argument snippets), and the names in scope.
void addNames(ItemBuilder& items, const Analysis& analysis, std::uint32_t offset);
// The modules of the standard library, as `import "..."` names them.
std::vector<std::string> stdlibModules(const std::string& stdlibDirectory);

} // namespace cncc::lsp
