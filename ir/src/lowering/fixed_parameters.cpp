// The part parameters whose defaults the lowering reads as constants: a
// loop bound, an `if` condition, a curve sampled into tables, a transform's
// offset. The controller cannot recompute these, so a program that lets the
// operator edit the parameter checks it still has the compiled-in value.
#include "lowering/part_lowering.h"

#include <fmt/format.h>

namespace cncc::ir::lowering {

using namespace frontend;

namespace {

void collectNames(const Expr& expression, std::vector<const Declaration*>& names) {
  auto visit = [&](const ExprPtr& child) {
    if (child) {
      collectNames(*child, names);
    }
  };
  switch (expression.kind) {
  case ExprKind::Name:
    names.push_back(as<NameExpr>(expression).declaration);
    return;
  case ExprKind::Unary:
    return visit(as<UnaryExpr>(expression).operand);
  case ExprKind::Binary:
    visit(as<BinaryExpr>(expression).left);
    return visit(as<BinaryExpr>(expression).right);
  case ExprKind::Call:
    for (const Argument& argument : as<CallExpr>(expression).arguments) {
      visit(argument.value);
    }
    return;
  case ExprKind::Point:
    for (const ExprPtr& component : as<PointExpr>(expression).components) {
      visit(component);
    }
    return;
  case ExprKind::List:
    for (const ExprPtr& element : as<ListExpr>(expression).elements) {
      visit(element);
    }
    return;
  case ExprKind::Range:
    visit(as<RangeExpr>(expression).low);
    return visit(as<RangeExpr>(expression).high);
  case ExprKind::Index:
    visit(as<IndexExpr>(expression).base);
    return visit(as<IndexExpr>(expression).index);
  case ExprKind::Member:
    return visit(as<MemberExpr>(expression).base);
  case ExprKind::IfElse:
    visit(as<IfElseExpr>(expression).condition);
    visit(as<IfElseExpr>(expression).thenValue);
    return visit(as<IfElseExpr>(expression).elseValue);
  default:
    return;
  }
}

} // namespace

std::set<std::string> PartLowering::parametersOf(const Expr& expression) const {
  std::vector<const Declaration*> names;
  collectNames(expression, names);
  std::set<std::string> parameters;
  for (const Declaration* declaration : names) {
    auto found = parameterNames_.find(declaration);
    if (found != parameterNames_.end()) {
      parameters.insert(found->second.begin(), found->second.end());
    }
  }
  return parameters;
}

void PartLowering::fixParameters(const Expr& expression, SourceSpan use, std::string_view what) {
  if (checkingDefaults_) {
    return;
  }
  for (const std::string& name : parametersOf(expression)) {
    bool known = false;
    for (const FixedParameter& fixed : fixedParameters_) {
      known = known || fixed.name == name;
    }
    if (known) {
      continue;
    }
    fixedParameters_.push_back({name, use});
    double value = 0;
    for (const frontend::Parameter& parameter : part_.parameters) {
      if (parameter.name == name && parameter.declaration && parameter.declaration->value) {
        value = parameter.declaration->value->number;
      }
    }
    if (options_.controllerLoops) {
      diagnostics_.report(DiagnosticKind::ParameterFixed, use,
                          fmt::format("'{}' is fixed at its value {:g} in this program: the "
                                      "controller cannot recompute {}; the program raises "
                                      "an alarm if it is changed",
                                      name, value, what));
    }
  }
}

// What the controller-side lowering of a curve takes from the compiler: the
// offsets, angles and factors of the transforms around it, the arguments of
// a fn that makes it (its body is evaluated with them as numbers) and the
// parameter range of a builtin curve.
void PartLowering::fixControllerCurveParameters(const Expr& curve) {
  if (curve.kind == ExprKind::Name) {
    const Declaration* declaration = as<NameExpr>(curve).declaration;
    auto found = letValues_.find(declaration);
    auto value = environment_.find(declaration);
    if (found != letValues_.end() && value != environment_.end() &&
        value->second.type.kind == TypeKind::Curve) {
      fixControllerCurveParameters(*found->second);
    }
    return;
  }
  if (curve.kind != ExprKind::Call) {
    return;
  }
  const auto& call = as<CallExpr>(curve);
  bool userFunction = call.declaration != nullptr &&
                      call.declaration->kind == DeclarationKind::Function &&
                      call.declaration->function != nullptr;
  bool transform = call.callee == "translate" || call.callee == "rotate" || call.callee == "scale";
  for (std::size_t i = 0; i < call.arguments.size(); ++i) {
    if (!call.arguments[i].value) {
      continue;
    }
    const Expr& argument = *call.arguments[i].value;
    if (userFunction) {
      fixParameters(argument, argument.span, "this curve");
    } else if (transform && i > 0) {
      fixParameters(argument, argument.span, "this transform");
    } else if (transform || call.callee == "path") {
      fixControllerCurveParameters(argument);
    } else if (argument.kind == ExprKind::Range) {
      fixParameters(argument, argument.span, "this curve's range");
    }
  }
}

} // namespace cncc::ir::lowering
