// Completion: decides from the text before the cursor what may come next
// (a module after `import`, a modifier or its value after `curve <expr>`, a
// setting after `tool N`, an offset after `origin`, a mode after `coolant`,
// a statement or item keyword at the start of a line, or an expression) and
// offers the matching items.
#include "completion_items.h"

#include "cncc/frontend/ast.h"

#include <optional>
#include <string_view>

namespace cncc::lsp {

namespace {

bool isIdentifierCharacter(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_';
}

bool isBlank(std::string_view text) {
  return text.find_first_not_of(" \t\r") == std::string_view::npos;
}

// The cursor's surroundings on its line.
struct CursorLine {
  std::string_view before; // from the line start to the cursor
  std::string_view head;   // `before` without the word being typed
  std::uint32_t lineStart = 0;
};

CursorLine cursorLine(std::string_view text, std::uint32_t offset) {
  std::uint32_t lineStart = offset;
  while (lineStart > 0 && text[lineStart - 1] != '\n') {
    --lineStart;
  }
  CursorLine line{text.substr(lineStart, offset - lineStart), {}, lineStart};
  std::size_t wordStart = line.before.size();
  while (wordStart > 0 && isIdentifierCharacter(line.before[wordStart - 1])) {
    --wordStart;
  }
  line.head = line.before.substr(0, wordStart);
  return line;
}

std::string_view skipBlanks(std::string_view text) {
  std::size_t first = text.find_first_not_of(" \t");
  return first == std::string_view::npos ? std::string_view() : text.substr(first);
}

// `text` without its leading blanks and then `word`, if it starts so.
std::optional<std::string_view> after(std::string_view text, std::string_view word) {
  text = skipBlanks(text);
  if (text.substr(0, word.size()) != word ||
      (text.size() > word.size() && isIdentifierCharacter(text[word.size()]))) {
    return std::nullopt;
  }
  return text.substr(word.size());
}

// In `import "st|` the module names replace what is typed in the string;
// after `import |` they come with their quotes.
bool completeImport(ItemBuilder& items, const CursorLine& line, const TextPositions& positions,
                    std::uint32_t offset, const CompletionOptions& options) {
  Position position = positions.positionOf(offset);
  std::optional<std::string_view> rest = after(line.before, "import");
  if (!rest) {
    return false;
  }
  std::string_view path = skipBlanks(*rest);
  bool inString =
      !path.empty() && path.front() == '"' && path.find('"', 1) == std::string_view::npos;
  if (inString) {
    auto typed = static_cast<std::uint32_t>(path.size() - 1);
    Range range{positions.positionOf(offset - typed), position};
    for (const std::string& module : stdlibModules(options.stdlibDirectory)) {
      items.addReplacement(module, ItemKind::Module, range, module);
    }
    return true;
  }
  if (path.empty()) {
    for (const std::string& module : stdlibModules(options.stdlibDirectory)) {
      items.addReplacement(module, ItemKind::Module, {position, position}, "\"" + module + "\"");
    }
    return true;
  }
  return false;
}

// What follows the statement `word` and a blank on the line, or nothing when
// the line does not begin with it.
std::optional<std::string_view> afterStatementWord(const CursorLine& line, std::string_view word) {
  std::optional<std::string_view> rest = after(line.head, word);
  if (!rest || rest->empty() || (rest->front() != ' ' && rest->front() != '\t')) {
    return std::nullopt;
  }
  return skipBlanks(*rest);
}

// Whether `written` ends in a complete expression and a blank, where a
// setting or a modifier may follow.
bool endsAfterExpression(std::string_view written) {
  int depth = 0;
  for (char c : written) {
    depth += (c == '(' || c == '[') ? 1 : (c == ')' || c == ']') ? -1 : 0;
  }
  std::size_t last = written.find_last_not_of(" \t");
  return depth == 0 && last != std::string::npos && last + 1 < written.size() &&
         std::string_view("+-*/%^=<>!&|,.(").find(written[last]) == std::string::npos;
}

// After `curve <expression> ` on the same line: the cut's modifiers, or the
// choices after `method=`, `entry=`, `side=` and `comp=`.
bool completeModifiers(ItemBuilder& items, const CursorLine& line) {
  std::optional<std::string_view> rest = afterStatementWord(line, "curve");
  if (!rest) {
    return false;
  }
  std::string cut(*rest);
  for (std::string_view modifier : {"method=", "entry=", "side=", "comp="}) {
    if (cut.size() >= modifier.size() && cut.substr(cut.size() - modifier.size()) == modifier) {
      addModifierChoices(items, modifier.substr(0, modifier.size() - 1));
      return true;
    }
  }
  if (!endsAfterExpression(cut)) {
    return false;
  }
  addModifiers(items, cut);
  return true;
}

// The words of the set-up statements: the settings after `tool N `, the
// offsets after `origin ` and the modes after `coolant `.
bool completeSetup(ItemBuilder& items, const CursorLine& line) {
  if (std::optional<std::string_view> rest = afterStatementWord(line, "tool")) {
    if (!endsAfterExpression(*rest)) {
      return false;
    }
    addToolSettings(items, *rest);
    return true;
  }
  if (std::optional<std::string_view> rest = afterStatementWord(line, "origin")) {
    if (!rest->empty()) {
      return false;
    }
    addOriginOffsets(items);
    return true;
  }
  if (std::optional<std::string_view> rest = afterStatementWord(line, "coolant")) {
    if (!rest->empty()) {
      return false;
    }
    addCoolantModes(items);
    return true;
  }
  return false;
}

bool insidePart(const Analysis& analysis, std::uint32_t offset) {
  for (const frontend::ItemPtr& item : analysis.module().items) {
    if (item->kind == frontend::ItemKind::Part) {
      frontend::SourceSpan body = frontend::as<frontend::PartItem>(*item).body.span;
      if (body.begin < offset && offset <= std::max(body.end, body.begin + 1)) {
        return true;
      }
    }
  }
  return false;
}

// Whether the line continues an expression from the line before (its last
// character is an operator, a comma or an opening bracket).
bool continuesExpression(std::string_view text, std::uint32_t lineStart) {
  std::uint32_t i = lineStart;
  while (i > 0 && std::string_view(" \t\r\n").find(text[i - 1]) != std::string_view::npos) {
    --i;
  }
  return i > 0 && std::string_view("([,=+-*/%^<>&|!.").find(text[i - 1]) != std::string_view::npos;
}

// Whether the cursor is in a `//` comment or a string (judged from its line;
// block comments spanning lines are not detected).
bool inCommentOrString(std::string_view before) {
  bool inString = false;
  for (std::size_t i = 0; i < before.size(); ++i) {
    if (inString && before[i] == '\\') {
      ++i;
    } else if (before[i] == '"') {
      inString = !inString;
    } else if (!inString && before.substr(i, 2) == "//") {
      return true;
    }
  }
  return inString;
}

} // namespace

Json completion(const Analysis& analysis, Position position, const CompletionOptions& options) {
  ItemBuilder items(options.snippets);
  std::string_view text = analysis.text();
  std::uint32_t offset = analysis.offsetOf(position);
  CursorLine line = cursorLine(text, offset);
  if (completeImport(items, line, analysis.positions(), offset, options) ||
      inCommentOrString(line.before) || completeModifiers(items, line) ||
      completeSetup(items, line)) {
    return items.list();
  }
  bool lineStart = isBlank(line.head) && !continuesExpression(text, line.lineStart);
  bool inPart = insidePart(analysis, offset);
  if (lineStart && inPart) {
    addStatementKeywords(items);
  } else if (lineStart && !inPart) {
    addItemKeywords(items);
  } else {
    addExpressionKeywords(items);
    addNames(items, analysis, offset);
  }
  return items.list();
}

} // namespace cncc::lsp
