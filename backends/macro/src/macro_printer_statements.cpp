// Assignments (and the operations a dialect writes as statements of their
// own), the spindle, tool changes and NURBS blocks.
#include "macro_printer.h"

#include "cncc/backends/nurbs_blocks.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/nurbs_move.h"

#include <fmt/format.h>

#include <cmath>

namespace cncc::backends {

using ir::Opcode;
using ir::ValueId;
using enum MacroPosition;

void MacroProgramPrinter::printAssignment(const ir::Instruction& instruction) {
  std::string target = expressions_.variable(instruction.result);
  if (!dialect_.isStatement(instruction.opcode)) {
    line(assignment(
        target, expressions_.at(expressions_.definition(instruction.result), AssignedDefinition)));
    return;
  }
  auto assigned = [&](std::size_t i) {
    return expressions_.at(expressions_.value(instruction.operands[i]), AssignedValue);
  };
  switch (instruction.opcode) {
  case Opcode::Min:
  case Opcode::Max:
    printMinMax(instruction, target);
    return;
  case Opcode::Floor:
  case Opcode::Ceil:
    printFloorCeil(instruction, target);
    return;
  case Opcode::Select:
    choose(expressions_.condition(instruction.operands[0]),
           expressions_.condition(instruction.operands[0], true), target, assigned(1), assigned(2));
    return;
  case Opcode::Rem:
    printRemainder(instruction, target);
    return;
  case Opcode::Atan:
  case Opcode::Atan2:
    printArctangent(instruction, target);
    return;
  default:
    errors_.push_back(fmt::format("internal: no statement writes '{}'",
                                  ir::opcodeInfo(instruction.opcode).spelling));
    return;
  }
}

// As std::min and std::max: the first unless the second is beyond it.
void MacroProgramPrinter::printMinMax(const ir::Instruction& instruction,
                                      const std::string& target) {
  bool isMin = instruction.opcode == Opcode::Min;
  auto assigned = [&](std::size_t i) {
    return expressions_.at(expressions_.value(instruction.operands[i]), AssignedValue);
  };
  auto compared = [&](std::size_t i) {
    return expressions_.at(expressions_.value(instruction.operands[i]), Compared);
  };
  if (dialect_.minMax == MinMaxStyle::CompareWithTarget) {
    line(assignment(target, assigned(0)));
    conditional(fmt::format("[{} {} {}]", compared(1), isMin ? "LT" : "GT", target),
                fmt::format("[{} {} {}]", compared(1), isMin ? "GE" : "LE", target),
                assignment(target, assigned(1)));
    return;
  }
  std::string smaller = isMin ? compared(1) : compared(0);
  std::string larger = isMin ? compared(0) : compared(1);
  choose(fmt::format("[{} LT {}]", smaller, larger), fmt::format("[{} GE {}]", smaller, larger),
         target, assigned(1), assigned(0));
}

// FIX truncates toward zero; one step fixes the other sign.
void MacroProgramPrinter::printFloorCeil(const ir::Instruction& instruction,
                                         const std::string& target) {
  bool isFloor = instruction.opcode == Opcode::Floor;
  std::string value = expressions_.operand(instruction.operands[0]);
  line(
      assignment(target, fmt::format("FIX[{}]", expressions_.value(instruction.operands[0]).text)));
  conditional(fmt::format("[{} {} {}]", target, isFloor ? "GT" : "LT", value),
              fmt::format("[{} {} {}]", target, isFloor ? "LE" : "GE", value),
              assignment(target, fmt::format("{}{}{}", target, isFloor ? "-" : "+", dialect_.one)));
}

// fmod: the sign of the first operand.
void MacroProgramPrinter::printRemainder(const ir::Instruction& instruction,
                                         const std::string& target) {
  if (dialect_.remainder == RemainderStyle::FixQuotient) { // a and b are atoms here
    std::string a = expressions_.operand(instruction.operands[0]);
    std::string b = expressions_.operand(instruction.operands[1]);
    line(assignment(target, fmt::format("{}-FIX[{}/{}]*{}", a, a, b, b)));
    return;
  }
  // LinuxCNC's MOD is never negative.
  std::string magnitude =
      fmt::format("ABS[{}] MOD ABS[{}]", expressions_.value(instruction.operands[0]).text,
                  expressions_.value(instruction.operands[1]).text);
  std::string a = expressions_.at(expressions_.value(instruction.operands[0]), Compared);
  choose(fmt::format("[{} LT 0]", a), fmt::format("[{} GE 0]", a), target,
         fmt::format("-[{}]", magnitude), fmt::format("[{}]", magnitude));
}

// ATAN[y]/[x] gives 0..360 or -180..180 degrees by a parameter; both become
// the IR's -pi..pi.
void MacroProgramPrinter::printArctangent(const ir::Instruction& instruction,
                                          const std::string& target) {
  std::string x = instruction.opcode == Opcode::Atan
                      ? dialect_.one
                      : expressions_.value(instruction.operands[1]).text;
  line(assignment(
      target, fmt::format("ATAN[{}]/[{}]", expressions_.value(instruction.operands[0]).text, x)));
  conditional(fmt::format("[{} GT 180.]", target), fmt::format("[{} LE 180.]", target),
              assignment(target, fmt::format("{}-360.", target)));
  line(assignment(target,
                  fmt::format("{}*{}", target, expressions_.constant(1 / degreesPerRadian))));
}

void MacroProgramPrinter::printSpindle(const ir::Instruction& instruction) {
  ValueId speed = instruction.operands[0];
  std::optional<double> literal = expressions_.constantOf(speed);
  line(fmt::format("S{} M3", literal ? fmt::format("{}", std::llround(*literal))
                                     : expressions_.operand(speed)));
  spindleOn_ = true;
}

// The tool change with the tool's diameter said, beside the block that
// names the tool or on a line of its own.
void MacroProgramPrinter::printTool(const ir::Instruction& instruction) {
  if (spindleOn_) {
    line("M5");
    spindleOn_ = false;
  }
  std::optional<double> diameter = expressions_.constantOf(instruction.operands[0]);
  std::string diameterText = diameter ? expressions_.coordinateLiteral(*diameter) : std::string();
  std::string onToolBlock;
  if (diameter && dialect_.diameterOnToolBlock) {
    onToolBlock = commentText(keyword("diameter") + " " + diameterText);
  }
  for (std::string& block :
       toolChangeBlocks(*options_.setup, std::llround(instruction.number), onToolBlock)) {
    line(std::move(block));
  }
  if (diameter && !dialect_.diameterOnToolBlock) {
    comment(keyword("tool diameter") + " " + diameterText);
  }
  toolNumber_ = std::llround(instruction.number);
  moves_.forget();
  moves_.beforeNextZ(lengthOffsetWords(
      *options_.setup, static_cast<int>(std::llround(instruction.number)), instruction.index));
}

// G39 at the corner the last move ended at: Fanuc in a block of its own
// with I J towards the next move's start, Mitsubishi on that move's block
// (controller_profile.h).
void MacroProgramPrinter::printCornerArc(const ir::Instruction& instruction) {
  if (options_.profile == nullptr || !options_.profile->cornerArcOnMoveBlock) {
    line(fmt::format("G39 I{} J{}", expressions_.coordinate(instruction.operands[0]),
                     expressions_.coordinate(instruction.operands[1])));
    return;
  }
  auto isMotionBlock = [](std::string_view text) {
    return text.starts_with("G1") || text.starts_with("G2") || text.starts_with("G3") ||
           text.starts_with("X") || text.starts_with("Y");
  };
  if (lines_.empty() || !isMotionBlock(lines_.back())) {
    errors_.push_back("a corner arc (G39) does not follow a move in the plane");
    return;
  }
  lines_.back() = "G39 " + lines_.back();
}

// G41/G42 D<register> or G40. With dynamic compensation (LinuxCNC) the
// tool's own register, the default, becomes `G41.1/G42.1 D<diameter>`:
// the diameter compiled with, in the program, so that no tool table entry
// need hold it; a register of its own (`tool N radius=R`) says the shop
// keeps the diameter in that entry of the tool table, read by `G41 D<R>`.
std::string MacroProgramPrinter::compensationWords(const ir::Instruction& instruction) {
  bool ownRegister = static_cast<long long>(instruction.index) == toolNumber_;
  if (instruction.number == 0 || !dialect_.dynamicCompensation || !ownRegister) {
    return compensationBlock(instruction.number, instruction.index);
  }
  return fmt::format("{} D{}", instruction.number > 0 ? "G41.1" : "G42.1",
                     expressions_.coordinateLiteral(2 * std::fabs(instruction.number)));
}

// move.nurbs: the G06.2 blocks of its table at the pass height; a weight
// or a height computed on the controller (a part parameter, a pass loop's
// height) is printed as its expression, R#3 and Z#4, as the syntax allows.
void MacroProgramPrinter::printNurbs(const ir::Instruction& instruction) {
  if (!dialect_.hasNurbsBlocks) { // lowered only for targets with NURBS blocks
    errors_.push_back(fmt::format("{} has no NURBS blocks of the G06.2 kind (move.nurbs)",
                                  dialect_.controllerName));
    return;
  }
  std::size_t count = instruction.operands.size() - 2;
  std::optional<ir::NurbsBlockData> data =
      ir::readNurbsMoveTable(function_.tables[instruction.index], count);
  if (!data) {
    errors_.push_back("G06.2: a NURBS move without its block data");
    return;
  }
  ValueId height = instruction.operands[0];
  std::optional<double> z = expressions_.constantOf(height);
  std::vector<double> weights;
  NurbsBlockOptions options;
  for (std::size_t k = 0; k < count; ++k) {
    ValueId weight = instruction.operands[2 + k];
    std::optional<double> literal = expressions_.constantOf(weight);
    weights.push_back(literal.value_or(1.0));
    options.weightVariables.push_back(literal ? "" : expressions_.operand(weight));
  }
  std::optional<geom::NurbsCurve> curve;
  try {
    curve = ir::nurbsMoveCurve(*data, 0, weights);
  } catch (const ir::InterpreterError& error) {
    errors_.push_back(fmt::format("G06.2: {}", error.what()));
    return;
  }
  std::string feed = moves_.word('F', instruction.operands[1], false);
  options.dialect = dialect_.nurbs;
  options.coordinateDecimals = dialect_.numbers.coordinateDecimals + (options_.inches ? 1 : 0);
  options.z = z.value_or(0);
  if (!z) { // the pass loop's height
    options.zCoordinate = expressions_.coordinate(height);
    options.zOperand = expressions_.operand(height);
  }
  options.feedText = feed.empty() ? moves_.state().words['F'].text : feed.substr(2);
  options.currentPosition = data->points.front() + Eigen::Vector3d(0, 0, options.z);
  NurbsBlocks blocks = writeNurbsBlocks(*curve, options);
  errors_.insert(errors_.end(), blocks.errors.begin(), blocks.errors.end());
  for (std::string& text : blocks.lines) {
    line(std::move(text));
  }
  moves_.forget(); // G06.2 is modal now, and the position is the curve's end
}

} // namespace cncc::backends
