#include "cncc/frontend/ast_printer.h"

#include "cncc/frontend/sema.h"

#include <algorithm>
#include <filesystem>
#include <fmt/format.h>

namespace cncc::frontend {

namespace {

// Shortest text that reads back as the same double: stable across runs.
std::string formatNumber(double value) {
  return fmt::format("{}", value);
}

// `text` with unprintable bytes as `\xNN`, so every dump line stays one line.
std::string printable(std::string_view text) {
  std::string out;
  for (unsigned char c : text) {
    if (c < 0x20 || c >= 0x7f) {
      out += fmt::format("\\x{:02x}", c);
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}

// A string's value as a double-quoted literal, `"` and `\` escaped.
std::string stringLiteral(std::string_view text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
    }
    out += c;
  }
  return printable(out + "\"");
}

std::string location(SourceSpan span, const SourceManager& sources) {
  if (!span.valid()) {
    return "?:?";
  }
  LineColumn position = sources.file(span.file).lineColumn(span.begin);
  return fmt::format("{}:{}", position.line, position.column);
}

} // namespace

std::string_view tokenKindName(TokenKind kind) {
  switch (kind) {
#define CNCC_TOKEN(identifier, spelling)                                                           \
  case TokenKind::identifier:                                                                      \
    return #identifier;
#include "cncc/frontend/token_kinds.def"
  }
  return "Unknown";
}

std::string dumpTokens(const std::vector<Token>& tokens, const SourceManager& sources) {
  std::string out;
  for (const Token& token : tokens) {
    out += fmt::format("{} {} {}", location(token.span, sources), tokenKindName(token.kind),
                       "'" + printable(sources.text(token.span)) + "'");
    if (token.kind == TokenKind::Number) {
      out += fmt::format(" value={}", formatNumber(token.number));
      if (token.unit != UnitSuffix::None) {
        out += fmt::format(" unit={}", unitSuffixSpelling(token.unit));
      }
    } else if (token.kind == TokenKind::String) {
      out += fmt::format(" value={}", stringLiteral(token.text));
    }
    out += '\n';
  }
  return out;
}

namespace {

class AstPrinter {
public:
  AstPrinter(const SourceManager& sources, FileId file) : sources_(sources), file_(file) {}

  std::string print(const Module& module) {
    out_ = fmt::format("Module {}\n", module.file.valid() ? sources_.file(module.file).path()
                                                          : std::string("<no file>"));
    Indent indent(depth_);
    for (const ItemPtr& item : module.items) {
      printItem(*item);
    }
    return std::move(out_);
  }

private:
  struct Indent {
    explicit Indent(int& depth) : depth(depth) { ++depth; }
    ~Indent() { --depth; }
    int& depth;
  };

  // One node line: `Kind line:col details : type -> resolution`.
  void node(std::string_view kind, SourceSpan span, std::string_view details = {},
            Type type = Type::error(), std::string_view resolved = {}) {
    out_.append(static_cast<std::size_t>(depth_) * 2, ' ');
    out_ += kind;
    out_ += ' ';
    out_ += location(span, sources_);
    if (!details.empty()) {
      out_ += ' ';
      out_ += details;
    }
    if (type.kind != TypeKind::Error) {
      out_ += " : ";
      out_ += typeName(type);
    }
    out_ += resolved;
    out_ += '\n';
  }

  static std::string name(std::string_view text) {
    return text.empty() ? "<missing>" : std::string(text);
  }

  // ` -> part-parameter depth at 2:13` for a resolved name.
  std::string resolution(const Declaration* declaration) const {
    if (declaration == nullptr) {
      return "";
    }
    std::string kind(declarationKindName(declaration->kind));
    std::replace(kind.begin(), kind.end(), ' ', '-');
    std::string out = fmt::format(" -> {} {}", kind, declaration->name);
    if (!declaration->span.valid()) {
      return out;
    }
    std::string where = location(declaration->span, sources_);
    if (declaration->span.file != file_) {
      std::filesystem::path path(sources_.file(declaration->span.file).path());
      where = path.filename().string() + ":" + where;
    }
    return out + " at " + where;
  }

  // The type of what a declaring node declares, once checked.
  static Type declaredType(const Declaration* declaration) {
    return declaration != nullptr ? declaration->type : Type::error();
  }

