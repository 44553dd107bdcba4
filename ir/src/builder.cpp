#include "cncc/ir/builder.h"

namespace cncc::ir {

FunctionBuilder::FunctionBuilder(std::string name) {
  function_.name = std::move(name);
}

std::uint32_t FunctionBuilder::addParameter(std::string name, double defaultValue) {
  function_.parameters.push_back({std::move(name), defaultValue, false});
  return static_cast<std::uint32_t>(function_.parameters.size() - 1);
}

std::uint32_t FunctionBuilder::addTable(std::vector<double> values) {
  function_.tables.push_back(std::move(values));
  return static_cast<std::uint32_t>(function_.tables.size() - 1);
}

Region& FunctionBuilder::currentRegion() {
  if (insertion_.empty()) {
    return function_.body;
  }
  auto [instruction, region] = insertion_.back();
  return function_.instructions[instruction].regions[region];
}

InstructionId FunctionBuilder::append(Instruction instruction, ValueType resultType) {
  auto id = static_cast<InstructionId>(function_.instructions.size());
  if (resultType != ValueType::None) {
    instruction.result = ValueId{static_cast<std::uint32_t>(function_.valueTypes.size())};
    function_.valueTypes.push_back(resultType);
    function_.definitions.push_back(id);
  }
  currentRegion().instructions.push_back(id);
  instruction.span = span_;
  instruction.pass = pass_;
  function_.instructions.push_back(std::move(instruction));
  return id;
}

ValueId FunctionBuilder::constant(double value) {
  Instruction instruction;
  instruction.opcode = Opcode::Const;
  instruction.number = value;
  return function_.instructions[append(std::move(instruction), ValueType::F64)].result;
}

ValueId FunctionBuilder::constantBool(bool value) {
  Instruction instruction;
  instruction.opcode = Opcode::ConstBool;
  instruction.number = value ? 1 : 0;
  return function_.instructions[append(std::move(instruction), ValueType::Bool)].result;
}

ValueId FunctionBuilder::parameter(std::uint32_t index) {
  Instruction instruction;
  instruction.opcode = Opcode::Param;
  instruction.index = index;
  return function_.instructions[append(std::move(instruction), ValueType::F64)].result;
}

ValueId FunctionBuilder::tableLoad(std::uint32_t table, ValueId index) {
  Instruction instruction;
  instruction.opcode = Opcode::TableLoad;
  instruction.index = table;
  instruction.operands = {index};
  return function_.instructions[append(std::move(instruction), ValueType::F64)].result;
}

ValueId FunctionBuilder::operation(Opcode opcode, std::vector<ValueId> operands) {
  Instruction instruction;
  instruction.opcode = opcode;
  instruction.operands = std::move(operands);
  return function_.instructions[append(std::move(instruction), opcodeInfo(opcode).result)].result;
}

ValueId FunctionBuilder::beginLoop(ValueId low, ValueId high, LoopRole role) {
  Instruction instruction;
  instruction.opcode = Opcode::Loop;
  instruction.index = static_cast<std::uint32_t>(role);
  instruction.operands = {low, high};
  instruction.regions.resize(1);
  InstructionId id = append(std::move(instruction), ValueType::F64);
  insertion_.push_back({id, 0});
  return function_.instructions[id].result;
}

void FunctionBuilder::endLoop() {
  insertion_.pop_back();
}

void FunctionBuilder::endLoopAdvancingTo(ValueId next) {
  Instruction instruction;
  instruction.opcode = Opcode::LoopNext;
  instruction.operands = {next};
  append(std::move(instruction), ValueType::None);
  endLoop();
}

void FunctionBuilder::beginIf(ValueId condition) {
  Instruction instruction;
  instruction.opcode = Opcode::If;
  instruction.operands = {condition};
  instruction.regions.resize(2);
  InstructionId id = append(std::move(instruction), ValueType::None);
  insertion_.push_back({id, 0});
}

void FunctionBuilder::beginElse() {
  insertion_.back().second = 1;
}

void FunctionBuilder::endIf() {
  insertion_.pop_back();
}

std::uint32_t FunctionBuilder::addCurve(CurveTableEntry entry) {
  function_.curves.push_back(std::move(entry));
  return static_cast<std::uint32_t>(function_.curves.size() - 1);
}

ValueId FunctionBuilder::beginCurveLap(std::uint32_t curve, ValueId zFrom, ValueId zTo,
                                       ValueId feedRate,
                                       const std::vector<ValueId>& computedSteps) {
  Instruction instruction;
  instruction.opcode = Opcode::CurveLap;
  instruction.index = curve;
  instruction.operands = {zFrom, zTo, feedRate};
  instruction.operands.insert(instruction.operands.end(), computedSteps.begin(),
                              computedSteps.end());
  instruction.regions.resize(function_.curves[curve].regionCount());
  InstructionId id = append(std::move(instruction), ValueType::F64);
  insertion_.push_back({id, 0});
  return function_.instructions[id].result;
}

void FunctionBuilder::curvePoint(ValueId x, ValueId y, ValueId z) {
  operation(Opcode::CurvePoint, {x, y, z});
  endLapRegion();
}

void FunctionBuilder::curveArc(ValueId x, ValueId y, ValueId z, ValueId toCentreX,
                               ValueId toCentreY) {
  operation(Opcode::CurveArc, {x, y, z, toCentreX, toCentreY});
  endLapRegion();
}

void FunctionBuilder::curveWalk(ValueId x, ValueId y, ValueId z, ValueId step) {
  operation(Opcode::CurveWalk, {x, y, z, step});
  endLapRegion();
}

// After a region's last instruction: the lap's next region, or after the lap.
void FunctionBuilder::endLapRegion() {
  auto& [lap, region] = insertion_.back();
  if (region + 1 < function_.instructions[lap].regions.size()) {
    ++region;
  } else {
    insertion_.pop_back();
  }
}

void FunctionBuilder::rapid(ValueId x, ValueId y, ValueId z) {
  operation(Opcode::Rapid, {x, y, z});
}

void FunctionBuilder::climb(ValueId z) {
  operation(Opcode::Climb, {z});
}

void FunctionBuilder::feed(ValueId x, ValueId y, ValueId z, ValueId feedRate) {
  operation(Opcode::Feed, {x, y, z, feedRate});
}

void FunctionBuilder::arc(ArcTurn turn, ValueId x, ValueId y, ValueId z, ValueId i, ValueId j,
                          ValueId feedRate) {
  Instruction instruction;
  instruction.opcode = Opcode::Arc;
  instruction.index = static_cast<std::uint32_t>(turn);
  instruction.operands = {x, y, z, i, j, feedRate};
  append(std::move(instruction), ValueType::None);
}

void FunctionBuilder::nurbs(std::uint32_t table, ValueId z, ValueId feedRate,
                            const std::vector<ValueId>& weights) {
  Instruction instruction;
  instruction.opcode = Opcode::Nurbs;
  instruction.index = table;
  instruction.operands = {z, feedRate};
  instruction.operands.insert(instruction.operands.end(), weights.begin(), weights.end());
  append(std::move(instruction), ValueType::None);
}

void FunctionBuilder::spline(std::uint32_t table, ValueId z, ValueId feedRate) {
  Instruction instruction;
  instruction.opcode = Opcode::Spline;
  instruction.index = table;
  instruction.operands = {z, feedRate};
  append(std::move(instruction), ValueType::None);
}

void FunctionBuilder::spindle(ValueId speed) {
  operation(Opcode::Spindle, {speed});
}

void FunctionBuilder::tool(double number, ValueId diameter, std::uint32_t lengthRegister) {
  Instruction instruction;
  instruction.opcode = Opcode::Tool;
  instruction.number = number;
  instruction.index = lengthRegister;
  instruction.operands = {diameter};
  append(std::move(instruction), ValueType::None);
}

void FunctionBuilder::origin(double code, std::uint32_t extended) {
  Instruction instruction;
  instruction.opcode = Opcode::Origin;
  instruction.number = code;
  instruction.index = extended;
  append(std::move(instruction), ValueType::None);
}

void FunctionBuilder::coolant(CoolantMode mode) {
  Instruction instruction;
  instruction.opcode = Opcode::Coolant;
  instruction.index = static_cast<std::uint32_t>(mode);
  append(std::move(instruction), ValueType::None);
}

void FunctionBuilder::home() {
  operation(Opcode::Home, {});
}

void FunctionBuilder::contouring(double tolerance) {
  Instruction instruction;
  instruction.opcode = Opcode::Contouring;
  instruction.number = tolerance;
  append(std::move(instruction), ValueType::None);
}

void FunctionBuilder::compensation(double offset, std::uint32_t offsetRegister) {
  Instruction instruction;
  instruction.opcode = Opcode::Compensation;
  instruction.number = offset;
  instruction.index = offsetRegister;
  append(std::move(instruction), ValueType::None);
}

void FunctionBuilder::cornerArc(ValueId dx, ValueId dy) {
  operation(Opcode::CornerArc, {dx, dy});
}

void FunctionBuilder::comment(std::string text) {
  Instruction instruction;
  instruction.opcode = Opcode::Comment;
  instruction.text = std::move(text);
  append(std::move(instruction), ValueType::None);
}

void FunctionBuilder::passBegin(ValueId z) {
  operation(Opcode::PassBegin, {z});
}

void FunctionBuilder::alarm(std::string text) {
  Instruction instruction;
  instruction.opcode = Opcode::Alarm;
  instruction.text = std::move(text);
  append(std::move(instruction), ValueType::None);
}

void FunctionBuilder::cutBegin(std::uint32_t index) {
  Instruction instruction;
  instruction.opcode = Opcode::CutBegin;
  instruction.index = index;
  append(std::move(instruction), ValueType::None);
}

Function FunctionBuilder::finish() {
  insertion_.clear();
  return std::move(function_);
}

} // namespace cncc::ir
