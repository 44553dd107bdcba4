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
#include "cncc/ir/curve_lap.h"
#include "cncc/ir/cut_geometry.h"
#include "cncc/ir/ir.h"
#include "cncc/ir/lowering_options.h"
#include "cncc/ir/passes.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace cncc::ir {

// A part parameter whose default the lowering read as a constant, and the
// first use that did.
struct FixedParameter {
  std::string name;
  frontend::SourceSpan use;
};

struct LoweredPart {
  Function function;
  // In the order first fixed; each also has Parameter::fixed set. Those the
  // lowering fixed: the legalisation bound-controller-steps may fix more
  // (Parameter::fixed and a parameter-fixed warning, no entry here).
  std::vector<FixedParameter> fixedParameters;
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

// A lap's points that could not be chosen, as a diagnostic at its source.
void reportCurveLapError(const CurveLapError& error, frontend::DiagnosticEngine& diagnostics);
// Reports the warnings the legalisations left in the function (spline-as-
// chords only where `reportSplineAsChords`), and clears them.
void reportLegalisationWarnings(Function& function, frontend::DiagnosticEngine& diagnostics,
                                bool reportSplineAsChords = true);
// runCurveLegalisation, its warnings reported; where a pass fails, the
// warnings of those before it, then its error (false).
bool legaliseCurves(Function& function, frontend::DiagnosticEngine& diagnostics,
                    const AfterPassCallback& afterPass = {}, bool reportSplineAsChords = true);

enum class PartUnits { Millimetres, Inches };
// The `units` statement at the top of the part's body (millimetres without one).
PartUnits partUnits(const frontend::PartItem& part);

} // namespace cncc::ir
