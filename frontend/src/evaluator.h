// Compile-time evaluation of expressions to Values (private to the front
// end). Used for constants, part parameter defaults, and part bodies with
// their parameters at defaults, where it finds what only values reveal:
// division by zero, indexes out of range, bad weights and knots, ...
#pragma once

#include "sema_context.h"

#include "cncc/geom/math_functions.h"

#include <array>
#include <cmath>
#include <cstddef>
#include <new>
#include <optional>
#include <set>
#include <string_view>
#include <unordered_map>
#include <utility>

namespace cncc::frontend {

// Values bound to declarations while evaluating: a few bound in this frame
// (a fn call's parameters, a block's lets), then the enclosing frames, and
// under them all, optionally, an Environment given by the caller. Frames
// live on the stack, so a fn call costs no map and no copy of its caller's
// values.
class Bindings {
public:
  Bindings() = default;
  explicit Bindings(const Environment& environment) : environment_(&environment) {}
  explicit Bindings(const Bindings* outer) : outer_(outer) {}
  Bindings(const Bindings&) = delete;
  Bindings& operator=(const Bindings&) = delete;
  ~Bindings();

  void reserve(std::size_t count) {
    if (count > inlineBindings) {
      more_.reserve(count - inlineBindings);
    }
  }
  // The fast path's fn calls bind numbers without Values (up to
  // `maximumNumbers`), seen only by findNumber: such a frame is never handed
  // to the ordinary evaluation.
  static constexpr std::size_t maximumNumbers = 8;
  void bindNumber(const Declaration* declaration, double number) {
    numberDeclarations_[numberCount_] = declaration;
    numbers_[numberCount_++] = number;
  }
  // The innermost binding's number: false when it is not a number (or there
  // is none).
  bool findNumber(const Declaration* declaration, double& number) const;
  // Binds in this frame, replacing an earlier binding of the same declaration
  // made here.
  void bind(const Declaration* declaration, Value value);
  // The innermost binding, or null.
  const Value* find(const Declaration* declaration) const;
  // Every visible binding as one Environment (what a curve value keeps).
  Environment flatten() const;

private:
  using Binding = std::pair<const Declaration*, Value>;
  void flattenInto(Environment& environment) const;
  // This frame's binding of `declaration`, or null.
  const Value* findLocal(const Declaration* declaration) const;
  Binding* inlineBinding(std::size_t i) {
    return std::launder(reinterpret_cast<Binding*>(inlineStorage_.data()) + i);
  }
  const Binding* inlineBinding(std::size_t i) const {
    return std::launder(reinterpret_cast<const Binding*>(inlineStorage_.data()) + i);
  }

  // A fn call's parameters and a block's lets are few: the first ones live
  // in the frame itself (constructed only when bound), the others in `more_`.
  static constexpr std::size_t inlineBindings = 4;
  alignas(Binding) std::array<std::byte, inlineBindings * sizeof(Binding)> inlineStorage_;
  std::size_t inlineCount_ = 0;
  std::vector<Binding> more_;
  std::array<const Declaration*, maximumNumbers> numberDeclarations_;
  std::array<double, maximumNumbers> numbers_;
  std::size_t numberCount_ = 0;
  const Bindings* outer_ = nullptr;
  const Environment* environment_ = nullptr;
};

class Evaluator {
public:
  explicit Evaluator(SemaContext& context)
      : maximumSteps(context.options.evaluationSteps), context_(context),
        diagnostics_(&context.diagnostics) {}
  // This evaluator as it stands (steps spent, kinds and places reported,
  // samplings), reporting to `diagnostics` from now on: for evaluating some
  // parts on another thread.
  Evaluator copyReportingTo(DiagnosticEngine& diagnostics) const {
    Evaluator copy(*this);
    copy.diagnostics_ = &diagnostics;
    return copy;
  }
  // Reports what a copy reported to its own `diagnostics` ([first, last) of
  // them), in order, as this evaluator would have reported it had it done
  // the copy's work: each kind and place once.
  void addReportsOf(const DiagnosticEngine& diagnostics, std::size_t first, std::size_t last);
  std::size_t stepsSpent() const { return steps_; }