  // ------------------------------------------------------------ items
  void printItem(const Item& item) {
    switch (item.kind) {
    case ItemKind::Import: {
      const auto& import = as<ImportItem>(item);
      node("Import", item.span, stringLiteral(import.path));
      return;
    }
    case ItemKind::Const: {
      const auto& constant = as<ConstItem>(item);
      node("Const", item.span, name(constant.name), declaredType(constant.declaration));
      Indent indent(depth_);
      printExpression(*constant.value);
      return;
    }
    case ItemKind::Fn:
      printFunction(as<FnItem>(item));
      return;
    case ItemKind::Part:
      printPart(as<PartItem>(item));
      return;
    case ItemKind::Error:
      node("Error", item.span);
      return;
    }
  }

  void printFunction(const FnItem& function) {
    node("Fn", function.span, name(function.name), declaredType(function.declaration));
    Indent indent(depth_);
    printParameters(function.parameters);
    printExpression(*function.body);
  }

  void printPart(const PartItem& part) {
    node("Part", part.span, name(part.name));
    Indent indent(depth_);
    printParameters(part.parameters);
    printBlock("Body", part.body);
  }

  void printParameters(const NodeList<Parameter>& parameters) {
    for (const Parameter& parameter : parameters) {
      node("Parameter", parameter.nameSpan, name(parameter.name),
           declaredType(parameter.declaration));
      if (parameter.defaultValue) {
        Indent indent(depth_);
        printExpression(*parameter.defaultValue);
      }
    }
  }

  // ------------------------------------------------------------ statements
  void printBlock(std::string_view label, const Block& block) {
    node(label, block.span);
    Indent indent(depth_);
    for (const StmtPtr& statement : block.statements) {
      printStatement(*statement);
    }
  }

  void printStatement(const Stmt& statement) {
    switch (statement.kind) {
    case StmtKind::Units:
      node("Units", statement.span, name(as<UnitsStmt>(statement).unit));
      return;
    case StmtKind::Tool:
      printTool(as<ToolStmt>(statement));
      return;
    case StmtKind::Feed:
    case StmtKind::Spindle:
      node(statement.kind == StmtKind::Feed ? "Feed" : "Spindle", statement.span);
      printChild(*as<ValueStmt>(statement).value);
      return;
    case StmtKind::Safe:
      node("Safe", statement.span);
      printArguments(as<SafeStmt>(statement).settings);
      return;
    case StmtKind::Origin:
      printOrigin(as<OriginStmt>(statement));
      return;
    case StmtKind::Coolant:
      node("Coolant", statement.span, name(coolantModeSpelling(as<CoolantStmt>(statement).mode)));
      return;
    case StmtKind::Let: {
      const auto& let = as<LetStmt>(statement);
      node("Let", statement.span, name(let.name), declaredType(let.declaration));
      printChild(*let.value);
      return;
    }
    case StmtKind::Cut:
      printCut(as<CutStmt>(statement));
      return;
    case StmtKind::For:
      printFor(as<ForStmt>(statement));
      return;
    case StmtKind::If:
      printIf(as<IfStmt>(statement));
      return;
    case StmtKind::Error:
      node("Error", statement.span);
      return;
    }
  }

  void printTool(const ToolStmt& tool) {
    node("Tool", tool.span);
    printChild(*tool.number);
    printArguments(tool.settings);
  }

  void printOrigin(const OriginStmt& origin) {
    std::string offset = originOffsetSpelling(origin);
    if (origin.extended != 0) {
      offset += fmt::format(" P{}", origin.extended);
    }
    node("Origin", origin.span, name(offset));
  }

  void printCut(const CutStmt& cut) {
    node("Cut", cut.span);
    Indent indent(depth_);
    printExpression(*cut.curve);
    for (const Modifier& modifier : cut.modifiers) {
      node("Modifier", modifier.nameSpan, name(modifier.name));
      if (modifier.value) {
        printChild(*modifier.value);
      }
    }
  }

  void printFor(const ForStmt& loop) {
    node("For", loop.span, name(loop.variable), declaredType(loop.declaration));
    Indent indent(depth_);
    printExpression(*loop.range);
    printBlock("Body", loop.body);
  }

  void printIf(const IfStmt& branch) {
    node("If", branch.span);
    Indent indent(depth_);
    printExpression(*branch.condition);
    printBlock("Then", branch.thenBlock);
    if (branch.hasElse) {
      printBlock("Else", branch.elseBlock);
    }
  }

