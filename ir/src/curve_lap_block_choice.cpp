// `choose-curve-blocks`: the laps whose entry asks for curve blocks (a cut
// whose method= is a spline: CurveTableEntry::blocksAsked, the chords or
// steps the lowering gives every target) cut as the blocks their cut's
// target prints (CutGeometry::printedBlocks), where those can follow it:
// - Sinumerik spline blocks, for any of the four methods, of a curve in a
//   plane z = constant: the cut's whole tolerance, which the fit shares
//   with the rounding; a ramp lap stays chords, through the points the
//   blocks are then fitted to (an automatic start continues its last one);
// - Heidenhain SPL spans and G06.2 NURBS blocks (method=nurbs only), level
//   laps only: the tolerance less the rounding of their ends or control
//   points on the printed grid, an error where that leaves nothing.
// A lap whose ranges the program computes (a curve that reads parameters)
// is laid out at the compiled values and what it reads fixed (on a
// controller with a warning; a G06.2 block keeps a weight that is a
// parameter); one that reads the variable of a loop the controller runs
// cannot be blocks. write-curve-blocks fits them. Where the blocks cannot
// follow, the cut stays chords, with a spline-as-chords warning saying why.
#include "cncc/ir/curve_blocks.h"
#include "cncc/ir/curve_lap.h"

#include "lap_cuts.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <string_view>

