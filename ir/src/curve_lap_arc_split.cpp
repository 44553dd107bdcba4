// `split-arc-laps`: on a cut the host computes (gcode, sinumerik, jit), a
// curve.lap in steps with arc regions (a curve with an arc piece that reads
// part parameters: the lowering gives every target the controller's lap) is
// written as a lap per piece, as the host prints such a curve: each arc
// piece in its move.arc blocks at the compiled values, in whole turns where
// it turns whole turns (a controller's arcs are half turns its program
// counts), each other piece in chords within the cut's tolerance, as
// bound-controller-steps chooses them. A ramp lap's pieces descend by their
// shares of its descent. What the lap reads is fixed at its value (the
// host's program has no parameters to edit). The interpreter runs such a
// lap as these parts before the pass too (LegalisedEntries).
#include "cncc/ir/arc_blocks.h"
#include "cncc/ir/curve_lap.h"
#include "cncc/ir/passes.h"

#include "curve_lap_rewriter.h"
#include "lap_cuts.h"

#include <cmath>

namespace cncc::ir {

namespace {

// The lap of regions [first, first + count): their regions, the lap's three
// operands and the ranges and counts of the computed ones among them.
Instruction regionsLap(const Instruction& lap, const CurveTableEntry& stepped, std::size_t first,
                       std::size_t count) {
  Instruction part = lap;
  part.regions.assign(lap.regions.begin() + static_cast<std::ptrdiff_t>(first),
                      lap.regions.begin() + static_cast<std::ptrdiff_t>(first + count));
  part.operands.resize(3);
  std::size_t computed = 0;
  for (std::size_t region = 0; region < first + count; ++region) {
    if (region < stepped.regionSteps.size() && stepped.regionSteps[region] != 0) {
      continue;
    }
    std::size_t operand = 3 + 3 * computed++;
    if (region >= first) {
      part.operands.insert(part.operands.end(), lap.operands.begin() + operand,
                           lap.operands.begin() + operand + 3);
    }
  }
  return part;
}

// The lap's entry over one piece alone, in the piece's own parameter.
CurveTableEntry pieceEntry(const CurveTableEntry& stepped, std::size_t piece, std::size_t first,
                           std::size_t count) {
  CurveTableEntry entry = stepped;
  CurvePieceLayout layout = stepped.pieces[piece];
  entry.geometry = nullptr;
  if (stepped.geometry) {
    // The whole curve's parameter is a single piece's own, else from its start.
    double wholeFrom = stepped.pieces.size() == 1 ? layout.from : layout.start;
    entry.geometry = linearlyMappedCurve(stepped.geometry, {layout.from, layout.to},
                                         {wholeFrom, wholeFrom + (layout.to - layout.from)});
  }
  layout.start = layout.from;
  entry.pieces = {layout};
  entry.from = layout.from;
  entry.to = layout.to;
  entry.regionSteps.assign(stepped.regionSteps.begin() + static_cast<std::ptrdiff_t>(first),
                           stepped.regionSteps.begin() +
                               static_cast<std::ptrdiff_t>(first + count));
  entry.arcRegions.clear();
  entry.walkRegions.clear();
  entry.hostPointRegions.clear();
  for (std::size_t region : stepped.hostPointRegions) {
    if (region >= first && region < first + count) {
      entry.hostPointRegions.push_back(region - first);
    }
  }
  entry.chosenParameters = nullptr;
  entry.arcsAsked.reset();
  entry.offsetGrowth.reset(); // cut at the compiled radius: no distance read
  return entry;
}

// The turn of an arc region over its range at the compiled values: the
// angles between the radii at 2 (n + 1) equal steps of its parameter (n its
// half turns, so a step turns less than a quarter).
double compiledSweep(const Function& function, const Instruction& lap, std::size_t region,
                     const RegionAtCompiled& at, CompiledValues& compiled) {
  LapRegionEvaluator evaluator(function, lap, region,
                               [&](ValueId value) { return compiled(value); });
  double steps = 2 * (std::max(at.count, 0.0) + 1);
  double sweep = 0;
  Eigen::Vector2d radius = -evaluator.toCentre(at.from);
  for (double k = 1; k <= steps; ++k) {
    Eigen::Vector2d next = -evaluator.toCentre(at.from + (at.to - at.from) * k / steps);
    double cross = radius.x() * next.y() - radius.y() * next.x();
    sweep += std::atan2(cross, radius.dot(next));
    radius = next;
  }
  return sweep;
}

// An arc piece alone, in the blocks its turn at the compiled values takes;
// nullopt for an arc that does not turn there (left to the lap's loop).
std::optional<CurveTableEntry> arcPartEntry(const Function& function, const Instruction& lap,
                                            const CurveTableEntry& stepped, std::size_t region,
                                            const RegionAtCompiled& at, CompiledValues& compiled) {
  const ArcRegion& arc = *stepped.arcRegion(region);
  std::vector<CurveTableEntry::RegionPlace> places = stepped.regionPlaces();
  CurveTableEntry entry = pieceEntry(stepped, places[region].piece, region, 1);
  ArcRegion own{0, arc.counterClockwise, arc.wholeTurns};
  double blocks = at.count;
  if (stepped.regionSteps[region] == 0) { // half turns the program counts
    if (std::isnan(at.count)) {
      return std::nullopt; // the program's alarm (a radius of none)
    }
    if (!(at.count <= 2 * maximumArcBlocks + 2)) {
      throw CurveLapError(CurveLapError::Kind::ProgramTooLarge, stepped.curveSpan,
                          arcTurnsPastTheLimit({at.count, false, at.count / 2}));
    }
    double sweep = compiledSweep(function, lap, region, at, compiled);
    ArcBlockCount count = arcBlockCount(sweep);
    if (!(count.blocks <= maximumArcBlocks)) {
      throw CurveLapError(CurveLapError::Kind::ProgramTooLarge, stepped.curveSpan,
                          arcTurnsPastTheLimit(count));
    }
    blocks = count.blocks;
    own.counterClockwise = sweep > 0;
    own.wholeTurns = count.wholeTurns;
  }
  if (!(blocks >= 1 && at.to > at.from)) {
    return std::nullopt;
  }
  if (stepped.geometry) {
    entry.geometry = regionCurveOver(stepped, places[region], {at.from, at.to});
  }
  entry.pieces = {{at.from, at.from, at.to, {}}};
  entry.from = at.from;
  entry.to = at.to;
  entry.regionSteps = {static_cast<int>(blocks)};
  entry.arcRegions = {own};
  return entry;
}

// Each region's share of a ramp lap's descent (none for a level lap).
std::vector<LapRegionShare> rampShares(const Function& function, const Instruction& lap,
                                       const CurveTableEntry& stepped, CompiledValues& compiled) {
  if (!lapRamps(function, lap)) {
    return {};
  }
  std::shared_ptr<const geom::Curve> curve =
      lapCurve(function, lap, stepped, [&](ValueId value) { return compiled(value); });
  return descentShares(stepped, *curve);
}

} // namespace

std::optional<std::vector<LapPart>> hostArcLapParts(const Function& function,
                                                    const Instruction& lap, std::uint32_t cut,
                                                    const LoopTrip* trip) {
  const CutGeometry* hostCut = hostComputedCut(function, cut);
  if (hostCut == nullptr) {
    return std::nullopt;
  }
  CompiledValues compiled(function);
  std::optional<CurveTableEntry> measured = entryToMeasure(function, lap, compiled, trip);
  if (!measured) {
    return std::nullopt;
  }
  const CurveTableEntry& stepped = *measured;
  if (stepped.sampling != CurveSampling::Steps || stepped.arcRegions.empty() ||
      !stepped.walkRegions.empty() || lap.regions.size() != stepped.regionCount()) {
    return std::nullopt;
  }
  std::optional<std::vector<RegionAtCompiled>> regions = regionsAtCompiled(lap, stepped, compiled);
  if (!regions) {
    return std::nullopt;
  }
  std::vector<LapRegionShare> shares = rampShares(function, lap, stepped, compiled);
  std::vector<LapPart> parts;
  std::size_t first = 0;
  for (std::size_t piece = 0; piece < stepped.pieces.size(); ++piece) {
    std::size_t count = stepped.pieces[piece].regionCount();
    std::optional<CurveTableEntry> entry;
    if (stepped.arcRegion(first) != nullptr) {
      entry = arcPartEntry(function, lap, stepped, first, (*regions)[first], compiled);
    } else {
      CurveTableEntry part = pieceEntry(stepped, piece, first, count);
      bool chords = part.amount > 0; // samples=: its counts unless past the limit
      entry = compiledRangesEntry(regionsLap(lap, stepped, first, count), part, compiled, *hostCut,
                                  chords);
    }
    if (!entry) {
      return std::nullopt;
    }
    if (!shares.empty()) {
      entry->progressFrom = shares[first].before;
      entry->progressShare = 0;
      for (std::size_t region = first; region < first + count; ++region) {
        entry->progressShare += shares[region].share;
      }
    }
    parts.push_back({first, count, std::move(*entry)});
    first += count;
  }
  return parts;
}

Instruction partLap(const Instruction& lap, const LapPart& part) {
  Instruction written = lap;
  written.regions.assign(lap.regions.begin() + static_cast<std::ptrdiff_t>(part.firstRegion),
                         lap.regions.begin() +
                             static_cast<std::ptrdiff_t>(part.firstRegion + part.regionCount));
  written.operands.resize(3);
  return written;
}

namespace {

class ArcLapSplitter : public LapRewriter {
public:
  using LapRewriter::LapRewriter;

private:
  bool writes(std::uint32_t curve) const override {
    const CurveTableEntry& entry = source_.curves[curve];
    return entry.sampling == CurveSampling::Steps && !entry.arcRegions.empty();
  }

  void writeLap(const Instruction& lap) override {
    std::optional<std::vector<LapPart>> parts =
        hostArcLapParts(source_, lap, currentCut().value_or(noCut));
    if (!parts) {
      copy(lap);
      return;
    }
    for (std::uint32_t parameter : lapInputs(source_, lap).parameters) {
      output_.parameters[parameter].fixed = true;
    }
    for (LapPart& part : *parts) {
      Instruction written = partLap(lap, part);
      written.index = static_cast<std::uint32_t>(output_.curves.size());
      output_.curves.push_back(std::move(part.entry));
      ValueId parameter = beginRegions(
          written, {mapped(lap.operands[0]), mapped(lap.operands[1]), mapped(lap.operands[2])});
      for (std::size_t region = 0; region < written.regions.size(); ++region) {
        enterOutputRegion(region);
        replace(lap.result, parameter);
        rewriteRegion(written.regions[region]);
      }
      endRegions();
    }
  }

  // The regions are copied: each part's entry says how they are cut.
  void writePoint(const Instruction&, const Instruction& point) override { copy(point); }
};

} // namespace

bool splitArcLaps(Function& function) {
  return rewriteLaps<ArcLapSplitter>(function, CurveSampling::Steps);
}

} // namespace cncc::ir
