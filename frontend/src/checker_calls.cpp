// The checker's calls: binding arguments to parameters, builtin signatures,
// user functions, and the curve parameter `t` of polar and param.
#include "checker.h"

#include <algorithm>
#include <fmt/format.h>
#include <string_view>
#include <unordered_map>

namespace cncc::frontend {

using namespace std::string_view_literals;

std::string joinNames(const std::vector<ParameterSpec>& parameters) {
  std::string text;
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    text += fmt::format("{}'{}'", i == 0 ? "" : ", ", parameters[i].name);
  }
  return text;
}

Type Checker::checkCall(CallExpr& call, const Scope& scope) {
  const Declaration* declaration = scope.find(call.callee);
  if (declaration == nullptr) {
    std::vector<std::string> callable;
    for (const std::string& name : scope.visibleNames()) {
      const Declaration* candidate = scope.find(name);
      if (candidate->kind == DeclarationKind::Function ||
          candidate->kind == DeclarationKind::Builtin) {
        callable.push_back(name);
      }
    }
    context_.report(
        DiagnosticKind::UnknownFunction, call.calleeSpan,
        fmt::format("there is no function '{}'{}", call.callee, suggestion(call.callee, callable)));
    checkArgumentsAlone(call, scope);
    return Type::error();
  }
  context_.reference(call.calleeSpan, declaration, false);
  call.declaration = declaration;
  if (declaration->kind == DeclarationKind::Function) {
    return checkFunctionCall(call, *declaration, scope);
  }
  if (declaration->kind == DeclarationKind::Builtin && declaration->name != "pi"sv) {
    return checkBuiltinCall(call, scope);
  }
  context_.report(DiagnosticKind::NotCallable, call.calleeSpan,
                  fmt::format("'{}' is a {} ({}), not a function", call.callee,
                              declarationKindName(declaration->kind), typeName(declaration->type)));
  checkArgumentsAlone(call, scope);
  return Type::error();
}

void Checker::checkArgumentsAlone(CallExpr& call, const Scope& scope) {
  for (Argument& argument : call.arguments) {
    checkExpression(*argument.value, scope);
  }
}

ArgumentBinding Checker::bindArguments(const CallExpr& call,
                                       const std::vector<ParameterSpec>& parameters,
                                       bool variadic) {
  ArgumentBinding binding;
  binding.bound.assign(parameters.size(), nullptr);
  std::size_t nextPositional = 0;
  for (const Argument& argument : call.arguments) {
    if (argument.name.empty()) {
      if (variadic) {
        binding.extra.push_back(&argument);
        continue;
      }
      while (nextPositional < parameters.size() && binding.bound[nextPositional] != nullptr) {
        ++nextPositional;
      }
      if (nextPositional >= parameters.size()) {
        context_.report(DiagnosticKind::TooManyArguments, argument.value->span,
                        fmt::format("'{}' takes {} argument{}; this one is too many", call.callee,
                                    parameters.size(), parameters.size() == 1 ? "" : "s"));
        binding.ok = false;
        continue;
      }
      binding.bound[nextPositional++] = &argument;
      continue;
    }
    bindNamedArgument(call, argument, parameters, binding);
  }
  return binding;
}

void Checker::bindNamedArgument(const CallExpr& call, const Argument& argument,
                                const std::vector<ParameterSpec>& parameters,
                                ArgumentBinding& binding) {
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    if (parameters[i].name != argument.name) {
      continue;
    }
    if (binding.bound[i] != nullptr) {
      Diagnostic* diagnostic = context_.report(
          DiagnosticKind::DuplicateArgument, argument.nameSpan,
          fmt::format("argument '{}' of '{}' is given twice", argument.name, call.callee));
      context_.diagnostics.addNote(diagnostic, binding.bound[i]->span(), "first given here");
      binding.ok = false;
      return;
    }
    binding.bound[i] = &argument;
    return;
  }
  std::vector<std::string> names;
  for (const ParameterSpec& parameter : parameters) {
    names.push_back(parameter.name);
  }
  std::string expected = parameters.empty()
                             ? fmt::format("'{}' takes no named arguments", call.callee)
                             : fmt::format("'{}' takes {}", call.callee, joinNames(parameters));
  context_.report(DiagnosticKind::UnknownArgument, argument.nameSpan,
                  fmt::format("unknown argument '{}'; {}{}", argument.name, expected,
                              suggestion(argument.name, names)));
  binding.ok = false;
  binding.unknownName = true;
}

