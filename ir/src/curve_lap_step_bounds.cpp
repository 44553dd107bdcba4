// `bound-controller-steps`: a curve.lap cut in steps whose counts the
// program computes (a piece whose shape depends on part parameters) is cut
// at points the host chooses within its tolerance instead where the host
// computes the cut's numbers (gcode, sinumerik, jit: the lowering gives
// every target the same steps, and the host's chords are fewer), or where
// the counts come, at the values the part is compiled with, past the limit
// of one region (maximumStepsPerRegion: a weight of 1e9 typed for 1 asks
// the controller for a loop of a hundred million steps). Its regions stay
// what they are, each over the range it had at those values (a walked
// span's end a curve.point), laid out one piece per region in a
// chord-tolerance entry; the parameters its regions read are fixed at
// their values, which a controller's program checks (a warning there; the
// host's program has no parameters to edit). A controller's chords are
// printed as numbers, which its digits hold.
#include "cncc/ir/curve_lap.h"

#include "compiled_values.h"
#include "lap_cuts.h"

#include "cncc/geom/composite_curve.h"
#include "cncc/geom/function_curve.h"
#include "cncc/geom/geometry_error.h"

#include <fmt/format.h>

#include <cmath>
#include <map>
#include <set>

namespace cncc::ir {

std::optional<std::vector<RegionAtCompiled>> regionsAtCompiled(const Instruction& lap,
                                                               const CurveTableEntry& stepped,
                                                               CompiledValues& compiled) {
  std::vector<RegionAtCompiled> regions;
  std::vector<CurveTableEntry::RegionPlace> places = stepped.regionPlaces();
  std::size_t computed = 0;
  for (std::size_t region = 0; region < places.size(); ++region) {
    int count = region < stepped.regionSteps.size() ? stepped.regionSteps[region] : 0;
    if (count != 0) {
      auto [from, to] = stepped.regionRange(places[region]);
      regions.push_back({from, to, static_cast<double>(count)});
      continue;
    }
    std::size_t first = 3 + 3 * computed++;
    if (first + 2 >= lap.operands.size()) {
      return std::nullopt; // the verifier's problem
    }
    std::optional<double> from = compiled(lap.operands[first]);
    std::optional<double> to = compiled(lap.operands[first + 1]);
    std::optional<double> steps = compiled(lap.operands[first + 2]);
    if (!from || !to || !steps) {
      return std::nullopt;
    }
    regions.push_back({*from, *to, *steps});
  }
  return regions;
}

namespace {

// Each region's parameter range at the compiled values when the host
// chooses the points, or some computed count there is past the limit;
// nullopt otherwise (or when a range is not known there, which leaves the
// lap to the program's own counts).
std::optional<std::vector<std::pair<double, double>>> chordRanges(const Instruction& lap,
                                                                  const CurveTableEntry& entry,
                                                                  CompiledValues& compiled,
                                                                  bool hostChooses) {
  std::optional<std::vector<RegionAtCompiled>> regions = regionsAtCompiled(lap, entry, compiled);
  if (!regions) {
    return std::nullopt;
  }
  std::vector<std::pair<double, double>> ranges;
  bool pastTheLimit = false;
  for (const RegionAtCompiled& region : *regions) {
    if (!(region.to > region.from)) {
      return std::nullopt; // no piece of its own to lay out
    }
    pastTheLimit = pastTheLimit || !(region.count <= maximumStepsPerRegion);
    ranges.emplace_back(region.from, region.to);
  }
  return hostChooses || pastTheLimit ? std::optional(std::move(ranges)) : std::nullopt;
}

} // namespace

std::shared_ptr<const geom::Curve> linearlyMappedCurve(std::shared_ptr<const geom::Curve> drawn,
                                                       std::pair<double, double> range,
                                                       std::pair<double, double> whole) {
  double from = range.first; // a lambda captures no structured binding (clang 14)
  double wholeFrom = whole.first;
  double scale = (whole.second - whole.first) / (range.second - range.first);
  auto wholeAt = [=](double local) { return wholeFrom + (local - from) * scale; };
  return std::make_shared<geom::FunctionCurve>(
      geom::ParameterRange{range.first, range.second},
      [drawn, wholeAt](double local) { return drawn->point(wholeAt(local)); },
      [drawn, wholeAt, scale](double local) {
        return Eigen::Vector3d(drawn->derivative(wholeAt(local)) * scale);
      },
      [drawn, wholeAt, scale](double local) {
        return Eigen::Vector3d(drawn->secondDerivative(wholeAt(local)) * scale * scale);
      });
}

std::shared_ptr<const geom::Curve> regionCurveOver(const CurveTableEntry& stepped,
                                                   const CurveTableEntry::RegionPlace& place,
                                                   std::pair<double, double> range) {
  auto [ownFrom, ownTo] = stepped.regionRange(place);
  return linearlyMappedCurve(
      stepped.geometry, range,
      {stepped.wholeParameter(place, ownFrom), stepped.wholeParameter(place, ownTo)});
}

namespace {

// The stepped entry's curve in the chord entry's parameter: each region's
// range at the compiled values mapped linearly onto the part of the curve
// the region cut (a walked span's u, a counted span's 0 .. N, a piece's own
// range); null without the curve (a function read from text: its regions
// are interpreted).
std::shared_ptr<const geom::Curve>
curveOverRanges(const CurveTableEntry& stepped,
                const std::vector<std::pair<double, double>>& ranges) {
  if (!stepped.geometry) {
    return nullptr;
  }
  std::vector<CurveTableEntry::RegionPlace> places = stepped.regionPlaces();
  std::vector<std::shared_ptr<const geom::Curve>> pieces;
  for (std::size_t region = 0; region < ranges.size(); ++region) {
    pieces.push_back(regionCurveOver(stepped, places[region], ranges[region]));
  }
  if (pieces.size() == 1) {
    return pieces.front();
  }
  try {
    return std::make_shared<geom::CompositeCurve>(std::move(pieces), pathJoinTolerance);
  } catch (const geom::GeometryError&) {
    return nullptr; // the regions interpreted, which report where they part
  }
}

// Whether each region's range is its own in the entry's layout (a knot
// span's u from 0 to 1, a piece's own range at the compiled values).
bool rangesAsLaidOut(const CurveTableEntry& stepped,
                     const std::vector<std::pair<double, double>>& ranges) {
  std::vector<CurveTableEntry::RegionPlace> places = stepped.regionPlaces();
  for (std::size_t region = 0; region < ranges.size(); ++region) {
    if (stepped.regionRange(places[region]) != ranges[region]) {
      return false;
    }
  }
  return true;
}

// The entry of the lap's points chosen on the host: one piece per region,
// over the range the region had; for a cut the host computes (`hostCut`),
// within its tolerance less the rounding of three axes, as the lowering
// chooses chords, and over the whole curve where the ranges are as laid
// out (no point at each region's end).
CurveTableEntry chordEntry(const CurveTableEntry& stepped,
                           const std::vector<std::pair<double, double>>& ranges,
                           const CutGeometry* hostCut) {
  CurveTableEntry entry = stepped;
  entry.sampling = CurveSampling::ChordTolerance;
  entry.regionSteps.clear();
  entry.walkRegions.clear();
  entry.chosenParameters = nullptr;
  entry.offsetGrowth.reset(); // the chords of the offset at the compiled radius
  if (hostCut != nullptr) {
    double points = hostCut->budget().forPoints();
    entry.amount = points > 0 ? points : entry.amount; // else the lowering's error
    if (rangesAsLaidOut(stepped, ranges)) {
      return entry;
    }
  }
  entry.geometry = curveOverRanges(stepped, ranges);
  // A controller's as numbers: regions whose counts run that far compute
  // with numbers its digits may not hold (a weight of 1e9).
  entry.pointsAsNumbers = hostCut == nullptr;
  entry.pieces.clear();
  double start = 0;
  for (auto [from, to] : ranges) {
    entry.pieces.push_back({ranges.size() == 1 ? from : start, from, to, {}});
    start += to - from;
  }
  entry.from = entry.pieces.front().start;
  entry.to = ranges.size() == 1 ? ranges.front().second : start;
  return entry;
}

} // namespace

void fixParametersRead(Function& function, const Instruction& lap, const CurveTableEntry& entry,
                       const CutGeometry* hostCut, std::string_view because,
                       const std::set<std::uint32_t>& kept) {
  for (std::uint32_t index : lapInputs(function, lap).parameters) {
    Parameter& parameter = function.parameters[index];
    if (parameter.fixed || kept.contains(index)) {
      continue;
    }
    parameter.fixed = true;
    if (hostCut != nullptr) {
      continue; // the host's program has no parameters to edit
    }
    function.warnings.push_back({LegalisationWarning::Kind::ParameterFixed, entry.curveSpan,
                                 fmt::format("'{}' is fixed at its value {:g} in this program: "
                                             "{}; the program raises an alarm if it is changed",
                                             parameter.name, parameter.defaultValue, because)});
  }
}

void readChordEntry(Function& function, Instruction& lap, std::uint32_t chords,
                    const CurveTableEntry& stepped) {
  lap.index = chords;
  lap.operands.resize(3);
  for (std::size_t region : stepped.walkRegions) {
    if (region < lap.regions.size() && !lap.regions[region].instructions.empty()) {
      Instruction& end = function.instructions[lap.regions[region].instructions.back()];
      if (end.opcode == Opcode::CurveWalk) {
        end.opcode = Opcode::CurvePoint;
        end.operands.resize(3);
      }
    }
  }
}

std::optional<CurveTableEntry> compiledRangesEntry(const Instruction& lap,
                                                   const CurveTableEntry& stepped,
                                                   CompiledValues& compiled, const CutGeometry& cut,
                                                   bool withinTheLimit) {
  std::optional<std::vector<std::pair<double, double>>> ranges =
      chordRanges(lap, stepped, compiled, withinTheLimit);
  if (!ranges) {
    return std::nullopt;
  }
  return chordEntry(stepped, *ranges, &cut);
}

namespace {

// The ranges of a lap cut in steps within a tolerance whose points the
// host chooses (an offset's whose counts grow with the radius too: chords at
// the compiled radius), or whose computed counts are past the limit at the
// compiled values; nullopt for any other lap (samples=, arcs, a
// controller's offset growth).
std::optional<std::vector<std::pair<double, double>>>
boundedLapRanges(const Instruction& lap, const CurveTableEntry& stepped, CompiledValues& compiled,
                 const CutGeometry* hostCut) {
  if (stepped.sampling != CurveSampling::Steps || (stepped.offsetGrowth && hostCut == nullptr) ||
      !stepped.arcRegions.empty()) {
    return std::nullopt;
  }
  return chordRanges(lap, stepped, compiled, hostCut != nullptr && stepped.amount > 0);
}

} // namespace

std::optional<CurveTableEntry> boundedStepsEntry(const Function& function, const Instruction& lap,
                                                 std::uint32_t cut, const LoopTrip* trip) {
  CompiledValues compiled(function);
  std::optional<CurveTableEntry> stepped = entryToMeasure(function, lap, compiled, trip);
  if (!stepped) {
    return std::nullopt;
  }
  const CutGeometry* hostCut = hostComputedCut(function, cut);
  std::optional<std::vector<std::pair<double, double>>> ranges =
      boundedLapRanges(lap, *stepped, compiled, hostCut);
  if (!ranges) {
    return std::nullopt;
  }
  return chordEntry(*stepped, *ranges, hostCut);
}

bool boundControllerSteps(Function& function) {
  CompiledValues compiled(function);
  // By the stepped entry: its chord entry, made once for all its laps (a
  // ramp lap and the level laps share one).
  std::map<std::uint32_t, std::uint32_t> chordEntries;
  bool changed = false;
  for (const auto& [index, laps] : lapsByEntry(function)) {
    for (const LapOfCut& ofCut : laps) {
      Instruction& lap = function.instructions[ofCut.lap];
      const CutGeometry* hostCut = hostComputedCut(function, ofCut.cut);
      if (!lapInputs(function, lap).loopVariables.empty()) {
        continue; // no one value at the compiled values: entryToMeasure
      }
      std::optional<std::vector<std::pair<double, double>>> ranges =
          boundedLapRanges(lap, function.curves[index], compiled, hostCut);
      if (!ranges) {
        continue;
      }
      auto known = chordEntries.find(index);
      if (known == chordEntries.end()) {
        function.curves.push_back(chordEntry(function.curves[index], *ranges, hostCut));
        auto added = static_cast<std::uint32_t>(function.curves.size() - 1);
        known = chordEntries.emplace(index, added).first;
      }
      const CurveTableEntry& stepped = function.curves[index]; // no entry is added below
      fixParametersRead(function, lap, stepped, hostCut,
                        fmt::format("at that value the controller would cut this curve in more "
                                    "than {} steps of one piece, so its points are chosen when "
                                    "compiling",
                                    maximumStepsPerRegion));
      readChordEntry(function, lap, known->second, stepped);
      changed = true;
    }
  }
  return changed;
}

} // namespace cncc::ir
