// Lowering from the checked AST to the IR: one Function per part.
//
// The part's parameters become the function's parameters, their values (the
// defaults, or -D overrides) as defaults. Tool, spindle, feed and safe height
// become effects and lowered values; each cut becomes its passes: a rapid
// over the start at the safe height, a plunge at the cut's feed, a loop over
// a table of curve parameters chosen at compile time (chord tolerance,
// samples= or spacing=) that evaluates the curve point in IR arithmetic, and
// a retract. What this version cannot lower yet is an error diagnostic at its
// source span; lowering never skips a construct silently.
#pragma once

#include "cncc/frontend/diagnostics.h"
#include "cncc/frontend/sema.h"
#include "cncc/geom/curve.h"
#include "cncc/ir/ir.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace cncc::ir {

struct LoweringOptions {
  // The chord tolerance of a cut without tolerance=, samples= or spacing=.
  double defaultTolerance = 0.01;
  // Whether the target interpolates splines (method=cspline, aspline,
  // bspline, nurbs) itself. Without it such a cut is cut as straight feed
  // moves within its tolerance, with a spline-as-chords warning.
  bool splineInterpolation = false;
  // Fanuc/Mitsubishi G06.2: a method=nurbs cut is lowered as one marked feed
  // per pass that the printer prints as NURBS blocks (nurbs_cuts.cpp).
  bool nurbsBlocks = false;
  // Heidenhain SPL: a spline-method cut (cspline, aspline, bspline, nurbs) is
  // lowered as move.polynomial cubic spans (polynomial_cuts.cpp).
  bool polynomialBlocks = false;
  // Targets that print host-fitted G02/G03 arcs: a cut that wants arcs
  // (arcs=true, or arcsOnEveryCut without arcs=false) is lowered as the
  // fitted move.arc ops on the printed grid (arc_cuts.cpp).
  bool arcBlocks = false;
  bool arcsOnEveryCut = false; // --arcs
  // Controller-side targets (macro programs): each cut becomes loops the
  // controller runs over uniform parameter steps, a pass loop over the sweep
  // and no constant tables; what depends on part parameters (step counts
  // included) is computed on the controller. See controller_cuts.cpp.
  bool controllerLoops = false;
  // The controller's least input increment (mm or inch; 0: none). Its
  // rounding of every executed coordinate, half an increment per axis, is
  // taken from the tolerance before the chord error is chosen.
  double coordinateIncrement = 0;
  // How deep the controller nests loops (0: no limit). A `for` run on the
  // controller that would nest deeper is unrolled instead.
  int maximumLoopNesting = 0;
  // What the machine's set-up has: `origin G54.1 Pn` up to this n (0: no
  // extended work offsets), and a code for through-spindle coolant.
  int maximumExtendedWorkOffset = 0;
  bool throughSpindleCoolant = false;
  // The machine's largest feed (mm/min, whatever the part's units) and
  // spindle speed (rpm); 0: no limit. A constant beyond it is an error at
  // the statement that sets it.
  double maximumFeed = 0;
  double maximumSpindleSpeed = 0;
};

enum class CutArcs { None, Native, Fitted };

// One cut of the part: what `cut.begin index` refers to.
struct CutGeometry {
  // The true curve in part coordinates, transforms applied (XY plane).
  std::shared_ptr<const geom::Curve> curve;
  // The cut's promise in mm; NaN when samples= or spacing= chose the points.
  double tolerance = 0;
  // The `curve` statement.
  frontend::SourceSpan span;
  // The cut's method= word (linear, aspline, bspline, cspline, nurbs); empty without one.
  std::string method;
  // How its passes use move.arc: not at all, for the curve's own arc pieces
  // (native circular interpolation), or as arcs fitted to the curve.
  CutArcs arcMoves = CutArcs::None;
};

// A part parameter whose default the lowering read as a constant, and the
// first use that did.
struct FixedParameter {
  std::string name;
  frontend::SourceSpan use;
};

struct LoweredPart {
  Function function;
  // In the order first fixed; each also has Parameter::fixed set.
  std::vector<FixedParameter> fixedParameters;
  // Indexed by cut.begin; a cut in an unrolled loop has one per iteration.
  std::vector<CutGeometry> cuts;
};

// The lowered part, or nullopt after an error diagnostic.
std::optional<LoweredPart> lowerPartWithCuts(const frontend::CheckedProgram& program,
                                             const frontend::PartItem& part,
                                             frontend::DiagnosticEngine& diagnostics,
                                             const LoweringOptions& options = {});
// The same, the function only.
std::optional<Function> lowerPart(const frontend::CheckedProgram& program,
                                  const frontend::PartItem& part,
                                  frontend::DiagnosticEngine& diagnostics,
                                  const LoweringOptions& options = {});

enum class PartUnits { Millimetres, Inches };
// The `units` statement at the top of the part's body (millimetres without one).
PartUnits partUnits(const frontend::PartItem& part);

} // namespace cncc::ir