void Checker::reportMissing(const CallExpr& call, const std::vector<ParameterSpec>& parameters,
                            ArgumentBinding& binding) {
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    if (binding.unknownName) {
      binding.ok = false;
      return;
    }
    if (parameters[i].required && binding.bound[i] == nullptr) {
      context_.report(DiagnosticKind::MissingArgument, call.calleeSpan,
                      fmt::format("'{}' needs the argument '{}'", call.callee, parameters[i].name));
      binding.ok = false;
    }
  }
}

Type Checker::checkFunctionCall(CallExpr& call, const Declaration& declaration,
                                const Scope& scope) {
  const FnItem& function = *declaration.function;
  auto [cached, inserted] = functionParameters_.try_emplace(&function);
  if (inserted) {
    for (const Parameter& parameter : function.parameters) {
      cached->second.push_back({parameter.name, true});
    }
  }
  const std::vector<ParameterSpec>& parameters = cached->second;
  ArgumentBinding binding = bindArguments(call, parameters, false);
  reportMissing(call, parameters, binding);
  checkArgumentsAlone(call, scope);
  if (stateOf(&declaration) == ItemState::InProgress) {
    Diagnostic* diagnostic = context_.report(
        DiagnosticKind::RecursiveFunction, call.calleeSpan,
        fmt::format("'{}' calls itself; functions are inlined and cannot be recursive",
                    call.callee));
    context_.diagnostics.addNote(diagnostic, declaration.span, "the function is defined here");
    context_.invalidFunctions.insert(&declaration);
    return Type::error();
  }
  ensureChecked(&declaration);
  return binding.ok ? declaration.type : Type::error();
}

namespace {

// Each builtin function's parameters as the checker binds them, built once.
struct BuiltinSpec {
  const BuiltinInfo* info = nullptr;
  std::vector<ParameterSpec> parameters;
};

const BuiltinSpec& builtinSpec(const std::string& name) {
  static const std::unordered_map<std::string_view, BuiltinSpec> specs = [] {
    std::unordered_map<std::string_view, BuiltinSpec> table;
    for (const BuiltinInfo& builtin : builtinFunctions()) {
      // The last of a name wins, as a search through the list would find.
      BuiltinSpec& spec = table[builtin.name];
      spec.info = &builtin;
      spec.parameters.clear();
      for (const BuiltinParameter& parameter : builtin.parameters) {
        spec.parameters.push_back({parameter.name, parameter.required});
      }
    }
    return table;
  }();
  return specs.at(name);
}

} // namespace

Type Checker::checkBuiltinCall(CallExpr& call, const Scope& scope) {
  const BuiltinSpec& spec = builtinSpec(call.callee);
  const BuiltinInfo* info = spec.info;
  const std::vector<ParameterSpec>& parameters = spec.parameters;
  ArgumentBinding binding = bindArguments(call, parameters, info->variadic);
  reportMissing(call, parameters, binding);
  if (info->name == "nurbs"sv || info->name == "bspline"sv) {
    checkOrderOrDegree(call, binding);
  }
  if (info->name == "polar"sv || info->name == "param"sv) {
    return checkAnalyticCurve(call, parameters, binding, scope) ? Type::curve() : Type::error();
  }
  bool ok = binding.ok;
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    if (binding.bound[i] != nullptr) {
      ok &= checkBuiltinArgument(info->name, parameters[i].name, *binding.bound[i]->value, scope);
    }
  }
  for (const Argument* argument : binding.extra) {
    ok &= expectTypeOf(*argument->value, checkExpression(*argument->value, scope), TypeKind::Curve,
                       [&] { return fmt::format("each argument of '{}'", info->name); });
  }
  if (info->variadic && binding.extra.empty()) {
    context_.report(DiagnosticKind::MissingArgument, call.calleeSpan,
                    fmt::format("'{}' needs at least one curve", info->name));
    ok = false;
  }
  if (!ok) {
    return Type::error();
  }
  return builtinResultType(info->name);
}

