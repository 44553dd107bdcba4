// The checker's calls: binding arguments to parameters, builtin signatures,
// user functions, and the curve parameter `t` of polar and param.
#include "checker.h"

#include <algorithm>
#include <fmt/format.h>
#include <functional>
#include <iterator>
#include <string_view>
#include <unordered_map>

namespace cncc::frontend {

using namespace std::string_view_literals;

std::string joinNames(ParameterList parameters) {
  std::string text;
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    text += fmt::format("{}'{}'", i == 0 ? "" : ", ", parameters.name(i));
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
    context_.report(DiagnosticKind::UnknownFunction, call.calleeSpan,
                    fmt::format("there is no function '{}'{}", call.callee,
                                suggestion(std::string(call.callee), callable)));
    checkArgumentsAlone(call, scope);
    return Type::error();
  }
  context_.reference(call.calleeSpan, declaration, false);
  call.declaration = declaration;
  if (declaration->kind == DeclarationKind::Function) {
    return checkFunctionCall(call, *declaration, scope);
  }
  if (declaration->kind == DeclarationKind::Builtin) {
    if (const BuiltinSpec* spec = builtinSpecOf(*declaration)) {
      return checkBuiltinCall(call, *spec, scope);
    }
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

void Checker::bindArguments(const CallExpr& call, ParameterList parameters, bool variadic,
                            ArgumentBinding& binding) {
  std::size_t nextPositional = 0;
  for (const Argument& argument : call.arguments) {
    if (argument.name.empty()) {
      if (variadic) {
        ++binding.extra;
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
}

void Checker::bindNamedArgument(const CallExpr& call, const Argument& argument,
                                ParameterList parameters, ArgumentBinding& binding) {
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    if (!sameName(parameters.name(i), argument.name)) {
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
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    names.emplace_back(parameters.name(i));
  }
  std::string expected = parameters.empty()
                             ? fmt::format("'{}' takes no named arguments", call.callee)
                             : fmt::format("'{}' takes {}", call.callee, joinNames(parameters));
  context_.report(DiagnosticKind::UnknownArgument, argument.nameSpan,
                  fmt::format("unknown argument '{}'; {}{}", argument.name, expected,
                              suggestion(std::string(argument.name), names)));
  binding.ok = false;
  binding.unknownName = true;
}

void Checker::reportMissing(const CallExpr& call, ParameterList parameters,
                            ArgumentBinding& binding) {
  if (call.argumentsCutShort) {
    binding.ok = false; // the syntax error is the message
    return;
  }
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    if (binding.unknownName) {
      binding.ok = false;
      return;
    }
    if (parameters.required(i) && binding.bound[i] == nullptr) {
      context_.report(DiagnosticKind::MissingArgument, call.calleeSpan,
                      fmt::format("'{}' needs the argument '{}'", call.callee, parameters.name(i)));
      binding.ok = false;
    }
  }
}

Type Checker::checkFunctionCall(CallExpr& call, const Declaration& declaration,
                                const Scope& scope) {
  const FnItem& function = *declaration.function;
  ParameterList parameters(function.parameters);
  ArgumentBinding binding(parameters.size());
  bindArguments(call, parameters, false, binding);
  reportMissing(call, parameters, binding);
  checkArgumentsAlone(call, scope);
  ItemState state = stateOf(&declaration);
  if (state == ItemState::InProgress) {
    Diagnostic* diagnostic = context_.report(
        DiagnosticKind::RecursiveFunction, call.calleeSpan,
        fmt::format("'{}' calls itself; functions are inlined and cannot be recursive",
                    call.callee));
    context_.diagnostics.addNote(diagnostic, declaration.span, "the function is defined here");
    context_.invalidFunctions.insert(&declaration);
    return Type::error();
  }
  if (state == ItemState::Unchecked) {
    ensureChecked(&declaration);
  }
  return binding.ok ? declaration.type : Type::error();
}

// The type an argument of a builtin must have.
struct ArgumentType {
  TypeKind kind;
  TypeKind element = TypeKind::Any; // of a list
};

// Each builtin function's parameters as the checker binds them, with the
// types their arguments must have and the type of a call's value.
struct BuiltinSpec {
  const BuiltinInfo* info = nullptr;
  std::vector<ParameterSpec> parameters;
  std::vector<ArgumentType> argumentTypes; // one per parameter
  Type result;
  bool orderOrDegree = false; // nurbs and bspline
  bool analytic = false;      // polar and param
};

namespace {

ArgumentType builtinArgumentType(std::string_view function, std::string_view parameter) {
  if (parameter == "points"sv) {
    return {TypeKind::List, TypeKind::Point};
  }
  if (parameter == "weights"sv || parameter == "knots"sv) {
    return {TypeKind::List, TypeKind::Num};
  }
  if (parameter == "list"sv) {
    return {TypeKind::List};
  }
  if (parameter == "curve"sv) {
    return {TypeKind::Curve};
  }
  if ((function == "line"sv && (parameter == "from"sv || parameter == "to"sv)) ||
      parameter == "center"sv) {
    return {TypeKind::Point};
  }
  if (function == "arc"sv && parameter == "z"sv) {
    return {TypeKind::Range};
  }
  return {TypeKind::Num};
}

Type builtinResultType(std::string_view name) {
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

// Built once, by name.
const std::unordered_map<std::string_view, BuiltinSpec>& builtinSpecs() {
  static const std::unordered_map<std::string_view, BuiltinSpec> specs = [] {
    std::unordered_map<std::string_view, BuiltinSpec> table;
    for (const BuiltinInfo& builtin : builtinFunctions()) {
      // The last of a name wins, as a search through the list would find.
      BuiltinSpec& spec = table[builtin.name];
      spec.info = &builtin;
      spec.parameters.clear();
      spec.argumentTypes.clear();
      for (const BuiltinParameter& parameter : builtin.parameters) {
        spec.parameters.push_back({parameter.name, parameter.required});
        spec.argumentTypes.push_back(builtinArgumentType(builtin.name, parameter.name));
      }
      spec.result = builtinResultType(builtin.name);
      spec.orderOrDegree = builtin.name == "nurbs"sv || builtin.name == "bspline"sv;
      spec.analytic = builtin.name == "polar"sv || builtin.name == "param"sv;
    }
    return table;
  }();
  return specs;
}

} // namespace

const BuiltinSpec* Checker::builtinSpecOf(const Declaration& declaration) {
  auto [cached, inserted] = builtinSpecs_.try_emplace(&declaration, nullptr);
  if (inserted) {
    const auto& specs = builtinSpecs();
    auto found = specs.find(declaration.name);
    cached->second = found == specs.end() ? nullptr : &found->second;
  }
  return cached->second;
}

Type Checker::checkBuiltinCall(CallExpr& call, const BuiltinSpec& spec, const Scope& scope) {
  const BuiltinInfo* info = spec.info;
  std::span<const ParameterSpec> parameters = spec.parameters;
  ArgumentBinding binding(parameters.size());
  bindArguments(call, parameters, info->variadic, binding);
  reportMissing(call, parameters, binding);
  if (spec.orderOrDegree) {
    checkOrderOrDegree(call, binding);
  }
  if (spec.analytic) {
    return checkAnalyticCurve(call, spec, binding, scope) ? Type::curve() : Type::error();
  }
  bool ok = binding.ok;
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    if (binding.bound[i] != nullptr) {
      ok &= checkBuiltinArgument(spec, i, *binding.bound[i]->value, scope);
    }
  }
  if (binding.extra != 0) {
    // The positional arguments of a variadic builtin, in order.
    for (Argument& argument : call.arguments) {
      if (argument.name.empty()) {
        ok &=
            expectTypeOf(*argument.value, checkExpression(*argument.value, scope), TypeKind::Curve,
                         [&] { return fmt::format("each argument of '{}'", info->name); });
      }
    }
  }
  if (info->variadic && binding.extra == 0 && !call.argumentsCutShort) {
    context_.report(DiagnosticKind::MissingArgument, call.calleeSpan,
                    fmt::format("'{}' needs at least one curve", info->name));
    ok = false;
  }
  if (!ok) {
    return Type::error();
  }
  return spec.result;
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
    if (call.argumentsCutShort) {
      binding.ok = false;
      return;
    }
    context_.report(DiagnosticKind::MissingArgument, call.calleeSpan,
                    fmt::format("'{}' needs 'order=' or 'degree='", call.callee));
    binding.ok = false;
  }
}

bool Checker::checkBuiltinArgument(const BuiltinSpec& spec, std::size_t parameter, Expr& value,
                                   const Scope& scope) {
  Type type = checkExpression(value, scope);
  ArgumentType wanted = spec.argumentTypes[parameter];
  return expectTypeOf(
      value, type, wanted.kind,
      [&] {
        return fmt::format("argument '{}' of '{}'", spec.parameters[parameter].name,
                           spec.info->name);
      },
      wanted.element);
}

// polar(r = ..., t = a .. b) and param(x = ..., y = ..., z = ..., t = a .. b):
// the expressions see the curve parameter `t`; the range does not.
bool Checker::checkAnalyticCurve(CallExpr& call, const BuiltinSpec& spec,
                                 const ArgumentBinding& binding, const Scope& scope) {
  std::span<const ParameterSpec> parameters = spec.parameters;
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
  std::string& description = parameter.description;
  description.reserve(28 + call.callee.size());
  description.append("the parameter of this ").append(call.callee).append(" curve");
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
  call.curveParameter = &parameter;
  return ok;
}

} // namespace cncc::frontend
