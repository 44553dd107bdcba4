#include "cncc/backends/machine_setup.h"

#include "cncc/ir/interpreter.h"

#include <fmt/format.h>

#include <array>

namespace cncc::backends {

namespace {

MachineSetup isoSetup(std::string dialect) {
  MachineSetup setup;
  setup.dialect = std::move(dialect);
  setup.lengthOffset = "G43 H{length}";
  setup.workOffset = "G{code}";
  setup.endRetract = {"G91 G28 Z0.", "G90"};
  setup.start = {"{units} G17 G90 G40 G49 G80"};
  setup.toolChange = {"T{tool} M6"};
  return setup;
}

std::array<MachineSetup, 5> makeBuiltinSetups() {
  // Fanuc 0i-F / 30i: AI contour control.
  MachineSetup fanuc = isoSetup("fanuc");
  fanuc.extendedWorkOffset = "G54.1 P{number}";
  fanuc.contouringOn = "G05.1 Q1";
  fanuc.contouringOff = "G05.1 Q0";
  // Mitsubishi M80: high-speed high-accuracy control II.
  MachineSetup m80 = isoSetup("m80");
  m80.extendedWorkOffset = "G54.1 P{number}";
  m80.contouringOn = "G05 P10000";
  m80.contouringOff = "G05 P0";
  // LinuxCNC: path blending within the tolerance, collinear moves merged.
  MachineSetup linuxcnc = isoSetup("linuxcnc");
  linuxcnc.contouringOn = "G64 P{tolerance} Q{tolerance}";
  linuxcnc.contouringOff = "G64";
  linuxcnc.endRetract = {"G53 G0 Z0"};
  linuxcnc.start = {"{units} G17 G90 G40 G49 G80 G94 G64 P{blend}"};
  linuxcnc.commentCase = CommentCase::AsWritten;
  MachineSetup sinumerik;
  sinumerik.dialect = "sinumerik";
  sinumerik.toolEdge = "D{length}";
  sinumerik.workOffset = "G{code}";
  sinumerik.contouringOn = "CYCLE832({tolerance}, _FINISH, 1)";
  sinumerik.contouringOff = "CYCLE832()";
  sinumerik.endRetract = {"SUPA G0 Z0 D0"};
  sinumerik.start = {"G17 G90 {units}"};
  sinumerik.toolChange = {"T=\"T{tool}\"", "M6"};
  sinumerik.commentCase = CommentCase::AsWritten;
  // Plain ISO G-code: no high-speed mode is common to all machines.
  MachineSetup gcode = isoSetup("gcode");
  gcode.start = {"{units}", "G17 G90", "G40 G49 G80"};
  gcode.toolChange = {"T{tool} M06"};
  return {std::move(fanuc), std::move(m80), std::move(linuxcnc), std::move(sinumerik),
          std::move(gcode)};
}

std::string formatted(const std::string& pattern, std::string_view name, std::string_view value) {
  return fmt::format(fmt::runtime(pattern), fmt::arg(std::string(name).c_str(), value));
}

} // namespace

std::vector<std::string> startBlocks(const MachineSetup& setup, bool inches,
                                     std::string_view blend) {
  bool sinumerik = setup.dialect == "sinumerik";
  std::string_view units = sinumerik ? (inches ? "G70" : "G71") : (inches ? "G20" : "G21");
  std::vector<std::string> blocks;
  for (const std::string& pattern : setup.start) {
    blocks.push_back(
        fmt::format(fmt::runtime(pattern), fmt::arg("units", units), fmt::arg("blend", blend)));
  }
  return blocks;
}

std::vector<std::string> toolChangeBlocks(const MachineSetup& setup, long long tool,
                                          std::string_view additions) {
  std::vector<std::string> blocks;
  bool added = false;
  for (const std::string& pattern : setup.toolChange) {
    std::string block = formatted(pattern, "tool", std::to_string(tool));
    if (!added && pattern.find("{tool}") != std::string::npos && !additions.empty()) {
      block += additions.front() == ' ' ? "" : " ";
      block += additions;
      added = true;
    }
    blocks.push_back(std::move(block));
  }
  return blocks;
}

const MachineSetup& builtinMachineSetup(std::string_view target) {
  static const std::array<MachineSetup, 5> setups = makeBuiltinSetups();
  for (const MachineSetup& setup : setups) {
    if (setup.dialect == target) {
      return setup;
    }
  }
  return setups.back();
}

std::string lengthOffsetWords(const MachineSetup& setup, int tool, std::uint32_t lengthRegister) {
  if (setup.lengthOffset.empty()) {
    return "";
  }
  std::string value = std::to_string(lengthRegister == 0 ? tool : static_cast<int>(lengthRegister));
  return formatted(setup.lengthOffset, "length", value);
}

std::string toolEdgeWords(const MachineSetup& setup, std::uint32_t lengthRegister) {
  if (setup.toolEdge.empty()) {
    return "";
  }
  return formatted(setup.toolEdge, "length",
                   std::to_string(lengthRegister == 0 ? 1 : lengthRegister));
}

std::string workOffsetBlock(const MachineSetup& setup, double code, std::uint32_t extended) {
  if (extended != 0) {
    return setup.extendedWorkOffset.empty()
               ? ""
               : formatted(setup.extendedWorkOffset, "number", std::to_string(extended));
  }
  return formatted(setup.workOffset, "code", fmt::format("{}", code));
}

std::string coolantBlock(const MachineSetup& setup, ir::CoolantMode mode) {
  switch (mode) {
  case ir::CoolantMode::Flood:
    return setup.coolantFlood;
  case ir::CoolantMode::Mist:
    return setup.coolantMist;
  case ir::CoolantMode::Through:
    return setup.coolantThrough;
  case ir::CoolantMode::Off:
    break;
  }
  return setup.coolantOff;
}

std::string compensationBlock(double offset, std::uint32_t offsetRegister) {
  if (offset == 0) {
    return "G40";
  }
  return fmt::format("{} D{}", offset > 0 ? "G41" : "G42", offsetRegister);
}

std::string contouringBlock(const MachineSetup& setup, double tolerance, std::string_view number) {
  if (tolerance == 0) {
    return setup.contouringOff;
  }
  return setup.contouringOn.empty() ? "" : formatted(setup.contouringOn, "tolerance", number);
}

std::vector<std::string> setupBlocks(const MachineSetup& setup, const ir::Instruction& instruction,
                                     std::string_view tolerance) {
  if (instruction.opcode == ir::Opcode::Home) {
    return setup.endRetract;
  }
  std::string text = settingBlock(
      setup, ir::settingEvent(instruction.opcode, instruction.number, instruction.index),
      tolerance);
  return text.empty() ? std::vector<std::string>{} : std::vector<std::string>{std::move(text)};
}

std::string settingBlock(const MachineSetup& setup, const ir::MachineEvent& event,
                         std::string_view tolerance) {
  switch (event.kind) {
  case ir::MachineEvent::Kind::Origin:
    return workOffsetBlock(setup, event.number, event.offsetRegister);
  case ir::MachineEvent::Kind::Coolant:
    return coolantBlock(setup, static_cast<ir::CoolantMode>(event.number));
  case ir::MachineEvent::Kind::Contouring:
    return contouringBlock(setup, event.number, tolerance);
  default:
    return "";
  }
}

} // namespace cncc::backends
