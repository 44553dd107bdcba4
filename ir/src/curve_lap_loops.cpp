// `expand-controller-loops`: each curve.lap whose table entry says how many
// uniform steps each region takes (CurveSampling::Steps) written out as the
// loops a controller runs: per region of N steps over its own parameter
// range [from, to], a loop i = 1 .. N whose body is the region's arithmetic
// at from + i (to - from) / N and a feed move there (a region of one step:
// its arithmetic at `to`, no loop). A ramp lap descends through each region
// by its share of the lap's length, in proportion to i / N. Nothing is
// tabled: the program computes every point, so the part's parameters stay
// editable at the machine.
#include "cncc/geom/math_functions.h"
#include "cncc/ir/curve_lap_offset_steps.h"
#include "cncc/ir/curve_lap_steps.h"

#include "curve_lap_rewriter.h"

#include <algorithm>
#include <functional>
#include <map>
#include <optional>

namespace cncc::ir {

namespace {

// Blocks of an arc region written out one after the other; more go in a loop.
constexpr double largestUnrolledArc = 4;

class ControllerLoopExpander : public LapRewriter {
public:
  using LapRewriter::LapRewriter;

private:
  bool writes(std::uint32_t curve) const override {
    return source_.curves[curve].sampling == CurveSampling::Steps;
  }
  void writeLap(const Instruction& lap) override { expandLap(lap); }
  void writePoint(const Instruction& lap, const Instruction& point) override {
    if (point.opcode == Opcode::CurveArc || point.opcode == Opcode::CurveWalk) {
      regionEnd_ = mappedOperands(point); // read by emitArcBlock and emitWalk
      return;
    }
    feedToPoint(lap, point);
  }

  void expandLap(const Instruction& lap) {
    const CurveTableEntry& entry = countedEntry(lap);
    shares_ = isRamp(lap) ? &sharesOf(lap) : nullptr;
    std::size_t computed = 0;
    std::vector<CurveTableEntry::RegionPlace> places = entry.regionPlaces();
    for (std::size_t region = 0; region < places.size(); ++region) {
      share_ = shares_ != nullptr ? (*shares_)[region] : LapRegionShare{};
      RegionSteps steps = stepsOf(lap, entry, region, places[region], computed);
      count_ = steps.count;
      single_ = steps.single;
      if (const ArcRegion* arc = entry.arcRegion(region)) {
        emitArcRegion(lap, *arc, steps);
      } else if (entry.isWalkRegion(region)) {
        emitWalk(lap, region, steps);
      } else if (steps.single) {
        replace(lap.result, valueOf(steps.to));
        rewriteRegion(lap.regions[region]);
      } else {
        emitLoop(lap, region, steps);
      }
    }
  }

  // A region's range and count: numbers from the entry, or the lap's
  // operands (the k-th region whose steps the program computes).
  struct RegionSteps {
    Operand from, to, count;
    bool single = false;
  };
  RegionSteps stepsOf(const Instruction& lap, const CurveTableEntry& entry, std::size_t region,
                      const CurveTableEntry::RegionPlace& place, std::size_t& computed) {
    int count = entry.regionSteps[region];
    if (count == stepsChosenByLegalisation && entry.offsetGrowth) {
      return offsetRegionSteps(lap, entry, region, place);
    }
    if (count > 0) {
      auto [from, to] = entry.regionRange(place);
      return {
          {ValueId{}, from}, {ValueId{}, to}, {ValueId{}, static_cast<double>(count)}, count == 1};
    }
    std::size_t first = 3 + 3 * computed++;
    RegionSteps steps{operandOf(mapped(lap.operands[first])),
                      operandOf(mapped(lap.operands[first + 1])),
                      operandOf(mapped(lap.operands[first + 2]))};
    steps.single = passes::constantValue(source_, lap.operands[first + 2]) == 1.0;
    return steps;
  }

