#include "cncc/ir/verifier.h"

#include "cncc/ir/nurbs_move.h"
#include "cncc/ir/spline_move.h"

#include <cmath>
#include <fmt/format.h>
#include <set>

namespace cncc::ir {

namespace {

// The operand types an operation expects.
ValueType operandType(Opcode opcode, std::size_t operand) {
  switch (opcode) {
  case Opcode::And:
  case Opcode::Or:
  case Opcode::Not:
  case Opcode::If:
    return ValueType::Bool;
  case Opcode::Select:
    return operand == 0 ? ValueType::Bool : ValueType::F64;
  default:
    return ValueType::F64;
  }
}

std::string_view typeName(ValueType type) {
  switch (type) {
  case ValueType::None:
    return "none";
  case ValueType::F64:
    return "f64";
  case ValueType::Bool:
    return "bool";
  }
  return "?";
}

class Verifier {
public:
  explicit Verifier(const Function& function) : function_(function) {}

  std::vector<std::string> run() {
    if (function_.valueTypes.size() != function_.definitions.size()) {
      problem("value types and definitions disagree in size");
      return problems_;
    }
    std::vector<bool> visible(function_.valueTypes.size(), false);
    verifyRegion(function_.body, visible);
    if (placed_.size() != function_.instructions.size()) {
      problem(fmt::format("{} instructions are in no region",
                          function_.instructions.size() - placed_.size()));
    }
    return problems_;
  }

private:
  void problem(std::string message) { problems_.push_back(std::move(message)); }

  // `visible` holds the values defined so far on the way to this point.
  // `loopBody`: the region is a loop's body, which alone may end in loop.next.
  void verifyRegion(const Region& region, std::vector<bool>& visible, bool loopBody = false) {
    std::vector<ValueId> definedHere;
    for (InstructionId id : region.instructions) {
      if (id < function_.instructions.size() &&
          function_.instructions[id].opcode == Opcode::LoopNext &&
          !(loopBody && id == region.instructions.back())) {
        problem(fmt::format("instruction {} (loop.next) is not the last of a loop's body", id));
      }
      if (id >= function_.instructions.size() || !placed_.insert(id).second) {
        problem(fmt::format("instruction {} is missing or placed twice", id));
        continue;
      }
      const Instruction& instruction = function_.instructions[id];
      verifyInstruction(id, instruction, visible);
      if (instruction.result.valid() && instruction.result.index < visible.size()) {
        if (instruction.opcode != Opcode::Loop) {
          visible[instruction.result.index] = true;
          definedHere.push_back(instruction.result);
        }
      }
    }
    for (ValueId value : definedHere) {
      visible[value.index] = false; // out of scope after the region
    }
  }

  void verifyInstruction(InstructionId id, const Instruction& instruction,
                         std::vector<bool>& visible) {
    const OpcodeInfo& info = opcodeInfo(instruction.opcode);
    std::string where = fmt::format("instruction {} ({})", id, info.spelling);
    if (info.operandCount >= 0 &&
        instruction.operands.size() != static_cast<std::size_t>(info.operandCount)) {
      problem(fmt::format("{} has {} operands, needs {}", where, instruction.operands.size(),
                          info.operandCount));
    }
    for (std::size_t i = 0; i < instruction.operands.size(); ++i) {
      verifyOperand(where, instruction, i, visible);
    }
    verifyResult(where, id, instruction);
    verifyImmediates(where, instruction);
    verifyRegions(where, instruction, visible);
  }

  void verifyOperand(const std::string& where, const Instruction& instruction, std::size_t i,
                     const std::vector<bool>& visible) {
    ValueId operand = instruction.operands[i];
    if (!operand.valid() || operand.index >= visible.size()) {
      problem(fmt::format("{} uses an undefined value", where));
      return;
    }
    if (!visible[operand.index]) {
      problem(fmt::format("{} uses %{} where it is not visible", where, operand.index));
    }
    ValueType expected = operandType(instruction.opcode, i);
    ValueType actual = function_.valueTypes[operand.index];
    if (actual != expected) {
      problem(fmt::format("{} operand {} is {}, needs {}", where, i, typeName(actual),
                          typeName(expected)));
    }
  }

  void verifyResult(const std::string& where, InstructionId id, const Instruction& instruction) {
    ValueType expected = opcodeInfo(instruction.opcode).result;
    if (expected == ValueType::None) {
      if (instruction.result.valid()) {
        problem(fmt::format("{} has a result but the operation has none", where));
      }
      return;
    }
    if (!instruction.result.valid() || instruction.result.index >= function_.valueTypes.size() ||
        function_.definitions[instruction.result.index] != id ||
        function_.valueTypes[instruction.result.index] != expected) {
      problem(fmt::format("{} has a missing or inconsistent result", where));
    }
  }

