// The part's cut table: for each `cut.begin n` of a function, the cut's true
// curve, its tolerance budget and how its moves use arcs. What verify
// measures the executed path against, what plots draw, and what the
// legalisations read of the cut's tolerance and of the target's rounding.
#pragma once

#include "cncc/frontend/source_span.h"
#include "cncc/geom/curve.h"
#include "cncc/ir/spline_blocks_kind.h"
#include "cncc/ir/tolerance_budget.h"

#include <memory>
#include <optional>
#include <string>

namespace cncc::ir {

enum class CutArcs { None, Native, Fitted };

// The curve blocks a cut's target prints where its method= asks for them
// (choose-curve-blocks): none, Fanuc/Mitsubishi G06.2 NURBS blocks,
// Heidenhain SPL cubic spans, or Sinumerik spline blocks.
enum class PrintedBlocks { None, Nurbs, Polynomial, Spline };

// One cut of the part: what `cut.begin index` refers to.
struct CutGeometry {
  // The true curve in part coordinates, transforms applied (XY plane). For
  // a cut beside its curve (side=), the path the tool's centre must take.
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
  // Cut as spline blocks (move.spline): how they were found, as the
  // program's comment says it; empty otherwise.
  std::string splineBlocks = {};
  // A cut beside its curve (side=left|right): the curve as drawn, in part
  // coordinates, and the tool radius it was offset by; the contour the tool
  // leaves is measured against it. Null (radius 0) for a cut on its curve.
  std::shared_ptr<const geom::Curve> drawnCurve = nullptr;
  double toolRadius = 0;
  // The target's printed grid (its least input increment; 0: none), and
  // where the controller computes the program's numbers (a target that runs
  // loops), the significant digits it reads their literals with (0: as
  // exactly as the host); nullopt where the host computes every number the
  // program prints. The lowering sets them for every cut.
  double increment = 0;
  std::optional<int> controllerDigits = std::nullopt;
  // The blocks the target prints, and how its A and C splines begin and end.
  PrintedBlocks printedBlocks = PrintedBlocks::None;
  SplineEnds splineEnds = SplineEnds::Automatic;
  // Where the method= is written (where choose-curve-blocks warns that it
  // cuts chords); not in the IR's text, as `span`.
  frontend::SourceSpan methodSpan = {};

  ToleranceBudget budget() const { return {tolerance, increment}; }
};

} // namespace cncc::ir
