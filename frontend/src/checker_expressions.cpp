// The checker's expressions: names, operators, points, lists, indexing.
#include "checker.h"

#include <algorithm>
#include <fmt/format.h>

namespace cncc::frontend {

using namespace std::string_view_literals;

bool Checker::reportMismatch(const Expr& expression, Type actual, TypeKind expected,
                             std::string_view what, TypeKind element) {
  Type wanted = expected == TypeKind::List ? Type::listOf(element) : Type{expected};
  context_.report(
      DiagnosticKind::TypeMismatch, expression.span,
      fmt::format("{} must be a {}, but this is a {}", what, typeName(wanted), typeName(actual)));
  return false;
}

Type Checker::computeType(Expr& expression, const Scope& scope) {
  switch (expression.kind) {
  case ExprKind::Number:
    return Type::num();
  case ExprKind::Bool:
    return Type::boolean();
  case ExprKind::String:
    return Type::string();
  case ExprKind::Error:
    return Type::error();
  case ExprKind::Name:
    return checkName(as<NameExpr>(expression), scope);
  case ExprKind::Unary:
    return checkUnary(as<UnaryExpr>(expression), scope);
  case ExprKind::Binary:
    return checkBinary(as<BinaryExpr>(expression), scope);
  case ExprKind::Call:
    return checkCall(as<CallExpr>(expression), scope);
  case ExprKind::Point:
    return checkPoint(as<PointExpr>(expression), scope);
  case ExprKind::List:
    return checkList(as<ListExpr>(expression), scope);
  case ExprKind::Range:
    return checkRange(as<RangeExpr>(expression), scope);
  case ExprKind::Index:
    return checkIndex(as<IndexExpr>(expression), scope);
  case ExprKind::Member:
    return checkMember(as<MemberExpr>(expression), scope);
  case ExprKind::IfElse:
    return checkIfElse(as<IfElseExpr>(expression), scope);
  }
  return Type::error();
}

Type Checker::checkRange(RangeExpr& range, const Scope& scope) {
  bool ok =
      expectType(*range.low, checkExpression(*range.low, scope), TypeKind::Num, "start of a range");
  ok &=
      expectType(*range.high, checkExpression(*range.high, scope), TypeKind::Num, "end of a range");
  return ok ? Type::range() : Type::error();
}

Type Checker::checkName(NameExpr& name, const Scope& scope) {
  const Declaration* declaration = scope.find(name.name);
  if (declaration == nullptr) {
    std::string hint = name.name == "t"sv
                           ? "; 't' is the curve parameter only inside polar(...) and param(...)"
                           : suggestion(std::string(name.name), scope.visibleNames());
    context_.report(DiagnosticKind::UndefinedName, name.span,
                    fmt::format("'{}' is not defined{}", name.name, hint));
    return Type::error();
  }
  name.declaration = declaration;
  context_.reference(name.span, declaration, false);
  if (declaration->kind == DeclarationKind::Function ||
      (declaration->kind == DeclarationKind::Builtin && declaration->name != "pi"sv)) {
    context_.report(DiagnosticKind::TypeMismatch, name.span,
                    fmt::format("'{}' is a function; call it as {}(...)", name.name, name.name));
    return Type::error();
  }
  if (declaration->kind == DeclarationKind::Constant) {
    ItemState state = stateOf(declaration);
    if (state == ItemState::InProgress) {
      context_.report(DiagnosticKind::CircularConstant, name.span,
                      fmt::format("constant '{}' depends on itself", name.name));
      return Type::error();
    }
    if (state == ItemState::Unchecked) {
      ensureChecked(declaration);
    }
  }
  return declaration->type;
}

Type Checker::checkUnary(UnaryExpr& unary, const Scope& scope) {
  Type operand = checkExpression(*unary.operand, scope);
  if (operand.isLenient()) {
    return operand;
  }
  if (unary.op == UnaryOperator::Not) {
    return expectType(*unary.operand, operand, TypeKind::Bool, "operand of '!'") ? operand
                                                                                 : Type::error();
  }
  if (operand.kind == TypeKind::Num || operand.kind == TypeKind::Point) {
    return operand;
  }
  context_.report(DiagnosticKind::TypeMismatch, unary.span,
                  fmt::format("cannot negate a {}", typeName(operand)));
  return Type::error();
}

Type Checker::checkBinary(BinaryExpr& binary, const Scope& scope) {
  Type left = checkExpression(*binary.left, scope);
  Type right = checkExpression(*binary.right, scope);
  if (left.kind == TypeKind::Error || right.kind == TypeKind::Error) {
    return Type::error();
  }
  std::optional<Type> result = binaryResultType(binary.op, left, right);
  if (result) {
    return *result;
  }
  context_.report(DiagnosticKind::TypeMismatch, binary.operatorSpan,
                  fmt::format("'{}' cannot combine a {} and a {}", operatorSpelling(binary.op),
                              typeName(left), typeName(right)));
  return Type::error();
}

Type Checker::checkIfElse(IfElseExpr& choice, const Scope& scope) {
  Type condition = checkExpression(*choice.condition, scope);
  bool conditionOk = expectType(*choice.condition, condition, TypeKind::Bool, "condition of 'if'");
  Type thenType = checkExpression(*choice.thenValue, scope);
  Type elseType = checkExpression(*choice.elseValue, scope);
  if (!conditionOk || condition.kind == TypeKind::Error) {
    return Type::error();
  }
  if (thenType.isLenient()) {
    return elseType.kind == TypeKind::Error ? thenType : elseType;
  }
  if (elseType.isLenient() || thenType.kind == elseType.kind) {
    return thenType;
  }
  context_.report(DiagnosticKind::TypeMismatch, choice.elseValue->span,
                  fmt::format("both values of 'if' must have one type: this is a {}, the "
                              "'then' value is a {}",
                              typeName(elseType), typeName(thenType)));
  return Type::error();
}

Type Checker::checkPoint(PointExpr& point, const Scope& scope) {
  bool ok = true;
  for (ExprPtr& component : point.components) {
    ok &= expectType(*component, checkExpression(*component, scope), TypeKind::Num,
                     "a point's coordinate");
  }
  return ok && point.components.size() <= 3 ? Type::point() : Type::error();
}

Type Checker::checkList(ListExpr& list, const Scope& scope) {
  const Expr* first = nullptr;
  TypeKind element = TypeKind::Any;
  bool ok = true;
  for (ExprPtr& item : list.elements) {
    Type type = checkExpression(*item, scope);
    if (type.isLenient()) {
      ok &= type.kind != TypeKind::Error;
      continue;
    }
    if (first == nullptr) {
      first = item.get();
      element = type.kind;
    } else if (type.kind != element) {
      Diagnostic* diagnostic = context_.report(
          DiagnosticKind::MixedList, item->span,
          fmt::format("a list holds one type: this element is a {}, the first is a {}",
                      typeName(type), typeKindName(element)));
      context_.diagnostics.addNote(diagnostic, first->span, "the first element is here");
      ok = false;
    }
  }
  return ok ? Type::listOf(element) : Type::error();
}

Type Checker::checkIndex(IndexExpr& index, const Scope& scope) {
  Type base = checkExpression(*index.base, scope);
  Type position = checkExpression(*index.index, scope);
  bool ok = expectType(*index.index, position, TypeKind::Num, "an index");
  if (base.isLenient()) {
    return base;
  }
  if (base.kind != TypeKind::List) {
    std::string hint = base.kind == TypeKind::Point ? "; use .x, .y or .z for a coordinate" : "";
    context_.report(
        DiagnosticKind::TypeMismatch, index.base->span,
        fmt::format("only a list can be indexed; this is a {}{}", typeName(base), hint));
    return Type::error();
  }
  return ok ? Type{base.element} : Type::error();
}

Type Checker::checkMember(MemberExpr& member, const Scope& scope) {
  Type base = checkExpression(*member.base, scope);
  if (member.member.empty() || base.kind == TypeKind::Error) {
    return Type::error();
  }
  if (base.kind != TypeKind::Point && base.kind != TypeKind::Any) {
    context_.report(
        DiagnosticKind::TypeMismatch, member.base->span,
        fmt::format("only a point has .{}; this is a {}", member.member, typeName(base)));
    return Type::error();
  }
  if (member.member != "x"sv && member.member != "y"sv && member.member != "z"sv) {
    context_.report(DiagnosticKind::UnknownMember, member.memberSpan,
                    fmt::format("a point has no member '{}'; it has x, y and z{}", member.member,
                                suggestion(std::string(member.member), {"x", "y", "z"})));
    return Type::error();
  }
  return Type::num();
}

std::optional<Type> Checker::binaryResultType(BinaryOperator op, Type left, Type right) {
  bool anyLeft = left.kind == TypeKind::Any;
  bool anyRight = right.kind == TypeKind::Any;
  auto is = [](Type type, TypeKind kind) {
    return type.kind == kind || type.kind == TypeKind::Any;
  };
  switch (op) {
  case BinaryOperator::Add:
  case BinaryOperator::Subtract:
    if (anyLeft && anyRight) {
      return Type::any();
    }
    if (anyLeft || anyRight || left.kind == right.kind) {
      Type known = anyLeft ? right : left;
      if (known.kind == TypeKind::Num || known.kind == TypeKind::Point) {
        return known;
      }
    }
    return std::nullopt;
  case BinaryOperator::Multiply:
    if (is(left, TypeKind::Num) && is(right, TypeKind::Num)) {
      return anyLeft || anyRight ? Type::any() : Type::num();
    }
    if ((is(left, TypeKind::Num) && is(right, TypeKind::Point)) ||
        (is(left, TypeKind::Point) && is(right, TypeKind::Num))) {
      return Type::point();
    }
    return std::nullopt;
  case BinaryOperator::Divide:
    if (is(left, TypeKind::Num) && is(right, TypeKind::Num)) {
      return anyLeft ? Type::any() : Type::num();
    }
    if (is(left, TypeKind::Point) && is(right, TypeKind::Num)) {
      return Type::point();
    }
    return std::nullopt;
  case BinaryOperator::Remainder:
  case BinaryOperator::Power:
    if (is(left, TypeKind::Num) && is(right, TypeKind::Num)) {
      return Type::num();
    }
    return std::nullopt;
  case BinaryOperator::Less:
  case BinaryOperator::LessEqual:
  case BinaryOperator::Greater:
  case BinaryOperator::GreaterEqual:
    if (is(left, TypeKind::Num) && is(right, TypeKind::Num)) {
      return Type::boolean();
    }
    return std::nullopt;
  case BinaryOperator::Equal:
  case BinaryOperator::NotEqual:
    if (anyLeft || anyRight ||
        (left.kind == right.kind && (left.kind == TypeKind::Num || left.kind == TypeKind::Bool))) {
      return Type::boolean();
    }
    return std::nullopt;
  case BinaryOperator::And:
  case BinaryOperator::Or:
    if (is(left, TypeKind::Bool) && is(right, TypeKind::Bool)) {
      return Type::boolean();
    }
    return std::nullopt;
  }
  return std::nullopt;
}

} // namespace cncc::frontend
