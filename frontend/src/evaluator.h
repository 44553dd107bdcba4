// Compile-time evaluation of expressions to Values (private to the front
// end). Used for constants, part parameter defaults, and part bodies with
// their parameters at defaults, where it finds what only values reveal:
// division by zero, indexes out of range, bad weights and knots, ...
#pragma once

#include "sema_context.h"

#include <cmath>
#include <set>
#include <utility>

namespace cncc::frontend {

class Evaluator {
public:
  explicit Evaluator(SemaContext& context) : context_(context) {}

  // Error values are returned silently when the expression already had a
  // diagnostic (its type is Error) or when evaluation found a new problem
  // (reported here).
  Value evaluate(const Expr& expression, const Environment& environment);
  Value constantValue(const Declaration* declaration);

  // Reports once per kind and place, with a note for each fn call that led
  // here.
  void report(DiagnosticKind kind, SourceSpan span, std::string message);
  // Whether the step budget that protects against pathological inputs is
  // spent; evaluation then returns Error values without diagnostics.
  bool exhausted() const { return steps_ > maximumSteps; }

  // The argument expression bound to each parameter of a builtin or fn.
  static std::vector<const Expr*> bindArguments(const CallExpr& call,
                                                const std::vector<std::string>& parameterNames);

  SemaContext& context() { return context_; }

  static constexpr std::size_t maximumSteps = 20'000'000;

private:
  Value evaluateName(const NameExpr& name, const Environment& environment);
  Value evaluateUnary(const UnaryExpr& unary, const Environment& environment);
  Value evaluateBinary(const BinaryExpr& binary, const Environment& environment);
  Value evaluateArithmetic(const BinaryExpr& binary, const Value& left, const Value& right);
  Value evaluateCall(const CallExpr& call, const Environment& environment);
  Value evaluateFunctionCall(const CallExpr& call, const Declaration& function,
                             const Environment& environment);
  Value evaluateMathCall(const CallExpr& call, const Environment& environment);
  Value evaluatePoint(const PointExpr& point, const Environment& environment);
  Value evaluateList(const ListExpr& list, const Environment& environment);
  Value evaluateIndex(const IndexExpr& index, const Environment& environment);
  Value evaluateMember(const MemberExpr& member, const Environment& environment);
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
  std::vector<SourceSpan> callStack_;
  std::set<std::pair<int, std::pair<std::uint32_t, std::uint32_t>>> reported_;
  std::set<const Declaration*> constantsInProgress_;
  std::size_t steps_ = 0;
};

// Builds the CurveValue of a curve constructor call (nurbs, polar, line, ...)
// from its evaluated arguments, making the geometric checks.
Value buildCurve(Evaluator& evaluator, const CallExpr& call, const Environment& environment);

} // namespace cncc::frontend