  // Error values are returned silently when the expression already had a
  // diagnostic (its type is Error) or when evaluation found a new problem
  // (reported here).
  Value evaluate(const Expr& expression, const Bindings& bindings);
  Value evaluate(const Expr& expression, const Environment& environment) {
    return evaluate(expression, Bindings(environment));
  }
  // What `evaluate` gives, without building a Value when it is a number:
  // true with `number` set then; else false with `value` set to what
  // `evaluate` gives.
  bool evaluateAsNumber(const Expr& expression, const Bindings& bindings, double& number,
                        Value& value);
  Value constantValue(const Declaration* declaration);

  // Reports once per kind and place, with a note for each fn call that led
  // here.
  void report(DiagnosticKind kind, SourceSpan span, std::string message);
  // Whether the step budget that protects against pathological inputs is
  // spent; evaluation then returns Error values without diagnostics.
  bool exhausted() const { return steps_ > maximumSteps; }

  // The argument expression bound to each parameter of a builtin or fn:
  // `bound` has one entry per parameter, null to start with; `nameAt(i)` is
  // the name of parameter i.
  template <typename NameAt>
  static void bindArguments(const CallExpr& call, std::size_t count, NameAt nameAt,
                            const Expr** bound) {
    bindArgumentsWith(call, count, bound, [&](const Argument& argument) {
      for (std::size_t i = 0; i < count; ++i) {
        if (bound[i] == nullptr && nameAt(i) == argument.name) {
          bound[i] = argument.value.get();
        }
      }
    });
  }
  // As bindArguments, with `bindNamed(argument)` binding each named argument
  // in turn (for parameters found without comparing every name).
  template <typename BindNamed>
  static void bindArgumentsWith(const CallExpr& call, std::size_t count, const Expr** bound,
                                BindNamed bindNamed) {
    std::size_t next = 0;
    for (const Argument& argument : call.arguments) {
      if (!argument.name.empty()) {
        bindNamed(argument);
        continue;
      }
      while (next < count && bound[next] != nullptr) {
        ++next;
      }
      if (next < count) {
        bound[next++] = argument.value.get();
      }
    }
  }
  static std::vector<const Expr*> bindArguments(const CallExpr& call,
                                                const std::vector<std::string>& parameterNames);

  SemaContext& context() { return context_; }

  // What evaluation has done so far, for the sampling of analytic curves
  // (curve_values.cpp), which evaluates a curve met again with the same
  // values only once: steps spent, reports made, constants computed, fn
  // calls open.
  struct Progress {
    std::size_t steps = 0;
    std::size_t reports = 0;
    std::size_t constants = 0;
    std::size_t callDepth = 0;
  };
  Progress progress() const { return {steps_, reports_, constants_, callStack_.size()}; }
  // The last sampling of each curve call that reported nothing: the values
  // it ran with, at what fn call depth, and the steps it took.
  struct Sampling {
    // The curve sampled: the values it ran with are its environment, shared
    // rather than copied.
    std::shared_ptr<const CurveValue> curve;
    std::size_t callDepth = 0;
    std::size_t steps = 0;
  };
  std::unordered_map<const CallExpr*, Sampling>& samplings() { return samplings_; }
  // Spends `steps` as evaluating again would; false (and nothing spent) when
  // that would exhaust the budget.
  bool spendSteps(std::size_t steps) {
    if (steps_ + steps > maximumSteps) {
      return false;
    }
    steps_ += steps;
    return true;
  }