  void verifyImmediates(const std::string& where, const Instruction& instruction) {
    if (instruction.opcode == Opcode::Param && instruction.index >= function_.parameters.size()) {
      problem(fmt::format("{} names parameter {}, which does not exist", where, instruction.index));
    }
    if (instruction.opcode == Opcode::Arc &&
        instruction.index > static_cast<std::uint32_t>(ArcTurn::CounterClockwise)) {
      problem(fmt::format("{} turns neither clockwise nor counter-clockwise", where));
    }
    if (instruction.opcode == Opcode::Nurbs) {
      checkNurbs(instruction, where);
    }
    if (instruction.opcode == Opcode::Spline) {
      checkSpline(instruction, where);
    }
    if (instruction.opcode == Opcode::TableLoad && instruction.index >= function_.tables.size()) {
      problem(fmt::format("{} names table {}, which does not exist", where, instruction.index));
    }
    checkSetting(instruction, where);
  }

  void checkSetting(const Instruction& instruction, const std::string& where) {
    if (instruction.opcode == Opcode::Origin &&
        !isWorkOffsetCode(instruction.number, instruction.index)) {
      problem(
          fmt::format("{} is not a work offset (54 .. 59, or 54.1 with a number from 1)", where));
    }
    if (instruction.opcode == Opcode::Coolant &&
        instruction.index > static_cast<std::uint32_t>(CoolantMode::Through)) {
      problem(fmt::format("{} names no coolant mode", where));
    }
    if (instruction.opcode == Opcode::Compensation &&
        (!std::isfinite(instruction.number) ||
         (instruction.number == 0) != (instruction.index == 0))) {
      problem(fmt::format("{} needs a radius register and a finite offset, or neither", where));
    }
    if (instruction.opcode == Opcode::Contouring && !(instruction.number >= 0)) {
      problem(fmt::format("{} has a negative tolerance", where));
    }
  }

  static bool isWorkOffsetCode(double code, std::uint32_t extended) {
    if (code == 54.1) {
      return extended >= 1;
    }
    return extended == 0 && code >= 54 && code <= 59 && code == std::floor(code);
  }

  // Its table holds the block data of as many control points as it has
  // weights (nurbs_move.h).
  void checkNurbs(const Instruction& instruction, const std::string& where) {
    if (instruction.index >= function_.tables.size() || instruction.operands.size() < 2) {
      problem(fmt::format("{} names table {}, which does not exist", where, instruction.index));
      return;
    }
    std::string why;
    if (!readNurbsMoveTable(function_.tables[instruction.index], instruction.operands.size() - 2,
                            &why)) {
      problem(fmt::format("{} with {} weights: {}", where, instruction.operands.size() - 2, why));
    }
  }

  // Its table holds spline blocks (spline_move.h).
  void checkSpline(const Instruction& instruction, const std::string& where) {
    std::string why;
    if (instruction.index >= function_.tables.size()) {
      problem(fmt::format("{} names table {}, which does not exist", where, instruction.index));
    } else if (!readSplineMoveTable(function_.tables[instruction.index], &why)) {
      problem(fmt::format("{}: {}", where, why));
    }
  }

  void verifyRegions(const std::string& where, const Instruction& instruction,
                     std::vector<bool>& visible) {
    std::size_t expected =
        instruction.opcode == Opcode::Loop ? 1
        : instruction.opcode == Opcode::If ? 2
        : instruction.opcode == Opcode::CurveLap && instruction.index < function_.curves.size()
            ? function_.curves[instruction.index].regionCount()
            : 0;
    if (instruction.regions.size() != expected) {
      problem(
          fmt::format("{} has {} regions, needs {}", where, instruction.regions.size(), expected));
      return;
    }
    bool isLoop = (instruction.opcode == Opcode::Loop || instruction.opcode == Opcode::CurveLap) &&
                  instruction.result.valid() && instruction.result.index < visible.size();
    if (isLoop) {
      visible[instruction.result.index] = true;
    }
    for (const Region& region : instruction.regions) {
      verifyRegion(region, visible, instruction.opcode == Opcode::Loop);
    }
    if (isLoop) {
      visible[instruction.result.index] = false;
    }
  }

  const Function& function_;
  std::vector<std::string> problems_;
  std::set<InstructionId> placed_;
};

} // namespace

std::vector<std::string> verifyFunction(const Function& function) {
  return Verifier(function).run();
}

} // namespace cncc::ir