  // A region of an offset whose count grows with the tool radius: the
  // program computes ROUND[N0 * SQRT[1 + q * r] + 0.5] from the distance the
  // lap reads, N0 and q measured once per entry (curve_lap_offset_steps.h).
  RegionSteps offsetRegionSteps(const Instruction& lap, const CurveTableEntry& entry,
                                std::size_t region, const CurveTableEntry::RegionPlace& place) {
    auto known = offsetGrowth_.find(lap.index);
    if (known == offsetGrowth_.end()) {
      known = offsetGrowth_.emplace(lap.index, measureOffsetGrowth(source_, lap)).first;
    }
    const OffsetRegionGrowth& growth = known->second[region];
    const OffsetStepGrowth& offset = *entry.offsetGrowth;
    Operand distance = operandOf(mapped(lap.operands.back()));
    Operand radius = offset.side > 0 ? distance : unary(Opcode::Neg, distance);
    Operand share = add({ValueId{}, 1}, multiply({ValueId{}, growth.growth}, radius));
    Operand steps = multiply({ValueId{}, growth.drawnSteps}, unary(Opcode::Sqrt, share));
    Operand count = unary(Opcode::Round, add(steps, {ValueId{}, 0.5}));
    auto [from, to] = entry.regionRange(place);
    return {{ValueId{}, from}, {ValueId{}, to}, count, false};
  }

  // -a, SQRT[a], ROUND[a]: a number where a is (as offsetStepsAt computes it).
  Operand unary(Opcode opcode, const Operand& operand) {
    if (operand.isNumber()) {
      double a = operand.number;
      double number = opcode == Opcode::Neg    ? -a
                      : opcode == Opcode::Sqrt ? geom::computeMath(geom::MathFunction::Sqrt, a)
                                               : geom::computeMath(geom::MathFunction::Round, a);
      return {ValueId{}, number};
    }
    Instruction instruction;
    instruction.opcode = opcode;
    return {emit(instruction, {operand.value}), 0};
  }

  // How the controller of the lap's cut reads its steps: literals of the
  // cut's controller digits (none: exactly), within its tolerance.
  std::optional<StepReading> stepReading() const {
    std::optional<std::uint32_t> cut = currentCut();
    if (!cut || *cut >= source_.cuts.size()) {
      return std::nullopt;
    }
    const CutGeometry& geometry = source_.cuts[*cut];
    if (!geometry.controllerDigits || *geometry.controllerDigits <= 0) {
      return std::nullopt;
    }
    return StepReading{*geometry.controllerDigits, geometry.budget().toleranceOrDefault()};
  }

  // The lap's entry with the counts it leaves to the legalisation chosen
  // (curve_lap_steps.h), once per entry, and checked against the
  // controller's reading of their steps; the output's entry says them.
  const CurveTableEntry& countedEntry(const Instruction& lap) {
    const CurveTableEntry& entry = source_.curves[lap.index];
    std::optional<StepReading> reading = stepReading();
    if (!hasChosenSteps(entry) && !reading) {
      return entry;
    }
    auto known = counted_.find(lap.index);
    if (known == counted_.end()) {
      std::shared_ptr<const geom::Curve> curve = curveOf(lap);
      CurveTableEntry counted = withChosenSteps(entry, *curve);
      if (reading) {
        checkStepDrift(counted, *curve, reading->digits, reading->tolerance);
      }
      if (lap.index < output_.curves.size()) {
        // As written: an offset's count that grows with the radius, the program's.
        std::vector<int>& written = output_.curves[lap.index].regionSteps;
        written = counted.regionSteps;
        std::replace(written.begin(), written.end(), stepsChosenByLegalisation, 0);
      }
      known = counted_.emplace(lap.index, std::move(counted)).first;
    }
    return known->second;
  }

  const std::vector<LapRegionShare>& sharesOf(const Instruction& lap) {
    auto known = entryShares_.find(lap.index);
    if (known == entryShares_.end()) {
      known =
          entryShares_.emplace(lap.index, descentShares(source_.curves[lap.index], *curveOf(lap)))
              .first;
    }
    return known->second;
  }

  // (to - from) / count: a number where the range and count are, else
  // computed where it is asked.
  Operand stepOf(const RegionSteps& steps) {
    bool numbers = steps.from.isNumber() && steps.to.isNumber() && steps.count.isNumber();
    if (numbers) {
      return {ValueId{}, (steps.to.number - steps.from.number) / steps.count.number};
    }
    return arithmetic(Opcode::Div, arithmetic(Opcode::Sub, steps.to, steps.from), steps.count);
  }