  // `name = value` pairs as Argument nodes; positional values as they are.
  template <typename Arguments> void printArguments(const Arguments& arguments) {
    Indent indent(depth_);
    for (const Argument& argument : arguments) {
      if (argument.name.empty()) {
        printExpression(*argument.value);
        continue;
      }
      node("Argument", argument.nameSpan, argument.name);
      printChild(*argument.value);
    }
  }

  // ------------------------------------------------------------ expressions
  void printChild(const Expr& expression) {
    Indent indent(depth_);
    printExpression(expression);
  }

  void printExpression(const Expr& expression) {
    Type type = expression.type;
    SourceSpan span = expression.span;
    switch (expression.kind) {
    case ExprKind::Number:
      node("Number", span, numberDetails(as<NumberExpr>(expression)), type);
      return;
    case ExprKind::Bool:
      node("Bool", span, as<BoolExpr>(expression).value ? "true" : "false", type);
      return;
    case ExprKind::String:
      node("String", span, stringLiteral(as<StringExpr>(expression).value), type);
      return;
    case ExprKind::Name: {
      const auto& nameExpr = as<NameExpr>(expression);
      node("Name", span, name(nameExpr.name), type, resolution(nameExpr.declaration));
      return;
    }
    case ExprKind::Unary: {
      const auto& unary = as<UnaryExpr>(expression);
      node("Unary", span, unary.op == UnaryOperator::Negate ? "-" : "!", type);
      printChild(*unary.operand);
      return;
    }
    case ExprKind::Binary: {
      const auto& binary = as<BinaryExpr>(expression);
      node("Binary", span, operatorSpelling(binary.op), type);
      printChildren({binary.left.get(), binary.right.get()});
      return;
    }
    case ExprKind::Call: {
      const auto& call = as<CallExpr>(expression);
      node("Call", span, name(call.callee), type, resolution(call.declaration));
      printArguments(call.arguments);
      return;
    }
    default:
      printCompound(expression);
      return;
    }
  }

  // `12`, or `2.5mm = 2.5` when a unit scaled the written number.
  std::string numberDetails(const NumberExpr& number) const {
    std::string value = formatNumber(number.value);
    if (number.unit == UnitSuffix::None) {
      return value;
    }
    return fmt::format("{} = {}", sources_.text(number.span), value);
  }

  // Points, lists, ranges, indexing, members, if-expressions and errors.
  void printCompound(const Expr& expression) {
    Type type = expression.type;
    SourceSpan span = expression.span;
    switch (expression.kind) {
    case ExprKind::Point:
      node("Point", span, {}, type);
      printChildren(as<PointExpr>(expression).components);
      return;
    case ExprKind::List:
      node("List", span, {}, type);
      printChildren(as<ListExpr>(expression).elements);
      return;
    case ExprKind::Range: {
      const auto& range = as<RangeExpr>(expression);
      node("Range", span, {}, type);
      printChildren({range.low.get(), range.high.get()});
      return;
    }
    case ExprKind::Index: {
      const auto& index = as<IndexExpr>(expression);
      node("Index", span, {}, type);
      printChildren({index.base.get(), index.index.get()});
      return;
    }
    case ExprKind::Member: {
      const auto& member = as<MemberExpr>(expression);
      node("Member", span, "." + name(member.member), type);
      printChild(*member.base);
      return;
    }
    case ExprKind::IfElse: {
      const auto& ifElse = as<IfElseExpr>(expression);
      node("IfElse", span, {}, type);
      printChildren({ifElse.condition.get(), ifElse.thenValue.get(), ifElse.elseValue.get()});
      return;
    }
    default:
      node("Error", span);
      return;
    }
  }

  void printChildren(std::initializer_list<const Expr*> expressions) {
    Indent indent(depth_);
    for (const Expr* expression : expressions) {
      printExpression(*expression);
    }
  }

  void printChildren(const NodeList<ExprPtr>& expressions) {
    Indent indent(depth_);
    for (const ExprPtr& expression : expressions) {
      printExpression(*expression);
    }
  }

  const SourceManager& sources_;
  FileId file_;
  std::string out_;
  int depth_ = 0;
};

} // namespace

std::string dumpAst(const Module& module, const SourceManager& sources) {
  return AstPrinter(sources, module.file).print(module);
}

} // namespace cncc::frontend
