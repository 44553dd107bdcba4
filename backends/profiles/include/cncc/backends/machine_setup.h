// The blocks a machine needs around the cutting moves, as data: the tool
// length offset after a tool change, the work offset, coolant and the
// controller's high-speed contouring mode, each a block with {placeholders}
// per dialect (TARGETS.md, "v1"). Every printer asks its setup for the text
// instead of writing the codes itself, so that a machine can change them.
#pragma once

#include "cncc/ir/ir.h"
#include "cncc/ir/tool_path.h"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::backends {

// `N` numbers on the blocks of a program: from `start` in steps of
// `increment`, starting again at `start` after `maximum`.
struct LineNumbering {
  bool enabled = false;
  int start = 10;
  int increment = 10;
  int maximum = 99999;
};

// How comment text is written: in capitals (what older Fanuc and Mitsubishi
// tape code has) or as the source has it.
enum class CommentCase { Upper, AsWritten };

struct MachineSetup {
  std::string dialect; // "fanuc", "m80", "sinumerik", "linuxcnc", "gcode"
  // Joined to the first Z move after a tool change, {length} the register
  // (the tool number when the part gives none). Empty: the tool change
  // itself activates the offset (Sinumerik's D, see toolEdge).
  std::string lengthOffset;
  // Sinumerik: the cutting edge `D{length}` activated with the tool, D1
  // when the part gives no register.
  std::string toolEdge;
  std::string workOffset;             // {code}: "G{code}"
  std::string extendedWorkOffset;     // {number}: "G54.1 P{number}"; empty: none
  int maximumExtendedWorkOffset = 48; // P1 .. P48, the common option
  std::string coolantFlood = "M8";
  std::string coolantMist = "M7";
  std::string coolantThrough; // machine-specific (M88, M51, ...); empty: none
  std::string coolantOff = "M9";
  // {tolerance} in millimetres or inches as the program is; empty: the
  // dialect has no such mode.
  std::string contouringOn;
  std::string contouringOff;
  // The blocks that retract Z in machine coordinates at the program's end,
  // before the spindle stops and the program ends.
  std::vector<std::string> endRetract;
  // The blocks after the program's header: {units} the unit word (G21/G20,
  // G71/G70), {blend} LinuxCNC's default blending tolerance.
  std::vector<std::string> start;
  // The blocks of a tool change, {tool} the tool number; the printer adds
  // its words (Sinumerik's D) and comment to the block with {tool}.
  std::vector<std::string> toolChange;
  // Blocks before the end of the program (after the retract and M5).
  std::vector<std::string> end;
  LineNumbering lineNumbers;
  bool comments = true;
  CommentCase commentCase = CommentCase::Upper;
};

// The built-in setup of a target (the names `-t` takes); the plain one
// (gcode) for a name it does not know.
const MachineSetup& builtinMachineSetup(std::string_view target);

// The start blocks for a program in inches or millimetres; `blend` is the
// value of {blend}.
std::vector<std::string> startBlocks(const MachineSetup& setup, bool inches,
                                     std::string_view blend = "");
// The blocks that change to `tool`, `additions` (words, a comment) joined
// to the block that names the tool.
std::vector<std::string> toolChangeBlocks(const MachineSetup& setup, long long tool,
                                          std::string_view additions);

// The words that activate the length offset of `tool` with this register (0:
// the tool's own number), empty when the tool change does it.
std::string lengthOffsetWords(const MachineSetup& setup, int tool, std::uint32_t lengthRegister);
// `D..` for a tool change on a machine that activates the offset with it.
std::string toolEdgeWords(const MachineSetup& setup, std::uint32_t lengthRegister);
// The block that selects the work offset `code` (54 .. 59, or 54.1 with
// `extended` its P number); empty when the machine has none.
std::string workOffsetBlock(const MachineSetup& setup, double code, std::uint32_t extended);
// The block that sets coolant so; empty when the machine has no code for it.
std::string coolantBlock(const MachineSetup& setup, ir::CoolantMode mode);
// The block that sets high-speed contouring for `tolerance` (0: off); empty
// when the dialect has none. `number` prints the tolerance as the program
// prints numbers.
std::string contouringBlock(const MachineSetup& setup, double tolerance, std::string_view number);

// The block that switches the controller's cutter radius compensation on
// (G41 for `offset` > 0, left of the direction of travel; G42 right) with
// the radius of register D`offsetRegister`, or off (G40, `offset` 0): the
// same on Fanuc, Mitsubishi, LinuxCNC and plain G-code.
std::string compensationBlock(double offset, std::uint32_t offsetRegister);

// The blocks of an origin, coolant, contouring or move.home op, for the
// printers that print the IR (none for a code the machine does not have);
// `tolerance` is the contouring tolerance as printed.
std::vector<std::string> setupBlocks(const MachineSetup& setup, const ir::Instruction& instruction,
                                     std::string_view tolerance);

// The block of an origin, coolant or contouring event, for the printers
// that print the executed path; `tolerance` is its tolerance as printed.
std::string settingBlock(const MachineSetup& setup, const ir::MachineEvent& event,
                         std::string_view tolerance);

} // namespace cncc::backends