  // i = 1 .. count, the region at from + i * step.
  void emitLoop(const Instruction& lap, std::size_t region, const RegionSteps& steps) {
    ValueId first = constant(1);
    ValueId last = valueOf(steps.count);
    ValueId index = beginLapLoop(lap, first, last);
    Operand step = stepOf(steps);
    Operand t = add(steps.from, multiply({index, 0}, step));
    index_ = index;
    replace(lap.result, valueOf(t));
    rewriteRegion(lap.regions[region]);
    endRegions();
  }

  // The region's curve.point: a feed move there, raised by the lap's height.
  void feedToPoint(const Instruction& lap, const Instruction& point) {
    std::vector<ValueId> operands = mappedOperands(point);
    ValueId z = valueOf(add(heightDone(lap, std::nullopt), operandOf(operands[2])));
    emitFeedMove(lap, operands[0], operands[1], z);
  }

  // The lap's height where `fraction` of the region is done (nullopt: the
  // step's i / count): on a ramp, from + (to - from) (before + share fraction).
  Operand heightDone(const Instruction& lap, std::optional<Operand> fraction) {
    Operand height = operandOf(mapped(lap.operands[1]));
    if (shares_ == nullptr) {
      return height;
    }
    if (!fraction) {
      fraction = single_ ? Operand{ValueId{}, 1} : arithmetic(Opcode::Div, {index_, 0}, count_);
    }
    Operand done = add({ValueId{}, share_.before}, multiply({ValueId{}, share_.share}, *fraction));
    Operand from = operandOf(mapped(lap.operands[0]));
    Operand rise = arithmetic(Opcode::Sub, height, from);
    return add(from, multiply(rise, done));
  }

  // An arc region in `count` blocks of equal turn, block j from
  // from + (j - 1) step to from + j step: written out one after the other
  // up to largestUnrolledArc, in a loop beyond (or when the program computes
  // the count).
  void emitArcRegion(const Instruction& lap, const ArcRegion& arc, const RegionSteps& steps) {
    if (steps.single) {
      emitArcBlock(lap, arc, steps.from, steps.to, Operand{ValueId{}, 1});
      return;
    }
    if (steps.count.isNumber() && steps.count.number <= largestUnrolledArc) {
      Operand step = stepOf(steps);
      for (double j = 1; j <= steps.count.number; ++j) {
        emitArcBlock(lap, arc,
                     arc.wholeTurns ? steps.from
                                    : add(steps.from, multiply({ValueId{}, j - 1}, step)),
                     add(steps.from, multiply({ValueId{}, j}, step)),
                     Operand{ValueId{}, j / steps.count.number});
      }
      return;
    }
    ValueId count = valueOf(steps.count);
    index_ = beginLapLoop(lap, constant(1), count);
    Operand index{index_, 0};
    Operand step = stepOf(steps);
    Operand start =
        arc.wholeTurns
            ? steps.from
            : add(steps.from, multiply(arithmetic(Opcode::Sub, index, {ValueId{}, 1}), step));
    emitArcBlock(lap, arc, start, add(steps.from, multiply(index, step)), std::nullopt);
    endRegions();
  }

  // A walk from the region's start while u is below its end: the step the
  // region computes at u, a feed to its point at min(u + step, end), which
  // is the loop's next u (loop.next).
  void emitWalk(const Instruction& lap, std::size_t region, const RegionSteps& steps) {
    ValueId to = valueOf(steps.to);
    ValueId u = beginLapLoop(lap, valueOf(steps.from), to);
    rewriteRegionFor(lap, region, u, {3});
    Operand next = minimum(add({u, 0}, operandOf(regionEnd_[3])), steps.to);
    rewriteRegionFor(lap, region, valueOf(next), {0, 1, 2});
    std::vector<ValueId> point = regionEnd_;
    // On a ramp, done: (next - from) / (to - from), next itself on 0 .. 1.
    Operand done = shares_ == nullptr
                       ? next
                       : arithmetic(Opcode::Div, arithmetic(Opcode::Sub, next, steps.from),
                                    arithmetic(Opcode::Sub, steps.to, steps.from));
    ValueId z = valueOf(add(heightDone(lap, done), operandOf(point[2])));
    emitFeedMove(lap, point[0], point[1], z);
    Instruction advance;
    advance.opcode = Opcode::LoopNext;
    emit(advance, {valueOf(next)});
    endRegions();
  }

