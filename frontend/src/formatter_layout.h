// The formatter's layout engine (private to the front end): a document of
// text, possible line breaks and groups, laid out within a line width.
//
// The idea is Wadler's "prettier printer": a group is printed on one line
// when it fits, otherwise its line breaks are taken and its subgroups get
// the same choice. A fill breaks a separator only where the next piece
// would not fit, so long lists of numbers pack into lines.
//
// Line breaks are lazy: a break followed by another break is one break (a
// blank line wins over a plain one), indentation is written only before
// text, and a space is dropped at the start of a line, so the output never
// has trailing spaces or runs of blank lines.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace cncc::frontend::format {

enum class DocKind {
  Text,      // literal text (may hold line breaks: a multi-line comment)
  LineEnd,   // text that ends its line (a trailing comment): not counted
             // against the width, so a comment never moves code
  Space,     // one space, dropped at the start of a line
  Line,      // a space, or a line break when its group breaks
  SoftLine,  // nothing, or a line break when its group breaks
  HardLine,  // always a line break; breaks every enclosing group
  BlankLine, // an empty line; breaks every enclosing group
  Concat,    // the children in order
  Nest,      // the child, with line breaks indented by `indent` more
  Group,     // the child on one line if it fits, else with its breaks taken
  Fill,      // content, separator, content, ...: a separator breaks only
             // when the content after it would not fit
};

// An immutable document node, shared: copying a Doc copies a pointer, so
// building nested documents costs no copies of their contents.
class Doc {
public:
  static Doc text(std::string text);
  static Doc lineEnd(std::string text);
  static Doc space() { return leaf(DocKind::Space); }
  static Doc line() { return leaf(DocKind::Line); }
  static Doc softLine() { return leaf(DocKind::SoftLine); }
  static Doc hardLine() { return leaf(DocKind::HardLine); }
  static Doc blankLine() { return leaf(DocKind::BlankLine); }
  static Doc concat(std::vector<Doc> children);
  static Doc nest(int indent, Doc child);
  static Doc group(Doc child);
  static Doc fill(std::vector<Doc> contentsAndSeparators);

  DocKind kind() const { return node_->kind; }
  const std::string& textValue() const { return node_->text; }
  int indent() const { return node_->indent; }
  const std::vector<Doc>& children() const { return node_->children; }
  // Whether this document must break the line (a hard or blank line, or
  // multi-line text, somewhere inside): its groups never print flat.
  bool forcesBreak() const { return node_->forcesBreak; }
  bool empty() const { return kind() == DocKind::Concat && children().empty(); }

private:
  struct Node {
    DocKind kind;
    std::string text;
    int indent = 0;
    std::vector<Doc> children;
    bool forcesBreak = false;
  };

  explicit Doc(std::shared_ptr<const Node> node) : node_(std::move(node)) {}
  static Doc leaf(DocKind kind);
  static Doc withChildren(DocKind kind, std::vector<Doc> children, int indent = 0);

  std::shared_ptr<const Node> node_;
};

// Lays `document` out in lines of at most `width` columns where it can, and
// ends the text with exactly one line break (none for an empty document).
std::string layout(const Doc& document, int width);

} // namespace cncc::frontend::format
