#include "cncc/ir/printer.h"

#include "curve_table_text.h"
#include "cut_table_text.h"
#include "ir_text.h"

#include <cmath>
#include <fmt/format.h>
#include <iterator>
#include <map>

namespace cncc::ir {

namespace {

constexpr std::string_view curveSamplingNames[] = {
    "chords", "samples",      "spacing",       "arcs",
    "steps",  "nurbs-blocks", "spline-blocks", "polynomial-blocks"};

} // namespace

std::string_view curveSamplingName(CurveSampling sampling) {
  return curveSamplingNames[static_cast<std::size_t>(sampling)];
}

std::optional<CurveSampling> curveSamplingNamed(std::string_view name) {
  for (std::size_t i = 0; i < std::size(curveSamplingNames); ++i) {
    if (curveSamplingNames[i] == name) {
      return static_cast<CurveSampling>(i);
    }
  }
  return std::nullopt;
}

namespace {

using text::quoted;

class Printer {
public:
  explicit Printer(const Function& function) : function_(function) {}

  std::string print() {
    out_ += fmt::format("func @{}(", function_.name);
    for (std::size_t i = 0; i < function_.parameters.size(); ++i) {
      const Parameter& parameter = function_.parameters[i];
      out_ += fmt::format("{}{} = {}{}", i == 0 ? "" : ", ", parameter.name, parameter.defaultValue,
                          parameter.fixed ? " fixed" : "");
    }
    out_ += ") {\n";
    for (std::size_t i = 0; i < function_.tables.size(); ++i) {
      out_ += fmt::format("  table @{} = [{}]\n", i, fmt::join(function_.tables[i], ", "));
    }
    for (std::size_t i = 0; i < function_.curves.size(); ++i) {
      out_ += curveEntryText(function_.curves, i);
    }
    for (std::size_t i = 0; i < function_.cuts.size(); ++i) {
      out_ += cutEntryText(i, function_.cuts[i]);
    }
    printRegion(function_.body, 1);
    out_ += "}\n";
    return out_;
  }

private:
  std::string name(ValueId value) {
    auto [entry, inserted] = names_.try_emplace(value.index, names_.size());
    return fmt::format("%{}", entry->second);
  }

  std::string operands(const Instruction& instruction) {
    std::string text;
    for (std::size_t i = 0; i < instruction.operands.size(); ++i) {
      text += (i == 0 ? "" : ", ") + name(instruction.operands[i]);
    }
    return text;
  }

  void printRegion(const Region& region, int depth) {
    for (InstructionId id : region.instructions) {
      printInstruction(function_.instructions[id], depth);
    }
  }

  void printInstruction(const Instruction& instruction, int depth) {
    std::string indent(static_cast<std::size_t>(depth) * 2, ' ');
    std::string_view spelling = opcodeInfo(instruction.opcode).spelling;
    std::string operandText = operands(instruction);
    std::string result = instruction.result.valid() ? name(instruction.result) + " = " : "";
    switch (instruction.opcode) {
    case Opcode::Const:
      out_ += fmt::format("{}{}const {}\n", indent, result, instruction.number);
      return;
    case Opcode::ConstBool:
      out_ += fmt::format("{}{}const.bool {}\n", indent, result,
                          instruction.number != 0 ? "true" : "false");
      return;
    case Opcode::Param:
      out_ += fmt::format("{}{}param {}\n", indent, result,
                          function_.parameters[instruction.index].name);
      return;
    case Opcode::TableLoad:
    case Opcode::Nurbs:
    case Opcode::Spline:
      out_ +=
          fmt::format("{}{}{} @{}, {}\n", indent, result, spelling, instruction.index, operandText);
      return;
    case Opcode::Tool:
      out_ += fmt::format("{}tool {} length {}, {}\n", indent, instruction.number,
                          instruction.index, operandText);
      return;
    case Opcode::Origin:
      out_ += instruction.index == 0
                  ? fmt::format("{}origin {}\n", indent, instruction.number)
                  : fmt::format("{}origin {} {}\n", indent, instruction.number, instruction.index);
      return;
    case Opcode::Coolant:
      out_ += fmt::format("{}coolant {}\n", indent,
                          coolantModeName(static_cast<CoolantMode>(instruction.index)));
      return;
    case Opcode::Home:
      out_ += fmt::format("{}move.home\n", indent);
      return;
    case Opcode::Contouring:
      out_ += instruction.number == 0
                  ? fmt::format("{}contouring off\n", indent)
                  : fmt::format("{}contouring {}\n", indent, instruction.number);
      return;
    case Opcode::Compensation:
      out_ += instruction.number == 0
                  ? fmt::format("{}compensation off\n", indent)
                  : fmt::format("{}compensation {} {} {}\n", indent,
                                instruction.number > 0 ? "left" : "right", instruction.index,
                                std::fabs(instruction.number));
      return;
    case Opcode::Comment:
    case Opcode::Alarm:
      out_ += fmt::format("{}{} {}\n", indent, spelling, quoted(instruction.text));
      return;
    case Opcode::CutBegin:
      out_ += fmt::format("{}cut.begin {}\n", indent, instruction.index);
      return;
    case Opcode::Arc:
      out_ += fmt::format(
          "{}move.arc {} {}\n", indent,
          instruction.index == static_cast<std::uint32_t>(ArcTurn::Clockwise) ? "cw" : "ccw",
          operandText);
      return;
    case Opcode::Loop:
      out_ += fmt::format("{}{}loop {} {{\n", indent, result, operandText);
      printRegion(instruction.regions[0], depth + 1);
      out_ += indent + "}\n";
      return;
    case Opcode::CurveLap:
      out_ +=
          fmt::format("{}{}curve.lap @{}, {} {{\n", indent, result, instruction.index, operandText);
      for (std::size_t region = 0; region < instruction.regions.size(); ++region) {
        if (region > 0) {
          out_ += indent + "} piece {\n";
        }
        printRegion(instruction.regions[region], depth + 1);
      }
      out_ += indent + "}\n";
      return;
    case Opcode::If:
      out_ += fmt::format("{}if {} {{\n", indent, operandText);
      printRegion(instruction.regions[0], depth + 1);
      if (!instruction.regions[1].instructions.empty()) {
        out_ += indent + "} else {\n";
        printRegion(instruction.regions[1], depth + 1);
      }
      out_ += indent + "}\n";
      return;
    default:
      out_ += fmt::format("{}{}{} {}\n", indent, result, spelling, operandText);
      return;
    }
  }

  const Function& function_;
  std::string out_;
  std::map<std::uint32_t, std::size_t> names_;
};

} // namespace

std::string printFunction(const Function& function) {
  return Printer(function).print();
}

} // namespace cncc::ir
