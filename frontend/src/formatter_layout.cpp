#include "formatter_layout.h"

#include <algorithm>

namespace cncc::frontend::format {

Doc Doc::leaf(DocKind kind) {
  auto node = std::make_shared<Node>();
  node->kind = kind;
  node->forcesBreak = kind == DocKind::HardLine || kind == DocKind::BlankLine;
  return Doc(std::move(node));
}

Doc Doc::withChildren(DocKind kind, std::vector<Doc> children, int indent) {
  auto node = std::make_shared<Node>();
  node->kind = kind;
  node->indent = indent;
  node->forcesBreak = std::any_of(children.begin(), children.end(),
                                  [](const Doc& child) { return child.forcesBreak(); });
  node->children = std::move(children);
  return Doc(std::move(node));
}

Doc Doc::text(std::string text) {
  auto node = std::make_shared<Node>();
  node->kind = DocKind::Text;
  node->forcesBreak = text.find('\n') != std::string::npos;
  node->text = std::move(text);
  return Doc(std::move(node));
}

Doc Doc::lineEnd(std::string text) {
  auto node = std::make_shared<Node>();
  node->kind = DocKind::LineEnd;
  node->forcesBreak = text.find('\n') != std::string::npos;
  node->text = std::move(text);
  return Doc(std::move(node));
}

Doc Doc::concat(std::vector<Doc> children) {
  return withChildren(DocKind::Concat, std::move(children));
}

Doc Doc::nest(int indent, Doc child) {
  return withChildren(DocKind::Nest, {std::move(child)}, indent);
}

Doc Doc::group(Doc child) {
  return withChildren(DocKind::Group, {std::move(child)});
}

Doc Doc::fill(std::vector<Doc> contentsAndSeparators) {
  return withChildren(DocKind::Fill, std::move(contentsAndSeparators));
}

namespace {

enum class Mode { Flat, Break };

// One piece of work for the printer: a document, the indentation its line
// breaks get, whether its group is flat, and for a fill the next child.
struct Command {
  int indent;
  Mode mode;
  const Doc* doc;
  std::size_t fillIndex = 0;
};

class Printer {
public:
  explicit Printer(int width) : width_(width) {}

  std::string run(const Doc& document) {
    std::vector<Command> stack{{0, Mode::Break, &document}};
    while (!stack.empty()) {
      Command command = stack.back();
      stack.pop_back();
      print(command, stack);
    }
    if (!output_.empty()) {
      output_ += '\n';
    }
    return std::move(output_);
  }

private:
  void print(const Command& command, std::vector<Command>& stack) {
    const Doc& doc = *command.doc;
    switch (doc.kind()) {
    case DocKind::Text:
    case DocKind::LineEnd:
      write(doc.textValue());
      return;
    case DocKind::Space:
      space();
      return;
    case DocKind::Line:
      if (command.mode == Mode::Break) {
        lineBreak(command.indent, 1);
      } else if (pendingLines_ > 0) {
        pendingIndent_ = command.indent; // a line already broken here: indent as this one
      } else {
        space();
      }
      return;
    case DocKind::SoftLine:
      if (command.mode == Mode::Break) {
        lineBreak(command.indent, 1);
      }
      return;
    case DocKind::HardLine:
      lineBreak(command.indent, 1);
      return;
    case DocKind::BlankLine:
      lineBreak(command.indent, 2);
      return;
    case DocKind::Concat:
      for (auto child = doc.children().rbegin(); child != doc.children().rend(); ++child) {
        stack.push_back({command.indent, command.mode, &*child});
      }
      return;
    case DocKind::Nest:
      stack.push_back({command.indent + doc.indent(), command.mode, &doc.children().front()});
      return;
    case DocKind::Group:
      printGroup(command, stack);
      return;
    case DocKind::Fill:
      printFill(command, stack);
      return;
    }
  }

  void printGroup(const Command& command, std::vector<Command>& stack) {
    const Doc& doc = *command.doc;
    Command flat{command.indent, Mode::Flat, &doc.children().front()};
    if (!doc.forcesBreak() && (command.mode == Mode::Flat || fits(flat, stack))) {
      stack.push_back(flat);
    } else {
      stack.push_back({command.indent, Mode::Break, &doc.children().front()});
    }
  }

