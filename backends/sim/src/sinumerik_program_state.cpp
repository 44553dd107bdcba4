#include "sinumerik_program_state.h"

#include "sinumerik_expression.h"

#include <fmt/format.h>

namespace cncc::backends::sinumerik {

double ProgramState::evaluate(const std::string& expression) const {
  return evaluateExpression(expression, [this](int number) { return parameter(number); });
}

double ProgramState::valueOf(const SinumerikWord& word) const {
  if (!word.expression.empty()) {
    return evaluate(word.expression);
  }
  if (!word.value) {
    throw ExpressionError(fmt::format("{} needs a number", word.address));
  }
  return *word.value;
}

double ProgramState::parameter(int number) const {
  if (number < 0 || number >= parameterCount) {
    throw ExpressionError(fmt::format("R{} does not exist: R0 to R{}", number, parameterCount - 1));
  }
  return parameters_[std::size_t(number)];
}

void ProgramState::setParameter(int number, double value) {
  parameter(number); // checks the number
  parameters_[std::size_t(number)] = value;
}

std::size_t ProgramState::next(const SinumerikProgramUnit& unit, std::size_t at) {
  const SinumerikBlock& block = unit.blocks[at];
  switch (block.control) {
  case Control::If:
  case Control::While:
    return evaluate(block.condition) != 0 ? at + 1 : block.partner + 1;
  case Control::Else: // reached at the end of the IF branch
    return block.partner + 1;
  case Control::EndWhile:
    return block.partner;
  case Control::For: {
    double start = valueOf(block.counter);
    double end = evaluate(block.condition);
    setParameter(block.counter.parameter, start);
    loopEnds_[&block] = end;
    return start <= end ? at + 1 : block.partner + 1;
  }
  case Control::EndFor: {
    const SinumerikBlock& loop = unit.blocks[block.partner];
    int counter = loop.counter.parameter;
    setParameter(counter, parameter(counter) + 1);
    return parameter(counter) <= loopEnds_[&loop] ? block.partner + 1 : at + 1;
  }
  default:
    return at + 1;
  }
}

} // namespace cncc::backends::sinumerik
