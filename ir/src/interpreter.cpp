#include "cncc/ir/interpreter.h"

#include <cmath>
#include <fmt/format.h>

namespace cncc::ir {

namespace {

double unaryResult(Opcode opcode, double a) {
  switch (opcode) {
  case Opcode::Neg:
    return -a;
  case Opcode::Abs:
    return std::abs(a);
  case Opcode::Sqrt:
    return std::sqrt(a);
  case Opcode::Sin:
    return std::sin(a);
  case Opcode::Cos:
    return std::cos(a);
  case Opcode::Tan:
    return std::tan(a);
  case Opcode::Asin:
    return std::asin(a);
  case Opcode::Acos:
    return std::acos(a);
  case Opcode::Atan:
    return std::atan(a);
  case Opcode::Exp:
    return std::exp(a);
  case Opcode::Ln:
    return std::log(a);
  case Opcode::Floor:
    return std::floor(a);
  case Opcode::Ceil:
    return std::ceil(a);
  case Opcode::Round:
    return std::round(a);
  case Opcode::Not:
    return a != 0 ? 0 : 1;
  default:
    return NAN;
  }
}

double binaryResult(Opcode opcode, double a, double b) {
  switch (opcode) {
  case Opcode::Add:
    return a + b;
  case Opcode::Sub:
    return a - b;
  case Opcode::Mul:
    return a * b;
  case Opcode::Div:
    return a / b;
  case Opcode::Rem:
    return std::fmod(a, b);
  case Opcode::Pow:
    return std::pow(a, b);
  case Opcode::Min:
    return std::min(a, b);
  case Opcode::Max:
    return std::max(a, b);
  case Opcode::Atan2:
    return std::atan2(a, b);
  case Opcode::Lt:
    return a < b;
  case Opcode::Le:
    return a <= b;
  case Opcode::Gt:
    return a > b;
  case Opcode::Ge:
    return a >= b;
  case Opcode::Eq:
    return a == b;
  case Opcode::Ne:
    return a != b;
  case Opcode::And:
    return (a != 0) && (b != 0);
  case Opcode::Or:
    return (a != 0) || (b != 0);
  default:
    return NAN;
  }
}

class Interpreter {
public:
  Interpreter(const Function& function, const InterpreterOptions& options)
      : function_(function), options_(options), values_(function.valueTypes.size(), 0.0) {
    for (const Parameter& parameter : function.parameters) {
      auto given = options.parameters.find(parameter.name);
      parameters_.push_back(given == options.parameters.end() ? parameter.defaultValue
                                                              : given->second);
    }
  }

  ToolPath run() {
    runRegion(function_.body);
    return std::move(path_);
  }

private:
  double value(ValueId id) const { return values_[id.index]; }

  void runRegion(const Region& region) {
    for (InstructionId id : region.instructions) {
      if (++steps_ > options_.maximumSteps) {
        throw InterpreterError(
            fmt::format("the program takes more than {} steps", options_.maximumSteps));
      }
      runInstruction(function_.instructions[id]);
    }
  }

  void runInstruction(const Instruction& instruction) {
    const std::vector<ValueId>& operands = instruction.operands;
    double result = 0;
    switch (instruction.opcode) {
    case Opcode::Const:
    case Opcode::ConstBool:
      result = instruction.number;
      break;
    case Opcode::Param:
      result = parameters_[instruction.index];
      break;
    case Opcode::TableLoad:
      result = tableLoad(instruction);
      break;
    case Opcode::Select:
      result = value(operands[0]) != 0 ? value(operands[1]) : value(operands[2]);
      break;
    case Opcode::Loop:
      runLoop(instruction);
      return;
    case Opcode::If:
      runRegion(instruction.regions[value(operands[0]) != 0 ? 0 : 1]);
      return;
    case Opcode::Rapid:
    case Opcode::Feed:
    case Opcode::Spindle:
    case Opcode::Tool:
    case Opcode::Comment:
    case Opcode::CutBegin:
      record(instruction);
      return;
    default:
      result = operands.size() == 1
                   ? unaryResult(instruction.opcode, value(operands[0]))
                   : binaryResult(instruction.opcode, value(operands[0]), value(operands[1]));
      break;
    }
    values_[instruction.result.index] = result;
  }

  double tableLoad(const Instruction& instruction) const {
    const std::vector<double>& table = function_.tables[instruction.index];
    double index = value(instruction.operands[0]);
    if (!(index >= 0 && index < static_cast<double>(table.size()))) {
      throw InterpreterError(fmt::format("index {} is outside table @{} of {} entries", index,
                                         instruction.index, table.size()));
    }
    return table[static_cast<std::size_t>(index)];
  }

  void runLoop(const Instruction& loop) {
    double low = value(loop.operands[0]);
    double high = value(loop.operands[1]);
    if (!std::isfinite(low) || !std::isfinite(high)) {
      throw InterpreterError("a loop bound is not a finite number");
    }
    for (double i = low; i <= high; ++i) {
      values_[loop.result.index] = i;
      runRegion(loop.regions[0]);
    }
  }

  void record(const Instruction& instruction) {
    MachineEvent event;
    const std::vector<ValueId>& operands = instruction.operands;
    switch (instruction.opcode) {
    case Opcode::Rapid:
    case Opcode::Feed:
      event.kind = instruction.opcode == Opcode::Rapid ? MachineEvent::Kind::Rapid
                                                       : MachineEvent::Kind::Feed;
      event.x = value(operands[0]);
      event.y = value(operands[1]);
      event.z = value(operands[2]);
      event.feed = instruction.opcode == Opcode::Feed ? value(operands[3]) : 0;
      break;
    case Opcode::Spindle:
      event.kind = MachineEvent::Kind::Spindle;
      event.number = value(operands[0]);
      break;
    case Opcode::Tool:
      event.kind = MachineEvent::Kind::Tool;
      event.number = instruction.number;
      event.diameter = value(operands[0]);
      break;
    case Opcode::CutBegin:
      event.kind = MachineEvent::Kind::CutBegin;
      event.number = instruction.index;
      break;
    default:
      event.kind = MachineEvent::Kind::Comment;
      event.text = instruction.text;
      break;
    }
    path_.events.push_back(std::move(event));
  }

  const Function& function_;
  const InterpreterOptions& options_;
  std::vector<double> values_;
  std::vector<double> parameters_;
  ToolPath path_;
  std::size_t steps_ = 0;
};

} // namespace

ToolPath interpret(const Function& function, const InterpreterOptions& options) {
  return Interpreter(function, options).run();
}

} // namespace cncc::ir
