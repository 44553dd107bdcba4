// A machine file (`cncc --machine FILE.toml`) describes one shop's machine:
// the target it runs, the controller profile of a macro target and the
// set-up blocks the printers write (machine_setup.h). Anything the file does
// not set keeps the target's built-in value. The schema (TOML):
//
//   name = "Shop VMC 3"                  # optional, for messages
//   description = "Fanuc 0i-MF, 20 tools" # optional
//   target = "fanuc"                     # required: fanuc, m80, linuxcnc,
//                                        # gcode, sinumerik or jit
//   [profile]                            # fanuc and m80 only, required there
//   extends = "fanuc"                    # a built-in profile: fanuc,
//                                        # fanuc-0i-small, m80
//   maximum_block_length = 128           # characters, 16 .. 1024
//   coordinate_decimals = 3              # 0 .. 6
//   least_input_increment = 0.001        # mm, > 0 and <= 1
//   maximum_program_number = 9999        # 1 .. 99999999
//   maximum_sequence_number = 99999      # 1 .. 99999999
//   maximum_loop_nesting = 3             # 1 .. the profile's DO identifiers
//   macro_word_abbreviations = false     # true: `cncc sim` reads WH for
//                                        # WHILE, SI for SIN, ... (the
//                                        # control must be known to)
//   [setup]                              # blocks; {placeholders} as noted
//   length_offset = "G43 H{length}"      # {length}; "" when the tool
//                                        # change activates the offset
//   tool_edge = "D{length}"              # {length} (Sinumerik's D)
//   work_offset = "G{code}"              # {code}: 54 .. 59; not empty
//   extended_work_offset = "G54.1 P{number}" # {number}; "": none
//   maximum_extended_work_offset = 48    # 1 .. 9999
//   coolant_flood = "M8"                 # no placeholders; "": none
//   coolant_mist = "M7"
//   coolant_through = "M88"              # "": the machine has none
//   coolant_off = "M9"
//   high_speed = true                    # false: no contouring blocks
//   contouring_on = "G05.1 Q1"           # {tolerance} (mm or inch)
//   contouring_off = "G05.1 Q0"
//   end_retract = ["G91 G28 Z0.", "G90"] # blocks before the spindle stops
//   start = ["{units} G17 G90 G40 G49 G80"] # after the header; {units} (G21
//                                        # or G20, G71 or G70) in one block;
//                                        # LinuxCNC also {blend}
//   tool_change = ["T{tool} M6"]         # {tool} in one block
//   end = ["M9"]                         # before M30 (M2, M99)
//   [program]
//   line_numbers = false                 # N on every block but headers and
//                                        # comment lines
//   line_number_start = 10               # 1 .. the maximum
//   line_number_increment = 10           # 1 .. 1000
//   line_number_maximum = 99999          # then from the start again; at
//                                        # most the profile's (fanuc, m80),
//                                        # 99999 (linuxcnc, gcode)
//   comments = true                      # false: only those the controller
//                                        # acts on (alarm messages, ...)
//   comment_case = "upper"               # or "as-written"
//   [limits]
//   maximum_feed = 10000                 # mm/min, > 0
//   maximum_spindle_speed = 12000        # rpm, > 0
//   [radius_offsets]                     # the tool radius offset registers
//   1 = 4.0                              # (D1 ..) as the shop measured them,
//   5 = 3.98                             # for `cncc sim` of programs with
//                                        # G41/G42; registers 1 .. 9999
//
// Every block must be a block of the target's dialect: words of a letter
// and a number and (comments) on the ISO targets, with no #-expressions;
// on Sinumerik also keywords (SUPA), NAME(args) calls, NAME=value and a
// `;` comment; and no longer than the profile's block length. Every problem
// is a diagnostic at the line and column of the key or value concerned.
#pragma once

#include "cncc/backends/controller_profile.h"
#include "cncc/backends/machine_setup.h"

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::backends {

struct MachineDiagnostic {
  int line = 0; // 1-based; 0 when the problem is the file as a whole
  int column = 0;
  std::string message;
  std::string code; // "machine-unknown-key", ...
};

struct MachineDescription {
  std::string name;
  std::string description;
  std::string target; // the -t it is for
  // The target's built-in setup with the file's fields over it.
  MachineSetup setup;
  // Macro targets (fanuc, m80): the profile named by `extends`, overridden.
  std::optional<ControllerProfile> profile;
  double maximumFeed = 0;         // mm/min; 0: no limit
  double maximumSpindleSpeed = 0; // rpm; 0: no limit
  // Register -> radius, what `D n` selects for G41/G42 in `cncc sim`.
  std::map<int, double> radiusOffsets;
};

// The largest tool radius offset register a machine file may set.
inline constexpr int maximumRadiusOffsetRegister = 9999;

// The machine described in the file at `path`; nullopt, with at least one
// diagnostic, when it cannot be read or is not valid. Never throws.
std::optional<MachineDescription> readMachineFile(const std::string& path,
                                                  std::vector<MachineDiagnostic>& diagnostics);
// The same from the file's text; `displayName` is the path in messages.
std::optional<MachineDescription> readMachineText(std::string_view text,
                                                  const std::string& displayName,
                                                  std::vector<MachineDiagnostic>& diagnostics);

// The targets a machine file may name.
bool isMachineTarget(std::string_view target);

} // namespace cncc::backends