void Checker::checkOrderOrDegree(const CallExpr& call, ArgumentBinding& binding) {
  const Argument* order = binding.bound[0];
  const Argument* degree = binding.bound[1];
  if (order != nullptr && degree != nullptr) {
    Diagnostic* diagnostic = context_.report(
        DiagnosticKind::OrderAndDegree, degree->span(),
        fmt::format("'{}' takes 'order' or 'degree', not both (order = degree + 1)", call.callee));
    context_.diagnostics.addNote(diagnostic, order->span(), "'order' is given here");
    binding.ok = false;
  } else if (order == nullptr && degree == nullptr) {
    context_.report(DiagnosticKind::MissingArgument, call.calleeSpan,
                    fmt::format("'{}' needs 'order=' or 'degree='", call.callee));
    binding.ok = false;
  }
}

Type Checker::builtinResultType(const std::string& name) {
  static constexpr std::string_view curveBuiltins[] = {"nurbs",     "bspline", "bezier", "polar",
                                                       "param",     "line",    "arc",    "path",
                                                       "translate", "rotate",  "scale"};
  for (std::string_view curve : curveBuiltins) {
    if (curve == name) {
      return Type::curve();
    }
  }
  return Type::num();
}

bool Checker::checkBuiltinArgument(const std::string& function, const std::string& parameter,
                                   Expr& value, const Scope& scope) {
  Type type = checkExpression(value, scope);
  auto what = [&] { return fmt::format("argument '{}' of '{}'", parameter, function); };
  if (parameter == "points"sv) {
    return expectTypeOf(value, type, TypeKind::List, what, TypeKind::Point);
  }
  if (parameter == "weights"sv || parameter == "knots"sv) {
    return expectTypeOf(value, type, TypeKind::List, what, TypeKind::Num);
  }
  if (parameter == "list"sv) {
    return expectTypeOf(value, type, TypeKind::List, what);
  }
  if (parameter == "curve"sv) {
    return expectTypeOf(value, type, TypeKind::Curve, what);
  }
  if ((function == "line"sv && (parameter == "from"sv || parameter == "to"sv)) ||
      parameter == "center"sv) {
    return expectTypeOf(value, type, TypeKind::Point, what);
  }
  return expectTypeOf(value, type, TypeKind::Num, what);
}

// polar(r = ..., t = a .. b) and param(x = ..., y = ..., z = ..., t = a .. b):
// the expressions see the curve parameter `t`; the range does not.
bool Checker::checkAnalyticCurve(CallExpr& call, const std::vector<ParameterSpec>& parameters,
                                 const ArgumentBinding& binding, const Scope& scope) {
  bool ok = binding.ok;
  const Argument* range = binding.bound.back();
  SourceSpan parameterSpan =
      range != nullptr && !range->name.empty() ? range->nameSpan : call.calleeSpan;
  if (range != nullptr) {
    ok &= expectTypeOf(*range->value, checkExpression(*range->value, scope), TypeKind::Range, [&] {
      return fmt::format("argument 't' of '{}' (write 't = a .. b')", call.callee);
    });
  }
  Declaration& parameter =
      context_.declare(DeclarationKind::CurveParameter, "t", parameterSpan, Type::num());
  parameter.description = fmt::format("the parameter of this {} curve", call.callee);
  context_.usedDeclarations.insert(&parameter);
  Scope curveScope(&scope);
  curveScope.add("t", &parameter);
  for (std::size_t i = 0; i + 1 < parameters.size(); ++i) {
    if (const Argument* argument = binding.bound[i]) {
      context_.program.scopeExtents.push_back({argument->value->span, &parameter});
      ok &= expectTypeOf(
          *argument->value, checkExpression(*argument->value, curveScope), TypeKind::Num,
          [&] { return fmt::format("argument '{}' of '{}'", parameters[i].name, call.callee); });
    }
  }
  context_.program.curveParameters[&call] = &parameter;
  return ok;
}

} // namespace cncc::frontend
