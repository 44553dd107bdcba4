// LinuxCNC (RS274NGC) programs that evaluate the part on the controller:
// IR loops become `o<n> while [..]` .. `o<n> endwhile`, ifs `o<n> if` ..
// `o<n> else` .. `o<n> endif` (a unique o-number each), IR values numbered
// parameters #31.. (ir::allocateVariables) or inline expressions, and the
// part parameters named globals `#<_depth>` set at the top of the program,
// where the operator edits them.
//
// Layout of a main program: comments naming the source, the part and each
// parameter with its default; the parameters; the modal line
// `G21 G17 G90 G40 G49 G80 G94 G64 P<blend>`; the tables; tool and spindle;
// the moves; `M5`, `M2`. With `callable` (--macro) the program is the
// subroutine `o<part> sub` .. `o<part> endsub` (LinuxCNC finds it in
// `<part>.ngc`), its parameters the call arguments #1.. in order, and the
// call is given in the header: `o<s_profile> call [3] [1] [3]`.
//
// A program that cannot fit LinuxCNC (a line of more than 255 characters,
// more than 30 call arguments, more numbered parameters than #31-#5000) is
// refused with the limit and the count named.
#pragma once

#include "cncc/backends/line_spans.h"
#include "cncc/backends/machine_setup.h"
#include "cncc/ir/cut_geometry.h"
#include "cncc/ir/ir.h"
#include "cncc/ir/lowering_options.h"

#include <string>
#include <vector>

namespace cncc::backends {

inline constexpr int linuxcncMaximumLineLength = 255;
// The significant digits of the program's constants (`0.959503912453`).
inline constexpr int linuxcncSignificantDigits = 12;
// The decimals of the program's coordinates, in millimetres and in inches.
inline constexpr int linuxcncCoordinateDecimals(bool inches) {
  return inches ? 6 : 5;
}
inline constexpr int linuxcncMaximumCallArguments = 30;
inline constexpr int linuxcncFirstGlobal = 31;
inline constexpr int linuxcncLastGlobal = 5000;

struct LinuxcncProgramOptions {
  std::string sourceName; // for the header comment, e.g. "s_profile.cdl"
  std::string partName;
  bool inches = false;
  bool callable = false; // --macro: an o<part> subroutine taking the parameters as arguments
  // G64 P: how far the controller may round a corner while blending moves
  // (and merge nearly collinear ones); the part's smallest tolerance.
  double blendTolerance = 0.01;
  MachineSetup setup = builtinMachineSetup("linuxcnc");
};

struct LinuxcncProgram {
  std::string text;                // empty when errors is not
  std::vector<std::string> errors; // each names the limit and the count
  // Where each line of `text` was printed from (an invalid span: before any
  // statement).
  LineOrigins lineOrigins;
};

// The named parameter of each part parameter, without `#<>`: `_depth`;
// lower case (LinuxCNC's names are), and never one of LinuxCNC's read-only
// predefined names (`_x`, `_feed`, ...) or another parameter's name, which
// get a trailing `_`.
std::vector<std::string> linuxcncParameterNames(const std::vector<ir::Parameter>& parameters);

// G64 P for a part: the smallest tolerance a cut promises (the lowering's
// default when none does), so that blending never strays further than the
// chords may.
double linuxcncBlendTolerance(const std::vector<ir::CutGeometry>& cuts);

LinuxcncProgram writeLinuxcncProgram(const ir::Function& function,
                                     const LinuxcncProgramOptions& options);

} // namespace cncc::backends
