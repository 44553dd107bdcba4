// The formatter's entry point, items and statements. See formatter.h for
// the layout and formatter_layout.h for how documents become lines.
#include "cncc/frontend/formatter.h"

#include "cncc/frontend/parser.h"
#include "formatter_tree.h"

#include <algorithm>

namespace cncc::frontend {

using format::Doc;

std::optional<std::string> formatFile(const SourceManager& sources, FileId file,
                                      DiagnosticEngine& diagnostics, const FormatOptions& options) {
  std::size_t errorsBefore = diagnostics.errorCount();
  std::vector<SourceSpan> comments;
  std::vector<Token> tokens = lex(sources, file, diagnostics, &comments);
  Module module = parse(tokens, file, diagnostics);
  if (diagnostics.errorCount() != errorsBefore) {
    return std::nullopt;
  }
  format::SourceCursor source(sources.file(file).text(), std::move(tokens), comments);
  format::TreeFormatter formatter(source, options);
  return format::layout(formatter.module(module), options.lineWidth);
}

namespace format {

namespace {

bool isPart(const Item& item) {
  return item.kind == ItemKind::Part;
}

} // namespace

// ---------------------------------------------------------------- items

Doc TreeFormatter::module(const Module& module) {
  std::vector<Doc> parts;
  const Item* previous = nullptr;
  for (const ItemPtr& item : module.items) {
    if (item->kind == ItemKind::Error) {
      continue;
    }
    if (previous != nullptr && (isPart(*previous) || isPart(*item))) {
      parts.push_back(Doc::blankLine());
    }
    parts.push_back(source_.commentsBefore(item->span.begin));
    parts.push_back(source_.lineBreakBefore(item->span.begin));
    source_.setStatementEnd(item->span.end);
    parts.push_back(this->item(*item));
    previous = item.get();
  }
  parts.push_back(source_.commentsBefore(source_.endOfText() + 1));
  return Doc::concat(std::move(parts));
}

Doc TreeFormatter::item(const Item& item) {
  switch (item.kind) {
  case ItemKind::Import:
    return importItem(as<ImportItem>(item));
  case ItemKind::Const:
    return constItem(as<ConstItem>(item));
  case ItemKind::Fn:
    return fnItem(as<FnItem>(item));
  case ItemKind::Part:
    return partItem(as<PartItem>(item));
  case ItemKind::Error:
    break;
  }
  return Doc::concat({});
}

// import "std/curves"
Doc TreeFormatter::importItem(const ImportItem& import) {
  return Doc::concat(
      {source_.printAt(import.span.begin), Doc::space(), source_.printAt(import.pathSpan.begin)});
}

// const name = value
Doc TreeFormatter::constItem(const ConstItem& constant) {
  return assignment({source_.printAt(constant.span.begin), Doc::space(),
                     source_.printAt(constant.nameSpan.begin), Doc::space(),
                     source_.printNext(TokenKind::Equal, constant.nameSpan.end)},
                    *constant.value);
}

// fn name(a, b) = body, the body on the next line when it does not fit.
Doc TreeFormatter::fnItem(const FnItem& function) {
  std::vector<Doc> parts{source_.printAt(function.span.begin), Doc::space(),
                         source_.printAt(function.nameSpan.begin),
                         parameters(function.parameters, function.nameSpan.end)};
  const Token& close = source_.closing(source_.find(TokenKind::LeftParen, function.nameSpan.end));
  parts.push_back(Doc::space());
  parts.push_back(source_.printNext(TokenKind::Equal, close.span.end));
  parts.push_back(Doc::nest(indent_, Doc::concat({Doc::line(), expression(*function.body)})));
  return Doc::group(Doc::concat(std::move(parts)));
}

// part name(p = 1, q = 2) { ... }
Doc TreeFormatter::partItem(const PartItem& part) {
  std::vector<Doc> parts{source_.printAt(part.span.begin), Doc::space(),
                         source_.printAt(part.nameSpan.begin)};
  if (source_.tokenAt(part.nameSpan.end).kind == TokenKind::LeftParen) {
    parts.push_back(parameters(part.parameters, part.nameSpan.end));
  }
  parts.push_back(Doc::space());
  parts.push_back(block(part.body));
  return Doc::concat(std::move(parts));
}

Doc TreeFormatter::parameters(const NodeList<Parameter>& parameters, std::uint32_t after) {
  const Token& open = source_.find(TokenKind::LeftParen, after);
  return bracketed(
      open, parameters.size(),
      [&](std::size_t i, std::vector<Doc>& parts) {
        parts.push_back(parameter(parameters[i]));
        return parameters[i].defaultValue ? parameters[i].defaultValue->span.end
                                          : parameters[i].nameSpan.end;
      },
      false);
}

Doc TreeFormatter::parameter(const Parameter& parameter) {
  Doc name = source_.printAt(parameter.nameSpan.begin);
  if (!parameter.defaultValue) {
    return name;
  }
  return Doc::concat({name, Doc::space(),
                      source_.printNext(TokenKind::Equal, parameter.nameSpan.end), Doc::space(),
                      expression(*parameter.defaultValue)});
}

// `head = value`: a call, list or point value breaks inside its brackets;
// any other value moves to the next line when it does not fit.
Doc TreeFormatter::assignment(std::vector<Doc> head, const Expr& value) {
  bool bracketedValue =
      value.kind == ExprKind::Call || value.kind == ExprKind::List || value.kind == ExprKind::Point;
  if (bracketedValue) {
    head.push_back(Doc::space());
    head.push_back(expression(value));
    return Doc::concat(std::move(head));
  }
  head.push_back(Doc::nest(indent_, Doc::concat({Doc::line(), expression(value)})));
  return Doc::group(Doc::concat(std::move(head)));
}

// ---------------------------------------------------------------- statements

Doc TreeFormatter::block(const Block& block) {
  const Token& open = source_.tokenAt(block.span.begin);
  const Token& close = source_.closing(open);
  std::vector<Doc> body;
  std::uint32_t enclosingEnd = source_.statementEnd();
  Doc opening = source_.print(open);
  source_.markBlockStart();
  for (const StmtPtr& statement : block.statements) {
    if (statement->kind == StmtKind::Error) {
      continue; // a lone ';' (the file has no syntax errors)
    }
    // Comments first: the blank line kept is the one next to the statement.
    body.push_back(source_.commentsBefore(statement->span.begin));
    body.push_back(source_.lineBreakBefore(statement->span.begin));
    source_.setStatementEnd(statement->span.end);
    body.push_back(this->statement(*statement));
  }
  source_.setStatementEnd(enclosingEnd);
  body.push_back(source_.commentsBefore(close.span.begin));
  if (body.size() == 1 && body.front().empty()) {
    return Doc::concat({opening, source_.print(close)});
  }
  return Doc::concat({opening, Doc::nest(indent_, Doc::concat(std::move(body))), Doc::hardLine(),
                      source_.print(close)});
}

Doc TreeFormatter::statement(const Stmt& statement) {
  switch (statement.kind) {
  case StmtKind::Units:
    return unitsStatement(as<UnitsStmt>(statement));
  case StmtKind::Tool:
    return toolStatement(as<ToolStmt>(statement));
  case StmtKind::Feed:
  case StmtKind::Spindle:
    return valueStatement(as<ValueStmt>(statement));
  case StmtKind::Safe:
    return safeStatement(as<SafeStmt>(statement));
  case StmtKind::Origin:
    return originStatement(as<OriginStmt>(statement));
  case StmtKind::Coolant:
    return coolantStatement(as<CoolantStmt>(statement));
  case StmtKind::Let:
    return letStatement(as<LetStmt>(statement));
  case StmtKind::Cut:
    return cutStatement(as<CutStmt>(statement));
  case StmtKind::For:
    return forStatement(as<ForStmt>(statement));
  case StmtKind::If:
    return ifStatement(as<IfStmt>(statement));
  case StmtKind::Error:
    break;
  }
  return Doc::concat({});
}

// units mm
Doc TreeFormatter::unitsStatement(const UnitsStmt& units) {
  return Doc::concat(
      {source_.printAt(units.span.begin), Doc::space(), source_.printAt(units.unitSpan.begin)});
}

// tool N diameter=D spindle=S feed=F
Doc TreeFormatter::toolStatement(const ToolStmt& tool) {
  Doc head =
      Doc::concat({source_.printAt(tool.span.begin), Doc::space(), expression(*tool.number)});
  return Doc::concat(
      {head, settings(tool.settings, {"diameter", "length", "radius", "spindle", "feed"})});
}

// feed F, spindle S
Doc TreeFormatter::valueStatement(const ValueStmt& setting) {
  return Doc::concat(
      {source_.printAt(setting.span.begin), Doc::space(), expression(*setting.value)});
}

// safe z=Z
Doc TreeFormatter::safeStatement(const SafeStmt& safe) {
  return Doc::concat({source_.printAt(safe.span.begin), settings(safe.settings, {"z"})});
}

// origin G55, origin G54.1 P3 (`P03` prints as `P3`)
Doc TreeFormatter::originStatement(const OriginStmt& origin) {
  std::vector<Doc> parts{source_.printAt(origin.span.begin), Doc::space(),
                         source_.printAs(origin.offsetSpan, originOffsetSpelling(origin))};
  if (origin.extended != 0) {
    parts.push_back(Doc::space());
    parts.push_back(source_.printAs(origin.extendedSpan, "P" + std::to_string(origin.extended)));
  }
  return Doc::concat(std::move(parts));
}

// coolant flood
Doc TreeFormatter::coolantStatement(const CoolantStmt& coolant) {
  return Doc::concat(
      {source_.printAt(coolant.span.begin), Doc::space(),
       source_.printAs(coolant.modeSpan, std::string(coolantModeSpelling(coolant.mode)))});
}

// let name = value
Doc TreeFormatter::letStatement(const LetStmt& let) {
  return assignment({source_.printAt(let.span.begin), Doc::space(),
                     source_.printAt(let.nameSpan.begin), Doc::space(),
                     source_.printNext(TokenKind::Equal, let.nameSpan.end)},
                    *let.value);
}

// curve <expr> modifiers
Doc TreeFormatter::cutStatement(const CutStmt& cut) {
  Doc head = Doc::concat({source_.printAt(cut.span.begin), Doc::space(), expression(*cut.curve)});
  return Doc::concat({head, modifiers(cut.modifiers)});
}

// for i in a .. b { ... }
Doc TreeFormatter::forStatement(const ForStmt& loop) {
  return Doc::concat({source_.printAt(loop.span.begin), Doc::space(),
                      source_.printAt(loop.variableSpan.begin), Doc::space(),
                      source_.printNext(TokenKind::KwIn, loop.variableSpan.end), Doc::space(),
                      expression(*loop.range), Doc::space(), block(loop.body)});
}

// if c { ... } else if d { ... } else { ... }
Doc TreeFormatter::ifStatement(const IfStmt& choice) {
  std::vector<Doc> parts{source_.printAt(choice.span.begin), Doc::space(),
                         expression(*choice.condition), Doc::space(), block(choice.thenBlock)};
  if (!choice.hasElse) {
    return Doc::concat(std::move(parts));
  }
  parts.push_back(Doc::space());
  parts.push_back(source_.printNext(TokenKind::KwElse, choice.thenBlock.span.end));
  parts.push_back(Doc::space());
  bool elseIf = source_.tokenAt(choice.elseBlock.span.begin).kind == TokenKind::KwIf;
  if (elseIf && !choice.elseBlock.statements.empty()) {
    parts.push_back(statement(*choice.elseBlock.statements.front()));
  } else {
    parts.push_back(block(choice.elseBlock));
  }
  return Doc::concat(std::move(parts));
}

// Settings of `tool` and `safe`: a known one may continue the statement on
// the next line, so the line breaks before those only.
Doc TreeFormatter::settings(const NodeList<Argument>& settings,
                            const std::vector<std::string>& known) {
  std::vector<Doc> pieces{Doc::concat({})};
  for (const Argument& argument : settings) {
    bool canBreak = std::find(known.begin(), known.end(), argument.name) != known.end();
    pieces.push_back(canBreak ? Doc::line() : Doc::space());
    pieces.push_back(setting(argument.nameSpan, argument.value.get()));
  }
  return Doc::nest(indent_, Doc::fill(std::move(pieces)));
}

// Modifiers of `curve`: only a known `name=value` may begin a later line.
Doc TreeFormatter::modifiers(const NodeList<Modifier>& modifiers) {
  const std::vector<std::string>& known = cutModifierNames();
  std::vector<Doc> pieces{Doc::concat({})};
  for (const Modifier& modifier : modifiers) {
    bool canBreak =
        modifier.value && std::find(known.begin(), known.end(), modifier.name) != known.end();
    pieces.push_back(canBreak ? Doc::line() : Doc::space());
    pieces.push_back(setting(modifier.nameSpan, modifier.value.get()));
  }
  return Doc::nest(indent_, Doc::fill(std::move(pieces)));
}

// `name=value`, or `name` alone.
Doc TreeFormatter::setting(SourceSpan nameSpan, const Expr* value) {
  Doc name = source_.printAt(nameSpan.begin);
  if (value == nullptr) {
    return name;
  }
  return Doc::concat({name, source_.printNext(TokenKind::Equal, nameSpan.end), expression(*value)});
}

} // namespace format

} // namespace cncc::frontend
