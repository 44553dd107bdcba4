#include "cncc/backends/sim_operation_count.h"

#include <unordered_set>

namespace cncc::backends::sim {

namespace {

bool isComparison(Operator op) {
  switch (op) {
  case Operator::Equal:
  case Operator::NotEqual:
  case Operator::Greater:
  case Operator::Less:
  case Operator::GreaterOrEqual:
  case Operator::LessOrEqual:
    return true;
  default:
    return false;
  }
}

void addExpression(const Expression& expression, OperationCounts& counts) {
  switch (expression.kind) {
  case Expression::Kind::Number:
  case Expression::Kind::Variable:
    break;
  case Expression::Kind::Negate:
    ++counts.arithmetic;
    break;
  case Expression::Kind::Binary:
    ++(isComparison(expression.op) ? counts.comparisons : counts.arithmetic);
    break;
  case Expression::Kind::Call:
    ++counts.functions;
    break;
  }
  // A variable's operand is its number: `#[100+#27]` adds one.
  for (const Expression& operand : expression.operands) {
    addExpression(operand, counts);
  }
}

void addScaled(OperationCounts& total, const OperationCounts& block, std::size_t times) {
  total.arithmetic += block.arithmetic * times;
  total.functions += block.functions * times;
  total.comparisons += block.comparisons * times;
  total.assignments += block.assignments * times;
}

bool isFeed(ExecutedEvent::Kind kind) {
  return kind == ExecutedEvent::Kind::Feed || kind == ExecutedEvent::Kind::ClockwiseArc ||
         kind == ExecutedEvent::Kind::CounterclockwiseArc;
}

} // namespace

double LoopOperationCounts::perFeedMove(std::size_t OperationCounts::*kind) const {
  return feedMoves == 0 ? 0.0
                        : static_cast<double>(operations.*kind) / static_cast<double>(feedMoves);
}

double LoopOperationCounts::totalPerFeedMove() const {
  return feedMoves == 0 ? 0.0
                        : static_cast<double>(operations.total()) / static_cast<double>(feedMoves);
}

OperationCounts countBlockOperations(const Block& block) {
  OperationCounts counts;
  switch (block.kind) {
  case Block::Kind::Assignment:
  case Block::Kind::IfThen:
    ++counts.assignments;
    addExpression(block.variable, counts);
    addExpression(block.value, counts);
    if (block.kind == Block::Kind::IfThen) {
      addExpression(block.condition, counts);
    }
    break;
  case Block::Kind::IfGoto:
    addExpression(block.condition, counts);
    addExpression(block.target, counts);
    break;
  case Block::Kind::Goto:
    addExpression(block.target, counts);
    break;
  case Block::Kind::While:
    if (block.hasCondition) {
      addExpression(block.condition, counts);
    }
    break;
  case Block::Kind::Words:
    for (const Word& word : block.words) {
      addExpression(word.value, counts);
    }
    break;
  default:
    break;
  }
  return counts;
}

LoopOperationCounts countLoopOperations(const ProgramText& program,
                                        const SimulationResult& result) {
  LoopOperationCounts counts;
  // A feed block counts once per execution, however many moves the control
  // interpolates it in (a G06.2 NURBS runs as chords).
  std::unordered_set<int> feedLines;
  for (const ExecutedEvent& event : result.path.events) {
    if (isFeed(event.kind)) {
      feedLines.insert(event.line);
    }
  }
  for (std::size_t i = 0; i < program.blocks.size() && i < result.blockExecutions.size(); ++i) {
    const Block& block = program.blocks[i];
    // A WHILE block's own test runs once per iteration, and once more to leave.
    bool inLoop = !block.loops.empty() || block.kind == Block::Kind::While;
    if (inLoop) {
      addScaled(counts.operations, countBlockOperations(block), result.blockExecutions[i]);
    }
    if (!block.loops.empty() && feedLines.contains(block.line)) {
      counts.feedMoves += result.blockExecutions[i];
    }
  }
  return counts;
}

} // namespace cncc::backends::sim
