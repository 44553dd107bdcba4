// `choose-controller-steps`: on a target whose controller computes the
// program's numbers (its cuts' controllerDigits), a lap cut within a chord
// tolerance along a curve that reads nothing but constants is cut in
// uniform steps the controller counts instead: the same regions, its
// points the loop's (expand-controller-loops measures each region's count
// on the curve), not a table of parameters chosen on the host; a lap of
// samples= over one region, in its samples' steps; a lap over a share of a
// longer descent (a piece between arcs, which are move.arc blocks) keeps
// its share (descentShares). What the lowering emits for such a curve is
// the same on every target; this is where a controller target's program
// takes its loops.
//
// A knot span's region is its polynomial in u either way (the lowering's
// spanPointAt of the cleaned span). Left as they are: laps whose points the
// host computes (pointsAsNumbers, host regions: a span whose literals the
// controller's digits cannot hold, chosen parameters), and laps whose
// regions read a parameter or a loop's variable (the lowering cuts those in
// steps it plans itself, or fixes what they read).
#include "cncc/ir/curve_lap.h"

#include "lap_cuts.h"

#include <map>
#include <set>

namespace cncc::ir {

namespace {

// Whether the entry is chords the controller could step: its points the
// regions' (no knot span whose literals the controller's digits cannot
// hold, host regions) and nothing chosen for it. A lap over a share of a
// longer descent (a piece between arcs) keeps its share in steps.
bool steppableEntry(const CurveTableEntry& entry) {
  bool stepped = entry.sampling == CurveSampling::ChordTolerance ||
                 (entry.sampling == CurveSampling::Samples && entry.regionCount() == 1);
  return stepped && !entry.pointsAsNumbers && entry.hostPointRegions.empty() &&
         !entry.chosenParameters && !entry.offsetGrowth;
}

// Whether everything the lap's regions read from outside them is a constant.
bool regionsReadOnlyConstants(const Function& function, InstructionId lapId) {
  const Instruction& lap = function.instructions[lapId];
  std::set<InstructionId> inside = {lapId};
  for (const Region& region : lap.regions) {
    inside.insert(region.instructions.begin(), region.instructions.end());
  }
  for (const Region& region : lap.regions) {
    for (InstructionId id : region.instructions) {
      for (ValueId operand : function.instructions[id].operands) {
        InstructionId definition = function.definitions[operand.index];
        if (!inside.contains(definition) &&
            function.instructions[definition].opcode != Opcode::Const) {
          return false;
        }
      }
    }
  }
  return true;
}

// The cut every one of the entry's laps belongs to, where each can be cut
// in steps; nullopt otherwise.
std::optional<std::uint32_t> steppingCut(const Function& function,
                                         const std::vector<LapOfCut>& laps) {
  std::uint32_t cut = laps.front().cut;
  if (cut >= function.cuts.size() || !function.cuts[cut].controllerDigits) {
    return std::nullopt;
  }
  for (const LapOfCut& lap : laps) {
    if (lap.cut != cut || !regionsReadOnlyConstants(function, lap.lap)) {
      return std::nullopt;
    }
  }
  return cut;
}

// The amount of the chords entry's steps: the cut's tolerance less the
// rounding of two axes (a curve in the plane z = 0) or three, and less the
// literals' share.
double stepsAmount(const CutGeometry& cut, const geom::Curve& curve) {
  return cut.budget().forControllerSteps(liesInThePlaneZero(curve) ? 2 : 3);
}

// The entry as steps: a chords entry's within `amount`, each region's count
// left to expand-controller-loops; a samples entry's one region in as many
// steps as it has chords (the controller of the cut reads them:
// expand-controller-loops checks their drift).
CurveTableEntry cutInSteps(CurveTableEntry entry, double amount) {
  if (entry.sampling == CurveSampling::Samples) {
    entry.regionSteps.assign(1, static_cast<int>(entry.amount) - 1);
    entry.amount = 0;
  } else {
    entry.regionSteps.assign(entry.regionCount(), stepsChosenByLegalisation);
    entry.amount = amount;
  }
  entry.sampling = CurveSampling::Steps;
  return entry;
}

} // namespace

bool liesInThePlaneZero(const geom::Curve& curve) {
  geom::ParameterRange domain = curve.domain();
  for (double t : {0.0, 0.25, 0.5, 0.75, 1.0}) {
    if (curve.point(domain.t0 + t * domain.length()).z() != 0) {
      return false;
    }
  }
  return true;
}

std::map<std::uint32_t, CurveTableEntry> controllerStepsEntries(const Function& function) {
  std::map<std::uint32_t, std::vector<LapOfCut>> laps = lapsByEntry(function);
  std::map<std::uint32_t, CurveTableEntry> stepped;
  for (const auto& [index, ofEntry] : laps) {
    if (index >= function.curves.size() || !steppableEntry(function.curves[index])) {
      continue;
    }
    std::optional<std::uint32_t> stepping = steppingCut(function, ofEntry);
    if (!stepping) {
      continue;
    }
    const CutGeometry& cutOfLaps = function.cuts[*stepping];
    const CurveTableEntry& entry = function.curves[index];
    if (entry.sampling == CurveSampling::Samples) {
      stepped.emplace(index, cutInSteps(entry, 0.0));
      continue;
    }
    auto constantsOnly = [](ValueId) { return std::optional<double>(); };
    std::shared_ptr<const geom::Curve> curve =
        lapCurve(function, function.instructions[ofEntry.front().lap], constantsOnly);
    double amount = stepsAmount(cutOfLaps, *curve);
    if (amount > 0) { // else nothing is left of the tolerance: the lowering's error, or chords
      stepped.emplace(index, cutInSteps(entry, amount));
    }
  }
  return stepped;
}

bool chooseControllerSteps(Function& function) {
  std::map<std::uint32_t, CurveTableEntry> stepped = controllerStepsEntries(function);
  for (auto& [index, entry] : stepped) {
    function.curves[index] = std::move(entry);
  }
  return !stepped.empty();
}

} // namespace cncc::ir