  Operand minimum(const Operand& a, const Operand& b) { return {binary(Opcode::Min, a, b), 0}; }

  // One move.arc: to the region's point at `to` about the centre seen from
  // its point at `from`; whole turns (`from` the region's start) end where
  // the region starts (its values, with no rounding between).
  // `fraction`: of the region done at its end (nullopt: the loop's i / count).
  void emitArcBlock(const Instruction& lap, const ArcRegion& arc, const Operand& from,
                    const Operand& to, std::optional<Operand> fraction) {
    std::size_t region = arc.region;
    if (arc.wholeTurns) {
      rewriteRegionFor(lap, region, valueOf(to), {2});
    } else {
      rewriteRegionFor(lap, region, valueOf(to), {0, 1, 2});
    }
    std::vector<ValueId> end = regionEnd_;
    if (arc.wholeTurns) {
      rewriteRegionFor(lap, region, valueOf(from), {0, 1, 3, 4});
      end[0] = regionEnd_[0];
      end[1] = regionEnd_[1];
    } else {
      rewriteRegionFor(lap, region, valueOf(from), {3, 4});
    }
    Instruction move;
    move.opcode = Opcode::Arc;
    move.index = static_cast<std::uint32_t>(arc.counterClockwise ? ArcTurn::CounterClockwise
                                                                 : ArcTurn::Clockwise);
    move.span = lap.span;
    move.pass = lap.pass;
    ValueId z = valueOf(add(heightDone(lap, fraction), operandOf(end[2])));
    emit(move, {end[0], end[1], z, regionEnd_[3], regionEnd_[4], mapped(lap.operands[2])});
  }

  // A ramp lap's regions' shares (null on a level lap), and the region's;
  // the region's count of steps and its loop's index (the fraction done:
  // i / count; 1 for a single step).
  const std::vector<LapRegionShare>* shares_ = nullptr;
  LapRegionShare share_;
  Operand count_;
  bool single_ = true;
  ValueId index_;
  std::map<std::uint32_t, std::vector<LapRegionShare>> entryShares_;
  std::vector<ValueId> regionEnd_; // the operands of an arc's or walk's end just written
  std::map<std::uint32_t, CurveTableEntry> counted_; // by curve: its chosen counts
  std::map<std::uint32_t, std::vector<OffsetRegionGrowth>> offsetGrowth_; // by curve
};

} // namespace

std::vector<StepRange> lapStepRanges(const CurveTableEntry& entry,
                                     const std::function<StepRange(std::size_t)>& computed) {
  std::vector<StepRange> ranges;
  std::size_t computedSoFar = 0;
  std::vector<CurveTableEntry::RegionPlace> places = entry.regionPlaces();
  for (std::size_t region = 0; region < places.size(); ++region) {
    int count = region < entry.regionSteps.size() ? entry.regionSteps[region] : 0;
    if (count == 0) {
      ranges.push_back(computed(computedSoFar++));
    } else {
      auto [from, to] = entry.regionRange(places[region]);
      ranges.push_back({from, to, static_cast<double>(count), count == 1});
    }
  }
  return ranges;
}

std::vector<LapStep> lapSteps(const std::vector<StepRange>& ranges) {
  std::vector<LapStep> steps;
  for (std::size_t region = 0; region < ranges.size(); ++region) {
    forEachRegionStep(region, ranges[region], [&](const LapStep& step) { steps.push_back(step); });
  }
  return steps;
}

bool expandControllerLoops(Function& function) {
  return rewriteLaps<ControllerLoopExpander>(function, CurveSampling::Steps);
}

} // namespace cncc::ir