  // Even children are contents, odd ones separators. A content prints flat
  // when it fits on the rest of the line; a separator prints flat when the
  // content after it fits too.
  void printFill(const Command& command, std::vector<Command>& stack) {
    const std::vector<Doc>& children = command.doc->children();
    std::size_t index = command.fillIndex;
    if (index >= children.size()) {
      return;
    }
    stack.push_back({command.indent, command.mode, command.doc, index + 1});
    bool flat;
    if (index % 2 == 0) {
      flat = !children[index].forcesBreak() && fitsAlone({&children[index]}, command.indent);
    } else {
      std::vector<const Doc*> measured{&children[index]};
      if (index + 1 < children.size()) {
        measured.push_back(&children[index + 1]);
      }
      flat = fitsAlone(measured, command.indent);
    }
    stack.push_back({command.indent, flat ? Mode::Flat : Mode::Break, &children[index]});
  }

  bool fitsAlone(const std::vector<const Doc*>& docs, int indent) const {
    std::vector<Command> rest;
    for (auto doc = docs.rbegin(); doc != docs.rend(); ++doc) {
      rest.push_back({indent, Mode::Flat, *doc});
    }
    Command first = rest.back();
    rest.pop_back();
    return fits(first, rest);
  }

  // Whether `next` printed flat, then what `rest` prints up to its first
  // line break, fits on the current line.
  bool fits(const Command& next, const std::vector<Command>& rest) const {
    int remaining = width_ - currentColumn();
    std::vector<Command> stack{next};
    std::size_t restIndex = rest.size();
    while (remaining >= 0) {
      if (stack.empty()) {
        if (restIndex == 0) {
          return true;
        }
        stack.push_back(rest[--restIndex]);
        continue;
      }
      Command command = stack.back();
      stack.pop_back();
      const Doc& doc = *command.doc;
      switch (doc.kind()) {
      case DocKind::Text: {
        std::size_t lineEnd = doc.textValue().find('\n');
        remaining -= static_cast<int>(std::min(lineEnd, doc.textValue().size()));
        if (lineEnd != std::string::npos) {
          return remaining >= 0;
        }
        break;
      }
      case DocKind::LineEnd:
        break;
      case DocKind::Space:
        remaining -= 1;
        break;
      case DocKind::Line:
        if (command.mode == Mode::Break) {
          return true;
        }
        remaining -= 1;
        break;
      case DocKind::SoftLine:
        if (command.mode == Mode::Break) {
          return true;
        }
        break;
      case DocKind::HardLine:
      case DocKind::BlankLine:
        return true;
      case DocKind::Concat:
      case DocKind::Fill:
        for (std::size_t i = doc.children().size(); i > command.fillIndex; --i) {
          stack.push_back({command.indent, command.mode, &doc.children()[i - 1]});
        }
        break;
      case DocKind::Nest:
        stack.push_back({command.indent + doc.indent(), command.mode, &doc.children().front()});
        break;
      case DocKind::Group:
        stack.push_back({command.indent, doc.forcesBreak() ? Mode::Break : command.mode,
                         &doc.children().front()});
        break;
      }
    }
    return false;
  }

  int currentColumn() const {
    return pendingLines_ > 0 ? pendingIndent_ : column_ + (pendingSpace_ ? 1 : 0);
  }

  void write(const std::string& text) {
    if (text.empty()) {
      return;
    }
    if (pendingLines_ > 0 && !output_.empty()) {
      output_.append(static_cast<std::size_t>(pendingLines_), '\n');
      output_.append(static_cast<std::size_t>(pendingIndent_), ' ');
      column_ = pendingIndent_;
    } else if (pendingSpace_ && !output_.empty()) {
      output_ += ' ';
      ++column_;
    }
    pendingLines_ = 0;
    pendingSpace_ = false;
    output_ += text;
    std::size_t lastBreak = text.rfind('\n');
    column_ = lastBreak == std::string::npos ? column_ + static_cast<int>(text.size())
                                             : static_cast<int>(text.size() - lastBreak - 1);
  }

  void space() {
    if (pendingLines_ == 0) {
      pendingSpace_ = true;
    }
  }

  void lineBreak(int indent, int lines) {
    pendingLines_ = std::max(pendingLines_, lines);
    pendingIndent_ = indent;
    pendingSpace_ = false;
  }

  int width_;
  std::string output_;
  int column_ = 0;
  int pendingLines_ = 0;
  int pendingIndent_ = 0;
  bool pendingSpace_ = false;
};

} // namespace

std::string layout(const Doc& document, int width) {
  return Printer(width).run(document);
}

} // namespace cncc::frontend::format
