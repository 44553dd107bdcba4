// Siemens Sinumerik 840D programs computed on the host: the part's tool path
// as G0/G1 blocks, each cut's curve as the spline blocks its method= asks
// for (BSPLINE with PW/PL, CSPLINE or ASPLINE through knots on the curve), or
// as G1 chords.
#pragma once

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

// How the A and C splines begin and end.
enum class SinumerikTransitions {
  // BTAN where the block before the spline moves in XY (the last lap of a
  // ramp), BNAT after a vertical plunge; ENAT before the retract.
  Automatic,
  Natural, // BNAT ENAT
  Auto,    // BAUTO EAUTO
};

struct SinumerikOptions {
  std::string sourceName; // for the header comment, e.g. "s_profile.cdl"
  std::string partName;
  std::string programName = "PART"; // NAME of NAME.MPF and of its subprograms
  bool inches = false;              // G70 instead of G71
  // The most decimals a coordinate is printed with. The controller keeps
  // 10^decimals increments per mm only if its computational resolution
  // ($MN_INT_INCR_PER_MM) is at least that; the rounding is taken off the
  // tolerance before splines are fitted.
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

// What the writer did with one cut.
struct SinumerikCutSummary {
  std::string method;            // linear, bspline, cspline, aspline
  std::size_t blocksPerPass = 0; // spline blocks (control points or knots), or G1 blocks
  double modelledDeviation = 0;  // of the spline from the curve, as the writer modelled it
  bool exact = false;            // a NURBS source written as it is
  std::string note;              // why a NURBS was re-fitted, if it was
};

struct SinumerikProgram {
  std::string text;
  // The cut each line of the main program belongs to (index 0 is line 1).
  std::vector<std::optional<std::size_t>> cutOfLine;
  std::vector<SinumerikCutSummary> cuts;
  // The CDL span each line of `text` was printed from.
  std::vector<frontend::SourceSpan> lineSpans;
};

// A cut the controller cannot be given within its tolerance.
class SinumerikError : public std::runtime_error {
public:
  SinumerikError(std::size_t cut, const std::string& message)
      : std::runtime_error(message), cut_(cut) {}
  std::size_t cut() const { return cut_; }

private:
  std::size_t cut_;
};

// `10`, `0.5`, `-1.25`: at most `decimals` decimals, no trailing zeros and
// no trailing point, never `-0`.
std::string formatSinumerikNumber(double value, int decimals);

// How to lower a part for this writer: spline cuts reach it as curves, and
// chords leave room for the rounding to `options.decimals`, so that the
// writer prints the tool path's chords as they are.
ir::LoweringOptions sinumerikLoweringOptions(const SinumerikOptions& options = {});

// One cut: its true curve and how it asks to be cut.
struct SinumerikCut {
  ir::CutGeometry geometry;
  // The cut's method= word: linear, bspline, nurbs (as bspline), cspline,
  // aspline; empty for linear.
  std::string method;
};

// The program for `path` (the IR's tool path) with the curves of `cuts`
// (indexed as the path's CutBegin events). Throws SinumerikError.
SinumerikProgram writeSinumerik(const ir::ToolPath& path, std::span<const SinumerikCut> cuts,
                                const SinumerikOptions& options);

} // namespace cncc::backends
