#include "part_pipeline.h"

#include "parallel_work.h"
#include "part_evaluation.h"

#include <span>
#include <vector>

namespace cncc::frontend {

namespace {

void checkAndEvaluate(Checker& checker, Evaluator& evaluator, PartItem& part, const Scope& scope,
                      std::vector<const Declaration*>* assigned = nullptr) {
  checker.checkPart(part, scope);
  evaluatePart(evaluator, part, assigned);
}

// How many diagnostics the second thread's checker and evaluator had
// reported when a part was done: its own are the ones since the part before.
struct ReportsAfterPart {
  std::size_t checking = 0;
  std::size_t evaluation = 0;
};

// The second run of parts goes through a checker and a copy of the
// evaluator of its own on another thread, each reporting to diagnostics of
// its own. Then the second thread's declarations join this program, and its
// diagnostics are reported part by part (the check's, then the run's), as
// one thread would have reported them. When the two threads together spent
// more than the evaluation budget (which one thread would have run out of
// part-way), the second run's values are dropped and its parts are run
// again here, in order, after the first run's.
void checkAndEvaluateOnTwoThreads(SemaContext& context, Checker& checker, Evaluator& evaluator,
                                  const Scope& scope, std::span<PartItem* const> first,
                                  std::span<PartItem* const> second) {
  CheckedProgram secondProgram;
  DiagnosticEngine checkDiagnostics(0);
  DiagnosticEngine evaluationDiagnostics(0);
  SemaContext secondContext(context.sources, checkDiagnostics, secondProgram, context.options);
  Checker secondChecker(secondContext, checker);
  Evaluator secondEvaluator = evaluator.copyReportingTo(evaluationDiagnostics);
  std::vector<const Declaration*> secondAssigned;
  std::vector<ReportsAfterPart> reports;
  reports.reserve(second.size());
  std::size_t stepsBefore = evaluator.stepsSpent();
  runAlongside(
      [&] {
        for (PartItem* part : second) {
          checkAndEvaluate(secondChecker, secondEvaluator, *part, scope, &secondAssigned);
          reports.push_back(
              {checkDiagnostics.diagnostics().size(), evaluationDiagnostics.diagnostics().size()});
        }
      },
      [&] {
        for (PartItem* part : first) {
          checkAndEvaluate(checker, evaluator, *part, scope);
        }
      });
  context.adopt(secondContext);
  std::size_t steps = evaluator.stepsSpent() + (secondEvaluator.stepsSpent() - stepsBefore);
  bool withinBudget = steps <= evaluator.maximumSteps;
  if (!withinBudget) {
    for (const Declaration* declaration : secondAssigned) {
      context.mutableDeclaration(declaration).value.reset();
    }
  }
  ReportsAfterPart done;
  for (std::size_t i = 0; i < second.size(); ++i) {
    context.diagnostics.reportRange(checkDiagnostics, done.checking, reports[i].checking);
    if (withinBudget) {
      evaluator.addReportsOf(evaluationDiagnostics, done.evaluation, reports[i].evaluation);
    } else {
      evaluatePart(evaluator, *second[i]);
    }
    done = reports[i];
  }
}

} // namespace

void checkAndEvaluateParts(SemaContext& context, Checker& checker, Evaluator& evaluator) {
  Module& main = context.program.modules.front();
  const Scope& scope = context.fileScopes.at(&main);
  std::vector<PartItem*> parts;
  for (ItemPtr& item : main.items) {
    if (item->kind == ItemKind::Part) {
      parts.push_back(&as<PartItem>(*item));
    }
  }
  std::size_t split = partSplit({parts.data(), parts.size()}, context.options);
  if (split != 0) {
    checkAndEvaluateOnTwoThreads(context, checker, evaluator, scope, std::span(parts).first(split),
                                 std::span(parts).subspan(split));
    return;
  }
  for (PartItem* part : parts) {
    checkAndEvaluate(checker, evaluator, *part, scope);
  }
}

} // namespace cncc::frontend
