// The part parameters whose defaults the lowering reads as constants: a
// loop bound, an `if` condition, a curve sampled into tables, a transform's
// offset. The controller cannot recompute these, so a program that lets the
// operator edit the parameter checks it still has the compiled-in value.
#include "part_lowering.h"

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
    if (as<CallExpr>(expression).callee == "len") {
      return; // a list literal's length is no parameter's
    }
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

void PartLowering::unrollForLoopVariables(const std::set<std::string>& names) {
  for (const std::string& name : names) {
    if (isLoopVariableMarker(name)) {
      throw NeedsUnrolling{};
    }
  }
}

void PartLowering::fixParameters(const Expr& expression, SourceSpan use, std::string_view what) {
  if (checkingDefaults_) {
    return;
  }
  std::set<std::string> parameters = parametersOf(expression);
  unrollForLoopVariables(parameters);
  for (const std::string& name : parameters) {
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
      diagnostics_->report(DiagnosticKind::ParameterFixed, use,
                           fmt::format("'{}' is fixed at its value {:g} in this program: the "
                                       "controller cannot recompute {}; the program raises "
                                       "an alarm if it is changed",
                                       name, value, what));
    }
  }
}

} // namespace cncc::ir::lowering
