// The formatter's expressions: parentheses where precedence needs them,
// operator spacing, and brackets that break when their contents are long.
#include "formatter_tree.h"

#include <algorithm>

namespace cncc::frontend::format {

int precedence(const Expr& expression) {
  switch (expression.kind) {
  case ExprKind::Range:
    return 0;
  case ExprKind::IfElse:
    return -1;
  case ExprKind::Unary:
    return 6;
  case ExprKind::Binary:
    switch (as<BinaryExpr>(expression).op) {
    case BinaryOperator::Or:
      return 1;
    case BinaryOperator::And:
      return 2;
    case BinaryOperator::Equal:
    case BinaryOperator::NotEqual:
    case BinaryOperator::Less:
    case BinaryOperator::LessEqual:
    case BinaryOperator::Greater:
    case BinaryOperator::GreaterEqual:
      return 3;
    case BinaryOperator::Add:
    case BinaryOperator::Subtract:
      return 4;
    case BinaryOperator::Multiply:
    case BinaryOperator::Divide:
    case BinaryOperator::Remainder:
      return 5;
    case BinaryOperator::Power:
      return 7;
    }
    return 8;
  default:
    return 8;
  }
}

namespace {

constexpr int multiplicativePrecedence = 5; // and tighter: printed without spaces
constexpr int unaryPrecedence = 6;
constexpr int primaryPrecedence = 8;

bool isPower(const Expr& expression) {
  return expression.kind == ExprKind::Binary &&
         as<BinaryExpr>(expression).op == BinaryOperator::Power;
}

bool isChainNode(const Expr& expression) {
  return expression.kind == ExprKind::Binary || expression.kind == ExprKind::Range;
}

std::pair<const Expr*, const Expr*> operandsOf(const Expr& expression) {
  if (expression.kind == ExprKind::Range) {
    const auto& range = as<RangeExpr>(expression);
    return {range.low.get(), range.high.get()};
  }
  const auto& binary = as<BinaryExpr>(expression);
  return {binary.left.get(), binary.right.get()};
}

// Whether a chain of operators (a tree of binary operators and ranges not
// broken by parentheses) holds an operator printed with spaces: any but
// `*`, `/`, `%` and `^`.
bool chainHasSpacedOperator(const Expr& node) {
  if (precedence(node) < multiplicativePrecedence) {
    return true;
  }
  auto [left, right] = operandsOf(node);
  for (auto [child, isRight] : {std::pair{left, false}, std::pair{right, true}}) {
    if (!needsParentheses(node, *child, isRight) && isChainNode(*child) &&
        chainHasSpacedOperator(*child)) {
      return true;
    }
  }
  return false;
}

bool isSimpleElement(const Expr& expression) {
  switch (expression.kind) {
  case ExprKind::Number:
  case ExprKind::Name:
  case ExprKind::Bool:
  case ExprKind::String:
    return true;
  case ExprKind::Unary:
    return isSimpleElement(*as<UnaryExpr>(expression).operand);
  case ExprKind::Point:
    for (const ExprPtr& component : as<PointExpr>(expression).components) {
      if (!isSimpleElement(*component)) {
        return false;
      }
    }
    return true;
  default:
    return false;
  }
}

} // namespace

bool needsParentheses(const Expr& parent, const Expr& child, bool right) {
  int level = precedence(child);
  switch (parent.kind) {
  case ExprKind::Range:
    return level <= 0;
  case ExprKind::Unary:
    return level < unaryPrecedence;
  case ExprKind::Index:
    return level < primaryPrecedence;
  case ExprKind::Member:
    // `1.x` would lex as a number with a bad unit.
    return level < primaryPrecedence || child.kind == ExprKind::Number;
  case ExprKind::Binary:
    if (isPower(parent)) {
      // The base is a postfix expression; the exponent may be unary.
      return right ? level < unaryPrecedence : level < primaryPrecedence;
    }
    return right ? level <= precedence(parent) : level < precedence(parent);
  default:
    return false;
  }
}

bool hasSpacedOperator(const Expr& root) {
  if (root.kind == ExprKind::IfElse) {
    return true;
  }
  return isChainNode(root) && chainHasSpacedOperator(root);
}

Doc TreeFormatter::expression(const Expr& expression) {
  switch (expression.kind) {
  case ExprKind::Unary:
    return unary(as<UnaryExpr>(expression));
  case ExprKind::Binary:
  case ExprKind::Range:
    return operatorChain(expression);
  case ExprKind::Call:
    return call(as<CallExpr>(expression));
  case ExprKind::Point:
    return point(as<PointExpr>(expression));
  case ExprKind::List:
    return list(as<ListExpr>(expression));
  case ExprKind::Index:
    return index(as<IndexExpr>(expression));
  case ExprKind::Member:
    return member(as<MemberExpr>(expression));
  case ExprKind::IfElse:
    return ifElse(as<IfElseExpr>(expression));
  default: // literals and names are one token
    return source_.printAt(expression.span.begin);
  }
}

Doc TreeFormatter::operand(const Expr& expression, bool parenthesised) {
  if (!parenthesised) {
    return this->expression(expression);
  }
  return Doc::concat({Doc::text("("), this->expression(expression), Doc::text(")")});
}

// A chain of binary operators and ranges, flattened: `*`, `/`, `%` and `^`
// without spaces, the others with; the line may break after a spaced
// operator, as many operands per line as fit.
Doc TreeFormatter::operatorChain(const Expr& root) {
  std::vector<Doc> pieces;
  std::vector<Doc> current;
  std::function<void(const Expr&)> visit = [&](const Expr& node) {
    auto [left, right] = operandsOf(node);
    auto visitOperand = [&](const Expr& child, bool isRight) {
      bool parenthesised = needsParentheses(node, child, isRight);
      if (!parenthesised && isChainNode(child)) {
        visit(child);
      } else {
        current.push_back(operand(child, parenthesised));
      }
    };
    visitOperand(*left, false);
    int level = precedence(node);
    Doc op = node.kind == ExprKind::Range
                 ? source_.printNext(TokenKind::DotDot, left->span.end)
                 : source_.printAt(as<BinaryExpr>(node).operatorSpan.begin);
    if (level < multiplicativePrecedence) {
      current.push_back(Doc::space());
      current.push_back(std::move(op));
      pieces.push_back(Doc::concat(std::move(current)));
      pieces.push_back(Doc::line());
      current.clear();
    } else {
      current.push_back(std::move(op));
    }
    visitOperand(*right, true);
  };
  visit(root);
  pieces.push_back(Doc::concat(std::move(current)));
  return Doc::nest(indent_, Doc::fill(std::move(pieces)));
}

Doc TreeFormatter::unary(const UnaryExpr& unary) {
  return Doc::concat({source_.printAt(unary.span.begin),
                      operand(*unary.operand, needsParentheses(unary, *unary.operand, false))});
}

Doc TreeFormatter::call(const CallExpr& call) {
  bool spacedEquals =
      std::any_of(call.arguments.begin(), call.arguments.end(), [](const Argument& argument) {
        return !argument.name.empty() && hasSpacedOperator(*argument.value);
      });
  Doc callee = source_.printAt(call.calleeSpan.begin);
  Doc arguments = bracketed(
      source_.tokenAt(call.calleeSpan.end), call.arguments.size(),
      [&](std::size_t i, std::vector<Doc>& parts) {
        parts.push_back(argument(call.arguments[i], spacedEquals));
        return call.arguments[i].value->span.end;
      },
      false);
  return Doc::concat({std::move(callee), std::move(arguments)});
}

// `name=value`, `name = value` in a call where some named value has a
// spaced operator, or a positional value.
Doc TreeFormatter::argument(const Argument& argument, bool spacedEquals) {
  if (argument.name.empty()) {
    return expression(*argument.value);
  }
  Doc name = source_.printAt(argument.nameSpan.begin);
  Doc equal = source_.printNext(TokenKind::Equal, argument.nameSpan.end);
  if (spacedEquals) {
    return Doc::concat({name, Doc::space(), equal, Doc::space(), expression(*argument.value)});
  }
  return Doc::concat({name, equal, expression(*argument.value)});
}

Doc TreeFormatter::point(const PointExpr& point) {
  return bracketed(
      source_.tokenAt(point.span.begin), point.components.size(),
      [&](std::size_t i, std::vector<Doc>& parts) {
        parts.push_back(expression(*point.components[i]));
        return point.components[i]->span.end;
      },
      false);
}

// Lists of numbers, names and points of those fill their lines; lists of
// anything else take one element per line when they do not fit on one.
Doc TreeFormatter::list(const ListExpr& list) {
  bool fill = std::all_of(list.elements.begin(), list.elements.end(),
                          [](const ExprPtr& element) { return isSimpleElement(*element); });
  return bracketed(
      source_.tokenAt(list.span.begin), list.elements.size(),
      [&](std::size_t i, std::vector<Doc>& parts) {
        parts.push_back(expression(*list.elements[i]));
        return list.elements[i]->span.end;
      },
      fill);
}

Doc TreeFormatter::index(const IndexExpr& index) {
  return Doc::concat({operand(*index.base, needsParentheses(index, *index.base, false)),
                      source_.printNext(TokenKind::LeftBracket, index.base->span.end),
                      expression(*index.index), source_.printAt(index.span.end - 1)});
}

Doc TreeFormatter::member(const MemberExpr& member) {
  return Doc::concat({operand(*member.base, needsParentheses(member, *member.base, false)),
                      source_.printNext(TokenKind::Dot, member.base->span.end),
                      source_.printAt(member.memberSpan.begin)});
}

// if c then a else b, broken before `then` and `else` when it is long.
Doc TreeFormatter::ifElse(const IfElseExpr& choice) {
  std::vector<Doc> parts{source_.printAt(choice.span.begin), Doc::space(),
                         expression(*choice.condition)};
  std::vector<Doc> rest{
      Doc::line(),  source_.printNext(TokenKind::KwThen, choice.condition->span.end),
      Doc::space(), expression(*choice.thenValue),
      Doc::line(),  source_.printNext(TokenKind::KwElse, choice.thenValue->span.end),
      Doc::space(), expression(*choice.elseValue)};
  parts.push_back(Doc::nest(indent_, Doc::concat(std::move(rest))));
  return Doc::group(Doc::concat(std::move(parts)));
}

Doc TreeFormatter::bracketed(const Token& open, std::size_t count, const ElementPrinter& element,
                             bool fill) {
  Doc opening = source_.print(open);
  const Token& close = source_.closing(open);
  std::vector<Doc> items;
  for (std::size_t i = 0; i < count; ++i) {
    std::vector<Doc> parts;
    std::uint32_t end = element(i, parts);
    if (i + 1 < count) {
      parts.push_back(source_.printNext(TokenKind::Comma, end));
    }
    if (i > 0) {
      items.push_back(Doc::line());
    }
    items.push_back(Doc::concat(std::move(parts)));
  }
  Doc contents = fill ? Doc::fill(std::move(items)) : Doc::concat(std::move(items));
  Doc comments = source_.commentsBefore(close.span.begin);
  Doc inside = Doc::nest(indent_, Doc::concat({Doc::softLine(), contents, comments}));
  Doc closing = source_.printWithoutTrailing(close);
  Doc group = Doc::group(Doc::concat({opening, inside, Doc::softLine(), std::move(closing)}));
  return Doc::concat({std::move(group), source_.trailingComments(close)});
}

} // namespace cncc::frontend::format
