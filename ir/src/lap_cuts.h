// The cut each curve.lap belongs to (the cut.begin before it in the
// program's order), for the legalisations that decide by the cut's target:
// whether its controller computes the program's numbers or the host does.
#pragma once

#include "cncc/ir/curve_lap.h"
#include "cncc/ir/ir.h"

#include "compiled_values.h"

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string_view>
#include <utility>
#include <vector>

namespace cncc::ir {

struct LapOfCut {
  InstructionId lap = 0;
  std::uint32_t cut = 0; // or noCut
};

// Every curve.lap, by the index of its entry in the curve table.
std::map<std::uint32_t, std::vector<LapOfCut>> lapsByEntry(const Function& function);

// Whether the lap climbs or descends: its two heights not one value.
bool lapRamps(const Function& function, const Instruction& lap);

// The function's cut `cut` where the host computes its numbers (no
// controller digits, CutGeometry::controllerDigits); null where a
// controller does, or for noCut.
const CutGeometry* hostComputedCut(const Function& function, std::uint32_t cut);

// What bound-controller-steps and split-arc-laps share (curve_lap_step_bounds.cpp).

// A region of a lap in steps at the compiled values: its range and count.
struct RegionAtCompiled {
  double from = 0;
  double to = 0;
  double count = 0;
};
// Each region's range and count at the compiled values: the entry's, or the
// lap's operands; nullopt where one is not known there.
std::optional<std::vector<RegionAtCompiled>>
regionsAtCompiled(const Instruction& lap, const CurveTableEntry& stepped, CompiledValues& compiled);
// The lap's entry (`stepped`, in steps; or a piece of it split from its
// arcs, whose computed regions' ranges and counts are `lap`'s operands
// after its three) laid out as chords over each region's range at the
// compiled values, as bound-controller-steps gives it (within the cut's
// tolerance less the rounding). nullopt where a range is not known there,
// and without `withinTheLimit` where no region's count there is past the
// limit (the lap keeps its counts).
std::optional<CurveTableEntry> compiledRangesEntry(const Instruction& lap,
                                                   const CurveTableEntry& stepped,
                                                   CompiledValues& compiled, const CutGeometry& cut,
                                                   bool withinTheLimit = true);
// The lap reads the function's entry `chords` laid out from its entry
// `stepped`: its three operands (no computed ranges), each walk's end a
// point.
void readChordEntry(Function& function, Instruction& lap, std::uint32_t chords,
                    const CurveTableEntry& stepped);
// Fixes each parameter the lap reads but `kept`; on a controller (no
// `hostCut`), with a parameter-fixed warning at the entry's curve: "'p' is
// fixed at its value v in this program: `because`; the program raises an
// alarm if it is changed".
void fixParametersRead(Function& function, const Instruction& lap, const CurveTableEntry& entry,
                       const CutGeometry* hostCut, std::string_view because,
                       const std::set<std::uint32_t>& kept = {});
// `drawn` from `whole.first` to `whole.second` in the parameter `range`,
// mapped linearly onto it.
std::shared_ptr<const geom::Curve> linearlyMappedCurve(std::shared_ptr<const geom::Curve> drawn,
                                                       std::pair<double, double> range,
                                                       std::pair<double, double> whole);
// The part of `stepped`'s curve (its geometry, not null) that the region at
// `place` cuts, over the parameter `range` mapped linearly onto it.
std::shared_ptr<const geom::Curve> regionCurveOver(const CurveTableEntry& stepped,
                                                   const CurveTableEntry::RegionPlace& place,
                                                   std::pair<double, double> range);
// What the lap's regions and its computed ranges read from before the lap:
// the parameters (by index) and the variables of the loops around it (by
// value index).
struct LapInputs {
  std::set<std::uint32_t> parameters;
  std::set<std::uint32_t> loopVariables;
};
LapInputs lapInputs(const Function& function, const Instruction& lap);
// What the values read, through pure arithmetic, from before them.
LapInputs valueInputs(const Function& function, std::vector<ValueId> values);
// The values of the variables of the loops around a lap in the trip being
// run (by the variable's value index): what the interpreter knows of a lap
// before unroll-host-control writes its loop out.
using LoopTrip = std::map<std::uint32_t, double>;
// The lap's entry as a legalisation measures it at the compiled values
// (`compiled`): its own; where its curve reads the variable of a loop
// around it, the variable has no one value there, so nullopt (a
// legalisation leaves the lap) unless `trip` gives it, and then `compiled`
// is told it and the entry is without the lowering's geometry (the curve
// at the loop's first trip: the regions at the trip's value are the curve).
std::optional<CurveTableEntry> entryToMeasure(const Function& function, const Instruction& lap,
                                              CompiledValues& compiled,
                                              const LoopTrip* trip = nullptr);

// A piece of a lap split at its arcs (split-arc-laps): the lap's regions
// [firstRegion, firstRegion + regionCount), cut as `entry` says.
struct LapPart {
  std::size_t firstRegion = 0;
  std::size_t regionCount = 0;
  CurveTableEntry entry;
};

// The pieces of a lap in steps with arc regions of the function's cut `cut`
// where the host computes it (curve_lap_arc_split.cpp); nullopt for any other
// lap, or where its ranges are not known at the compiled values. Throws
// CurveLapError (an arc of more turns than maximumArcBlocks).
std::optional<std::vector<LapPart>> hostArcLapParts(const Function& function,
                                                    const Instruction& lap, std::uint32_t cut,
                                                    const LoopTrip* trip = nullptr);
// A part's lap: the lap's regions of the part and its three operands (the
// heights and the feed; a part's entry computes no range), its result and
// span the lap's.
Instruction partLap(const Instruction& lap, const LapPart& part);

} // namespace cncc::ir
