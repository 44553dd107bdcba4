// Siemens Sinumerik 840D programs computed on the host: the part's tool path
// as G0/G1/G2/G3 blocks, and each move.spline the lowering fitted as the
// BSPLINE (PW/PL), CSPLINE or ASPLINE blocks its table holds.
#pragma once

#include "cncc/backends/line_spans.h"
#include "cncc/backends/machine_setup.h"
#include "cncc/ir/cut_geometry.h"
#include "cncc/ir/lowering_options.h"
#include "cncc/ir/tool_path.h"

#include <cstddef>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace cncc::backends {

// How the A and C splines begin and end (the lowering fits them so).
using SinumerikTransitions = ir::SplineEnds;

struct SinumerikOptions {
  std::string sourceName; // for the header comment, e.g. "s_profile.cdl"
  std::string partName;
  std::string programName = "PART"; // NAME of NAME.MPF and of its subprograms
  bool inches = false;              // G70 instead of G71
  // The most decimals a coordinate is printed with. The controller keeps
  // 10^decimals increments per mm only if its computational resolution
  // ($MN_INT_INCR_PER_MM) is at least that; the rounding is taken off the
  // tolerance before splines are fitted (sinumerikLoweringOptions).
  int decimals = 5;
  bool soft = true; // SOFT: jerk-limited acceleration, which spline paths want
  SinumerikTransitions transitions = SinumerikTransitions::Automatic;
  // The knots of each cut in a subprogram NAME_CUTn.SPF called once per pass
  // (the published programs' layout); the subprograms follow the main program
  // in the same text, each after a `%_N_NAME_SPF` header as in a Sinumerik
  // archive.
  bool subprograms = false;
  MachineSetup setup = builtinMachineSetup("sinumerik");
};

// What the writer printed for one cut.
struct SinumerikCutSummary {
  std::string method;            // linear, bspline, cspline, aspline
  std::size_t blocksPerPass = 0; // spline blocks (control points or knots), or G1 blocks
};

struct SinumerikProgram {
  std::string text;
  // The cut each line of the main program belongs to (index 0 is line 1).
  std::vector<std::optional<std::size_t>> cutOfLine;
  std::vector<SinumerikCutSummary> cuts;
  // Where each line of `text` was printed from.
  LineOrigins lineOrigins;
};

// `10`, `0.5`, `-1.25`: at most `decimals` decimals, no trailing zeros and
// no trailing point, never `-0`.
std::string formatSinumerikNumber(double value, int decimals);

// How to lower a part for this writer: spline cuts as move.spline blocks
// fitted on the printed grid of `options.decimals` with its transitions,
// chords leaving room for the rounding, so that the writer prints the IR's
// moves as they are.
ir::LoweringOptions sinumerikLoweringOptions(const SinumerikOptions& options = {});

// The program for `path` (the IR's tool path, whose move.spline chords
// name their blocks in `tables`, the function's tables) with `cutCount`
// cuts (indexed as the path's CutBegin events).
SinumerikProgram writeSinumerik(const ir::ToolPath& path,
                                std::span<const std::vector<double>> tables, std::size_t cutCount,
                                const SinumerikOptions& options);

} // namespace cncc::backends