  // The step budget (CheckOptions::evaluationSteps).
  const std::size_t maximumSteps;

private:
  // The three ways `evaluate` takes: a number written out (when the fast
  // path is on); the fast path, which leaves the steps as if it had not run
  // when it fails; the ordinary evaluation below such a failure.
  bool numberWrittenOut(const Expr& expression, double& number);
  bool fastPathNumber(const Expr& expression, const Bindings& bindings, double& number);
  Value evaluateWithoutFastPath(const Expr& expression, const Bindings& bindings);
  Value evaluateValue(const Expr& expression, const Bindings& bindings);
  // The fast path for numbers (number_evaluation.cpp): evaluates without
  // building Values and reports nothing. False when the value is not a
  // number or evaluation must report something; `evaluate` then evaluates
  // that expression the ordinary way, which reports.
  bool evaluateNumber(const Expr& expression, const Bindings& bindings, double& result);
  bool numberOfName(const NameExpr& name, const Bindings& bindings, double& result);
  bool numberOfBinary(const BinaryExpr& binary, const Bindings& bindings, double& result);
  bool numberOfCall(const CallExpr& call, const Bindings& bindings, double& result);
  bool numberOfFunctionCall(const CallExpr& call, const Declaration& function,
                            const Bindings& bindings, double& result);
  Value evaluateName(const NameExpr& name, const Bindings& bindings);
  Value evaluateUnary(const UnaryExpr& unary, const Bindings& bindings);
  Value evaluateBinary(const BinaryExpr& binary, const Bindings& bindings);
  Value evaluateArithmetic(const BinaryExpr& binary, const Value& left, const Value& right);
  Value evaluateCall(const CallExpr& call, const Bindings& bindings);
  Value evaluateFunctionCall(const CallExpr& call, const Declaration& function,
                             const Bindings& bindings);
  Value evaluateMathCall(const CallExpr& call, const Bindings& bindings);
  Value applyMathFunction(const CallExpr& call, const Value* values, std::size_t count);
  Value evaluatePoint(const PointExpr& point, const Bindings& bindings);
  Value evaluateList(const ListExpr& list, const Bindings& bindings);
  Value evaluateIndex(const IndexExpr& index, const Bindings& bindings);
  Value evaluateMember(const MemberExpr& member, const Bindings& bindings);
  // `describe` is called only when the number is not finite: formatting a
  // message for every good value would dominate evaluation time.
  template <typename Describe>
  Value checkedNumber(double number, SourceSpan span, Describe describe) {
    if (std::isfinite(number)) {
      return Value::ofNumber(number);
    }
    reportNonFinite(span, describe());
    return {};
  }
  void reportNonFinite(SourceSpan span, const std::string& what);
  Value typeError(SourceSpan span, std::string message);

  SemaContext& context_;
  DiagnosticEngine* diagnostics_;
  std::vector<SourceSpan> callStack_;
  using ReportKey = std::pair<int, std::pair<std::uint32_t, std::uint32_t>>;
  static ReportKey reportKey(DiagnosticKind kind, SourceSpan span) {
    return {static_cast<int>(kind), {span.begin, span.end}};
  }
  std::set<ReportKey> reported_;
  std::set<const Declaration*> constantsInProgress_;
  std::size_t steps_ = 0;
  std::size_t reports_ = 0;
  std::size_t constants_ = 0;
  std::unordered_map<const CallExpr*, Sampling> samplings_;
  // Off below an expression whose fast path failed, so no expression is
  // tried twice; and the steps that a failed fast path must not give back
  // (those of constants it evaluated, which stay evaluated).
  bool fastPathEnabled_ = true;
  int fastPathDepth_ = 0;
  std::size_t stepsKept_ = 0;
};

// The arithmetic both evaluation paths share, so they agree to the bit: the
// one table of math functions the IR, its interpreter and the JIT compute
// by too (cncc/geom/math_functions.h).
namespace arithmetic {
using geom::MathFunction;
// The math function CDL calls `name`; nullopt for any other name (len, a
// curve constructor).
inline std::optional<MathFunction> mathFunction(std::string_view name) {
  const geom::MathFunctionInfo* info = geom::findMathFunction(name);
  return info != nullptr ? std::optional(info->function) : std::nullopt;
}
inline double applyUnary(MathFunction function, double x) {
  return geom::computeMath(function, x);
}
inline double applyBinary(MathFunction function, double a, double b) {
  return geom::computeMath(function, a, b);
}
// The parameter names of a two-argument math function, in order.
inline std::array<std::string_view, 2> binaryParameterNames(MathFunction function) {
  return geom::mathFunctionInfo(function).parameters;
}
} // namespace arithmetic

// What the number fast paths (number_evaluation.cpp, number_sampling.cpp)
// share with the ordinary evaluation. Whether Evaluator::evaluate tries the
// fast path on an expression:
bool mayBeNumber(const Expr& expression);
// Whether a binary operator computes a number from numbers (not a
// comparison or logic, which give bools).
bool isArithmetic(BinaryOperator op);
// The math function of a call those paths evaluate (a builtin of one or two
// arguments other than len); nullopt for any other call.
std::optional<arithmetic::MathFunction> numericMathCall(const CallExpr& call);
// Whether a two-argument math call names its arguments in the other order
// (atan2(x = 1, y = 2)): its values then swap into parameter order.
bool binaryArgumentsSwapped(const CallExpr& call, arithmetic::MathFunction function);

// Builds the CurveValue of a curve constructor call (nurbs, polar, line, ...)
// from its evaluated arguments, making the geometric checks.
Value buildCurve(Evaluator& evaluator, const CallExpr& call, const Bindings& bindings);

} // namespace cncc::frontend