namespace cncc::ir {

namespace {

// The blocks a cut's method= asks of the blocks its target prints; nullopt
// where they are not the method's (G06.2 prints only method=nurbs).
std::optional<CurveSampling> askedSampling(const CutGeometry& cut) {
  const std::string& method = cut.method;
  if (!splineKindOfMethod(method)) {
    return std::nullopt;
  }
  switch (cut.printedBlocks) {
  case PrintedBlocks::Nurbs:
    return method == "nurbs" ? std::optional(CurveSampling::NurbsBlocks) : std::nullopt;
  case PrintedBlocks::Polynomial:
    return CurveSampling::PolynomialBlocks;
  case PrintedBlocks::Spline:
    return CurveSampling::SplineBlocks;
  case PrintedBlocks::None:
    break;
  }
  return std::nullopt;
}

// What SPL spans and NURBS blocks keep: the tolerance less the rounding of
// the points they are printed through. Throws where nothing is left.
double blocksTolerance(const CutGeometry& cut, const CurveTableEntry& entry,
                       std::string_view roundedPoints) {
  ToleranceBudget budget = cut.budget();
  budget.tolerance = budget.toleranceOrDefault();
  double rounding = budget.pointRounding();
  if (!(budget.tolerance > 2 * rounding)) {
    throw CurveLapError(
        CurveLapError::Kind::InvalidTolerance, entry.cutSpan,
        fmt::format("the tolerance {:g} leaves no room for the controller's rounding of the "
                    "{} ({:.6g})",
                    budget.tolerance, roundedPoints, rounding));
  }
  return budget.forPoints();
}

// The lap's entry as plain chords: no arcs, steps or blocks asked.
CurveTableEntry asChords(const CurveTableEntry& measured) {
  CurveTableEntry entry = measured;
  entry.blocksAsked = false;
  entry.arcsAsked.reset();
  entry.arcRegions.clear();
  entry.regionSteps.clear();
  entry.walkRegions.clear();
  entry.offsetGrowth.reset();
  entry.chosenParameters = nullptr;
  return entry;
}

// The lap's entry as blocks of `sampling` keeping `amount` on the cut's grid.
CurveTableEntry blocksEntry(const CurveTableEntry& measured, CurveSampling sampling, double amount,
                            double grid) {
  CurveTableEntry entry = asChords(measured);
  entry.sampling = sampling;
  entry.amount = amount;
  entry.grid = grid;
  entry.hostPointRegions.clear(); // the regions are the curve, not points to print
  entry.pointsAsNumbers = false;
  return entry;
}

// The lap's entry as the blocks are fitted to its curve: its own, or where
// the program computes its regions' ranges (a controller's steps along a
// curve that reads parameters), laid out at the compiled values; nullopt
// where a range is not known there.
std::optional<CurveTableEntry> measuredEntry(const Function& function, const Instruction& lap,
                                             const CutGeometry& cut, CompiledValues& compiled) {
  const CurveTableEntry& own = function.curves[lap.index];
  if (own.sampling != CurveSampling::Steps) {
    return own;
  }
  return compiledRangesEntry(lap, own, compiled, cut);
}

// How one entry's laps are cut: the entry of its level laps and of its ramp
// laps (the chords', or nullopt where they stay as they are); without a
// level entry, why the cut stays chords.
struct EntryChoice {
  std::optional<CurveTableEntry> level;
  std::optional<CurveTableEntry> ramp;
  std::string chordsBecause;
  bool ownNurbs = false; // a G06.2 block of the curve's own NURBS: its weights its own
};

EntryChoice chords(std::string because) {
  return {std::nullopt, std::nullopt, std::move(because)};
}

EntryChoice chooseEntry(const Function& function, const CutGeometry& cut, const Instruction& lap,
                        bool cutRamps) {
  std::optional<CurveSampling> sampling = askedSampling(cut);
  if (!sampling) {
    return chords("this target has no spline interpolation");
  }
  if (cutRamps && *sampling != CurveSampling::SplineBlocks) {
    return chords(fmt::format("{} blocks cannot descend an entry=ramp",
                              *sampling == CurveSampling::NurbsBlocks ? "G06.2 NURBS" : "SPL"));
  }
  // Each trip its own curve (on a host, unroll-host-control has written
  // the loop out).
  if (!lapInputs(function, lap).loopVariables.empty()) {
    return chords("this curve changes with a loop the program runs");
  }
  CompiledValues compiled(function);
  std::optional<CurveTableEntry> measured = measuredEntry(function, lap, cut, compiled);
  if (!measured) {
    return chords("this curve's pieces are not known when compiling");
  }
  std::shared_ptr<const geom::Curve> curve =
      lapCurve(function, lap, *measured, [&](ValueId value) { return compiled(value); });
  if (*sampling != CurveSampling::SplineBlocks) {
    bool nurbs = *sampling == CurveSampling::NurbsBlocks;
    double amount =
        blocksTolerance(cut, *measured, nurbs ? "NURBS control points" : "spline end points");
    bool own = nurbs && dynamic_cast<const geom::NurbsCurve*>(curve.get()) != nullptr;
    return {blocksEntry(*measured, *sampling, amount, cut.increment), std::nullopt, {}, own};
  }
  if (!liesInPlane(*curve)) {
    return chords("spline blocks move in X and Y, and this curve leaves its plane z = constant");
  }
  double amount = std::isfinite(cut.tolerance) ? cut.tolerance : 0;
  EntryChoice choice{blocksEntry(*measured, *sampling, amount, cut.increment), std::nullopt, {}};
  choice.level->splineFit =
      SplineBlocksFit{*splineKindOfMethod(cut.method), cut.splineEnds, cutRamps};
  if (amount == 0 || cutRamps) {
    // The points the blocks go through (samples=, spacing=), or the ramp's.
    CurveTableEntry points = asChords(*measured);
    auto chosen = std::make_shared<const std::vector<double>>(lapParameters(points, *curve));
    choice.level->chosenParameters = chosen;
    if (cutRamps) {
      points.chosenParameters = chosen;
      choice.ramp = std::move(points);
    }
  }
  return choice;
}

// The cuts with a ramp lap along a curve that asks for blocks.
std::set<std::uint32_t>
rampingCuts(const Function& function,
            const std::map<std::uint32_t, std::vector<LapOfCut>>& lapsOfEntries) {
  std::set<std::uint32_t> cuts;
  for (const auto& [index, laps] : lapsOfEntries) {
    for (const LapOfCut& ofCut : laps) {
      if (function.curves[index].blocksAsked &&
          lapRamps(function, function.instructions[ofCut.lap])) {
        cuts.insert(ofCut.cut);
      }
    }
  }
  return cuts;
}

// Once per cut: its method= is cut as chords, and why.
void warnChords(Function& function, const CutGeometry& cut, const CurveTableEntry& entry,
                const std::string& because, std::vector<frontend::SourceSpan>& warned) {
  frontend::SourceSpan span = cut.methodSpan.valid() ? cut.methodSpan : entry.cutSpan;
  if (std::find(warned.begin(), warned.end(), span) != warned.end()) {
    return;
  }
  warned.push_back(span);
  function.warnings.push_back(
      {LegalisationWarning::Kind::SplineAsChords, span,
       fmt::format("{}: method={} is cut as straight feed moves within the cut's tolerance",
                   because, cut.method)});
}

// The entry's laps cut as chosen: the entry itself becomes its level laps'
// blocks (or, where it has none, its ramp laps' chords: a ramp lap with
// arcs asked has an entry of its own); a ramp lap beside level laps gets an
// entry of its own.
void applyChoice(Function& function, std::uint32_t index, const std::vector<LapOfCut>& laps,
                 EntryChoice& choice) {
  const CurveTableEntry own = function.curves[index]; // the layout the laps' operands follow
  bool levelLaps = false;
  bool rampLaps = false;
  for (const LapOfCut& ofCut : laps) {
    (lapRamps(function, function.instructions[ofCut.lap]) ? rampLaps : levelLaps) = true;
  }
  if (!choice.ramp) { // not reached: a cut that ramps has its ramp's chords
    choice.ramp = asChords(own);
  }
  std::uint32_t level = index;
  std::uint32_t ramp = index;
  function.curves[index] = std::move(levelLaps ? *choice.level : *choice.ramp);
  if (levelLaps && rampLaps) {
    function.curves.push_back(std::move(*choice.ramp));
    ramp = static_cast<std::uint32_t>(function.curves.size() - 1);
  }
  for (const LapOfCut& ofCut : laps) {
    Instruction& lap = function.instructions[ofCut.lap];
    std::uint32_t entry = lapRamps(function, lap) ? ramp : level;
    if (own.sampling == CurveSampling::Steps) {
      readChordEntry(function, lap, entry, own); // no computed ranges now
    } else {
      lap.index = entry;
    }
  }
}

std::string_view blocksName(CurveSampling sampling) {
  return sampling == CurveSampling::NurbsBlocks    ? "G06.2 NURBS blocks"
         : sampling == CurveSampling::SplineBlocks ? "spline blocks"
                                                   : "SPL blocks";
}

// What the laps read is fixed (a controller's program checks it: a warning
// there), but the parameters a NURBS block keeps as its weights.
void fixWhatTheLapsRead(Function& function, const std::vector<LapOfCut>& laps,
                        const CurveTableEntry& entry, const EntryChoice& choice) {
  CurveSampling sampling = choice.level->sampling;
  std::set<std::uint32_t> kept;
  if (choice.ownNurbs) {
    for (const CurveTableEntry::ParameterWeight& weight : entry.parameterWeights) {
      kept.insert(weight.parameter);
    }
  }
  std::string because =
      fmt::format("this curve's {} are computed when compiling", blocksName(sampling));
  for (const LapOfCut& ofCut : laps) {
    fixParametersRead(function, function.instructions[ofCut.lap], entry,
                      hostComputedCut(function, ofCut.cut), because, kept);
  }
}

} // namespace

bool chooseCurveBlocks(Function& function) {
  std::map<std::uint32_t, std::vector<LapOfCut>> lapsOfEntries = lapsByEntry(function);
  std::set<std::uint32_t> ramping = rampingCuts(function, lapsOfEntries);
  std::vector<frontend::SourceSpan> warned; // where the method= is written
  bool changed = false;
  for (const auto& [index, laps] : lapsOfEntries) {
    if (!function.curves[index].blocksAsked || laps.empty() || laps.front().cut == noCut) {
      continue;
    }
    // Every lap of an entry is one cut's, or a copy's of a trip written out.
    const CutGeometry& cut = function.cuts[laps.front().cut];
    const Instruction& first = function.instructions[laps.front().lap];
    EntryChoice choice = chooseEntry(function, cut, first, ramping.contains(laps.front().cut));
    if (!choice.level) {
      warnChords(function, cut, function.curves[index], choice.chordsBecause, warned);
      function.curves[index].blocksAsked = false; // answered: chords
      changed = true;
      continue;
    }
    fixWhatTheLapsRead(function, laps, function.curves[index], choice);
    applyChoice(function, index, laps, choice);
    changed = true;
  }
  return changed;
}

} // namespace cncc::ir
