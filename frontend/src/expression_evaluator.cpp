// The public face of the compile-time evaluator, for phases after checking.
#include "cncc/frontend/sema.h"

#include "evaluator.h"

namespace cncc::frontend {

struct ExpressionEvaluator::State {
  State(const CheckedProgram& program, DiagnosticEngine& diagnostics)
      : context(sources, diagnostics, const_cast<CheckedProgram&>(program), options),
        evaluator(context) {}

  SourceManager sources; // nothing is loaded after checking
  CheckOptions options;
  // Evaluation only reads the program (constants already have their values).
  SemaContext context;
  Evaluator evaluator;
};

ExpressionEvaluator::ExpressionEvaluator(const CheckedProgram& program,
                                         DiagnosticEngine& diagnostics)
    : state_(std::make_unique<State>(program, diagnostics)) {}

ExpressionEvaluator::~ExpressionEvaluator() = default;

Value ExpressionEvaluator::evaluate(const Expr& expression, const Environment& environment) {
  return state_->evaluator.evaluate(expression, environment);
}

} // namespace cncc::frontend
