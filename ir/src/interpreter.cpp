#include "cncc/ir/interpreter.h"

#include "cncc/ir/arithmetic.h"
#include "cncc/ir/curve_blocks.h"
#include "cncc/ir/curve_lap.h"
#include "cncc/ir/curve_lap_offset_steps.h"
#include "cncc/ir/curve_lap_steps.h"
#include "cncc/ir/nurbs_move.h"
#include "cncc/ir/polynomial_move.h"
#include "cncc/ir/printer.h"
#include "cncc/ir/spline_move.h"

#include "legalised_entries.h"
#include "passes/rewriter.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <map>
#include <memory>
#include <variant>

namespace cncc::ir {

namespace {

class Interpreter {
public:
  Interpreter(const Function& function, const InterpreterOptions& options,
              MachineEventSink* sink = nullptr)
      : function_(function), options_(options), sink_(sink),
        values_(function.valueTypes.size(), 0.0) {
    for (const Parameter& parameter : function.parameters) {
      auto given = options.parameters.find(parameter.name);
      parameters_.push_back(given == options.parameters.end() ? parameter.defaultValue
                                                              : given->second);
    }
  }

  ToolPath run() {
    runRegion(function_.body);
    return std::move(path_);
  }

private:
  double value(ValueId id) const { return values_[id.index]; }

  void runRegion(const Region& region) {
    for (InstructionId id : region.instructions) {
      countStep();
      std::size_t first = path_.events.size();
      runInstruction(function_.instructions[id]);
      numberPassEvents(first);
      if (sink_ != nullptr) {
        passEventsToSink();
      } else if (path_.events.size() > options_.maximumEvents) {
        throw InterpreterError(
            fmt::format("the program makes more than {} events", options_.maximumEvents));
      }
    }
  }

  // An instruction's events (a NURBS block makes many) go to the sink once
  // it has run: it reads back the last of them.
  void passEventsToSink() {
    for (const MachineEvent& event : path_.events) {
      sink_->event(event);
    }
    path_.events.clear();
  }

  void runInstruction(const Instruction& instruction) {
    const std::vector<ValueId>& operands = instruction.operands;
    double result = 0;
    switch (instruction.opcode) {
    case Opcode::Const:
    case Opcode::ConstBool:
      result = instruction.number;
      break;
    case Opcode::Param:
      result = parameters_[instruction.index];
      break;
    case Opcode::TableLoad:
      result = tableLoad(instruction);
      break;
    case Opcode::Select:
      result = value(operands[0]) != 0 ? value(operands[1]) : value(operands[2]);
      break;
    case Opcode::Loop:
      runLoop(instruction);
      return;
    case Opcode::LoopNext:
      return; // read by the loop when its body is done
    case Opcode::If:
      runRegion(instruction.regions[value(operands[0]) != 0 ? 0 : 1]);
      return;
    case Opcode::CurveLap:
      runCurveLap(instruction);
      return;
    case Opcode::CurvePoint: // read by its lap when the region is done
      lapPoint_ = {value(operands[0]), value(operands[1]), value(operands[2])};
      return;
    case Opcode::CurveArc:
      lapPoint_ = {value(operands[0]), value(operands[1]), value(operands[2])};
      lapToCentre_ = {value(operands[3]), value(operands[4])};
      return;
    case Opcode::CurveWalk:
      lapPoint_ = {value(operands[0]), value(operands[1]), value(operands[2])};
      lapWalkStep_ = value(operands[3]);
      return;
    case Opcode::Arc:
      recordArc(instruction);
      return;
    case Opcode::Nurbs:
      recordNurbs(instruction);
      return;
    case Opcode::Spline:
      recordSpline(instruction);
      return;
    case Opcode::Polynomial:
      recordPolynomial(instruction);
      return;
    case Opcode::Alarm:
      throw InterpreterError("alarm: " + instruction.text);
    case Opcode::Rapid:
    case Opcode::Climb:
    case Opcode::Feed:
    case Opcode::Spindle:
    case Opcode::Tool:
    case Opcode::Origin:
    case Opcode::Coolant:
    case Opcode::Contouring:
    case Opcode::Home:
    case Opcode::Comment:
    case Opcode::PassBegin:
    case Opcode::CutBegin:
    case Opcode::Compensation:
    case Opcode::CornerArc:
      record(instruction);
      return;
    default:
      result = (operands.size() == 1
                    ? unaryResult(instruction.opcode, value(operands[0]))
                    : binaryResult(instruction.opcode, value(operands[0]), value(operands[1])))
                   .value_or(NAN);
      break;
    }
    values_[instruction.result.index] = result;
  }

  double tableLoad(const Instruction& instruction) const {
    const std::vector<double>& table = function_.tables[instruction.index];
    double index = value(instruction.operands[0]);
    if (!(index >= 0 && index < static_cast<double>(table.size()))) {
      throw InterpreterError(fmt::format("index {} is outside table @{} of {} entries", index,
                                         instruction.index, table.size()));
    }
    return table[static_cast<std::size_t>(index)];
  }

  void runLoop(const Instruction& loop) {
    double low = value(loop.operands[0]);
    double high = value(loop.operands[1]);
    if (!std::isfinite(low) || !std::isfinite(high)) {
      throw InterpreterError("a loop bound is not a finite number");
    }
    ValueId advance = loopAdvance(function_, loop);
    if (advance.valid()) {
      runAdvancingLoop(loop, low, high, advance);
      return;
    }
    SweepPass outer = passTrip_;
    for (double i = low; i <= high; ++i) {
      if (static_cast<LoopRole>(loop.index) == LoopRole::Passes) {
        passTrip_ = passTrip(i - low + 1, std::floor(high - low) + 1);
      }
      values_[loop.result.index] = i;
      runRegion(loop.regions[0]);
    }
    passTrip_ = outer;
  }

  // The events from `first` on, made in a trip of a pass loop, are that
  // pass's (where their instruction has none of its own).
  void numberPassEvents(std::size_t first) {
    for (std::size_t k = first; passTrip_.number != 0 && k < path_.events.size(); ++k) {
      path_.events[k].pass = passInLoop(path_.events[k].pass, passTrip_.number, passTrip_.count);
    }
  }

  // The variable runs from low while below high, taking the value of the
  // body's loop.next after each pass; a next value that does not exceed it
  // would never end the loop.
  void runAdvancingLoop(const Instruction& loop, double low, double high, ValueId advance) {
    for (double u = low; u < high;) {
      values_[loop.result.index] = u;
      runRegion(loop.regions[0]);
      double next = value(advance);
      if (!(next > u)) {
        throw InterpreterError(
            fmt::format("a loop's variable does not advance: {} after {}", next, u));
      }
      u = next;
    }
  }

  // The points of a lap chosen on its curve, and the ramp's progress at
  // each once a ramp lap asks; for the values the curve read from outside.
  struct LapPoints {
    std::vector<double> outside;
    std::shared_ptr<const geom::Curve> curve;
    std::vector<double> parameters;
    std::vector<double> progress;
    std::optional<LapArcs> arcs;            // a lap cut as arcs: its moves, no parameters
    std::vector<double> blocks;             // blocks fitted to it: their table's data
    std::vector<double> blockWeights;       // and a NURBS block's weights
    std::string blocksComment;              // or spline blocks' comment
    std::optional<CurveTableEntry> counted; // a lap cut in steps: its chosen counts
    std::vector<LapRegionShare> shares;     // a ramp lap cut in steps: each region's
  };

  // The lap as its entry after the legalisations says (a lap split at its
  // arcs: each part in turn).
  void runCurveLap(const Instruction& lap) {
    if (const LegalisedEntries::SplitLap* split = legalisedEntries_.splitOf(lap)) {
      for (std::size_t part = 0; part < split->laps.size(); ++part) {
        runCurveLap(split->laps[part], split->parts[part].entry);
      }
      return;
    }
    runCurveLap(lap, legalisedEntries_.of(lap));
  }

  // A feed move to each point after the first, the region that holds it
  // run at its own parameter, raised by the lap's height there.
  void runCurveLap(const Instruction& lap, const CurveTableEntry& entry) {
    double zFrom = value(lap.operands[0]);
    double zTo = value(lap.operands[1]);
    double feed = value(lap.operands[2]);
    bool ramp = zFrom != zTo;
    if (ramp && (entry.sampling == CurveSampling::Arcs || entry.isBlocks())) {
      throw InterpreterError(
          fmt::format("a lap cut by {} is level: its two heights must be one value",
                      curveSamplingName(entry.sampling)));
    }
    if (entry.isBlocks()) {
      Opcode kind = entry.sampling == CurveSampling::NurbsBlocks    ? Opcode::Nurbs
                    : entry.sampling == CurveSampling::SplineBlocks ? Opcode::Spline
                                                                    : Opcode::Polynomial;
      if (entry.blockTable) {
        recordBlocks(lap, kind, *entry.blockTable, function_.tables[*entry.blockTable], zTo, feed,
                     operandValues(lap, 3));
        return;
      }
      // Blocks the legalisation fits (curve_blocks.h), fitted as it does
      // (spline blocks after the comment it writes).
      const LapPoints& points = lapPoints(lap, entry, false);
      if (!points.blocksComment.empty()) {
        recordAt(lap, commentEvent(points.blocksComment));
      }
      recordBlocks(lap, kind, 0, points.blocks, zTo, feed, points.blockWeights);
      return;
    }
    if (entry.arcsAsked && !ramp) {
      // Arcs where a fit keeps them, as fit-arcs decides.
      const LapPoints& points = lapPoints(lap, entry, false);
      if (points.arcs) {
        runArcLap(lap, *points.arcs, zTo + points.arcs->planeZ, feed);
        return;
      }
    }
    if (entry.sampling == CurveSampling::Steps) {
      runSteppedLap(lap, entry, zFrom, zTo, feed);
      return;
    }
    const LapPoints& points = lapPoints(lap, entry, ramp);
    if (points.arcs) {
      runArcLap(lap, *points.arcs, zTo + points.arcs->planeZ, feed);
      return;
    }
    for (std::size_t k = 1; k < points.parameters.size(); ++k) {
      countStep();
      CurveLocation location = entry.locate(points.parameters[k]);
      values_[lap.result.index] = location.local;
      runRegion(lap.regions[location.region]);
      feedToLapPoint(lap, ramp ? zFrom + (zTo - zFrom) * points.progress[k] : zTo, feed);
    }
  }

  // The lap's regions at their steps' parameters, as the controller's loops
  // compute them; a ramp descends by each region's share of the lap's length.
  void runSteppedLap(const Instruction& lap, const CurveTableEntry& entry, double zFrom, double zTo,
                     double feed) {
    const std::vector<LapRegionShare>* shares =
        zFrom != zTo ? &lapPoints(lap, entry, true).shares : nullptr;
    // Counts left to the legalisation, chosen as it chooses them.
    const LapPoints* points =
        hasChosenSteps(entry) ? &lapPoints(lap, entry, zFrom != zTo) : nullptr;
    const CurveTableEntry& counted = points != nullptr ? *points->counted : entry;
    std::optional<CurveTableEntry> grown = withOffsetSteps(lap, counted);
    std::vector<StepRange> ranges =
        lapStepRanges(grown ? *grown : counted, [&](std::size_t computed) {
          std::size_t first = 3 + 3 * computed;
          ValueId count = lap.operands[first + 2];
          return StepRange{value(lap.operands[first]), value(lap.operands[first + 1]), value(count),
                           passes::constantValue(function_, count) == 1.0};
        });
    for (std::size_t region = 0; region < ranges.size(); ++region) {
      // The lap's height where `fraction` of the region is done.
      auto heightAt = [&](double fraction) {
        if (shares == nullptr) {
          return zTo;
        }
        const LapRegionShare& share = (*shares)[region];
        return zFrom + (zTo - zFrom) * (share.before + share.share * fraction);
      };
      const StepRange& range = ranges[region];
      if (entry.isWalkRegion(region)) {
        runWalk(lap, region, range, heightAt, feed);
        continue;
      }
      const ArcRegion* arc = entry.arcRegion(region);
      double start = range.from; // of an arc's block: the step before
      forEachRegionStep(region, range, [&](const LapStep& step) {
        countStep();
        if (arc != nullptr) {
          runArcBlock(lap, *arc, arc->wholeTurns ? range.from : start, step.local,
                      heightAt(step.fraction), feed);
        } else {
          regionPoint(lap, region, step.local);
          feedToLapPoint(lap, heightAt(step.fraction), feed);
        }
        start = step.local;
      });
    }
  }

  // The entry with an offset's counts that grow with the tool radius as the
  // program computes them at the distance the lap reads; nullopt for an
  // entry without them.
  std::optional<CurveTableEntry> withOffsetSteps(const Instruction& lap,
                                                 const CurveTableEntry& counted) {
    if (!counted.offsetGrowth) {
      return std::nullopt;
    }
    // Measured at the compiled values: once per entry (as the pass does),
    // whatever its laps read.
    auto known = offsetGrowth_.find(lap.index);
    if (known == offsetGrowth_.end()) {
      try {
        known = offsetGrowth_.emplace(lap.index, measureOffsetGrowth(function_, lap)).first;
      } catch (const CurveLapError& error) {
        throw InterpreterError(error.what());
      }
    }
    CurveTableEntry entry = counted;
    double distance = value(lap.operands.back());
    double most = std::min(static_cast<double>(options_.maximumSteps),
                           static_cast<double>(std::numeric_limits<int>::max()));
    for (std::size_t region = 0; region < entry.regionSteps.size(); ++region) {
      if (entry.regionSteps[region] != stepsChosenByLegalisation) {
        continue;
      }
      double steps = offsetStepsAt(known->second[region], *entry.offsetGrowth, distance);
      if (!(steps >= 1 && steps <= most)) {
        throw InterpreterError(fmt::format("the program computes {} steps for a piece of a cut "
                                           "beside its curve at the tool-centre distance {:g}",
                                           steps, distance));
      }
      entry.regionSteps[region] = static_cast<int>(steps);
    }
    return entry;
  }

  // A walked region from its start: at each u the step the region computes
  // there, to min(u + step, end), while u is below the end.
  template <class HeightAt>
  void runWalk(const Instruction& lap, std::size_t region, const StepRange& range,
               const HeightAt& heightAt, double feed) {
    for (double u = range.from; u < range.to;) {
      countStep();
      regionPoint(lap, region, u);
      // min as the program's min computes it (a NaN step included).
      double next = *binaryResult(Opcode::Min, u + lapWalkStep_, range.to);
      if (!(next > u)) {
        throw InterpreterError(
            fmt::format("a walk along a curve does not advance: {} after {}", next, u));
      }
      regionPoint(lap, region, next);
      feedToLapPoint(lap, heightAt((next - range.from) / (range.to - range.from)), feed);
      u = next;
    }
  }

  // The point (and offset to the centre) a region computes at t.
  void regionPoint(const Instruction& lap, std::size_t region, double t) {
    values_[lap.result.index] = t;
    runRegion(lap.regions[region]);
  }

  // A move.arc block of an arc region from its parameter `from` to `to`,
  // its end raised by height; whole turns end where they start.
  void runArcBlock(const Instruction& lap, const ArcRegion& arc, double from, double to,
                   double height, double feed) {
    regionPoint(lap, arc.region, from);
    std::array<double, 3> start = lapPoint_;
    std::array<double, 2> toCentre = lapToCentre_;
    regionPoint(lap, arc.region, to);
    std::array<double, 3> end = lapPoint_;
    if (arc.wholeTurns) {
      end[0] = start[0];
      end[1] = start[1];
    }
    MachineEvent event =
        arcMove(position_, arc.counterClockwise ? ArcTurn::CounterClockwise : ArcTurn::Clockwise,
                end[0], end[1], height + end[2], toCentre[0], toCentre[1], feed);
    event.span = lap.span;
    event.pass = lap.pass;
    recordLapMove(std::move(event));
  }

  // A feed move to the point the region just run computed, raised by height.
  void feedToLapPoint(const Instruction& lap, double height, double feed) {
    MachineEvent event;
    event.kind = MachineEvent::Kind::Feed;
    event.x = lapPoint_[0];
    event.y = lapPoint_[1];
    event.z = height + lapPoint_[2];
    event.feed = feed;
    event.span = lap.span;
    event.pass = lap.pass;
    recordLapMove(std::move(event));
  }

  // The lap's arcs and lines at height z.
  void runArcLap(const Instruction& lap, const LapArcs& arcs, double z, double feed) {
    for (const LapArcMove& move : arcs.moves) {
      countStep();
      MachineEvent event;
      if (move.turn) {
        event = arcMove(position_, *move.turn, move.end.x(), move.end.y(), z, move.centreOffset.x(),
                        move.centreOffset.y(), feed);
      } else {
        event.kind = MachineEvent::Kind::Feed;
        event.x = move.end.x();
        event.y = move.end.y();
        event.z = z;
        event.feed = feed;
      }
      event.span = lap.span;
      event.pass = lap.pass;
      recordLapMove(std::move(event));
    }
  }

  void countStep() {
    if (++steps_ > options_.maximumSteps) {
      throw InterpreterError(
          fmt::format("the program takes more than {} steps", options_.maximumSteps));
    }
  }

  void recordLapMove(MachineEvent event) {
    position_ = {event.x, event.y, event.z};
    path_.events.push_back(std::move(event));
    if (sink_ == nullptr && path_.events.size() > options_.maximumEvents) {
      throw InterpreterError(
          fmt::format("the program makes more than {} events", options_.maximumEvents));
    }
  }

  // Chosen once per lap and values read from outside it (a lap in a loop
  // over passes goes along the same curve each time).
  // The blocks write-curve-blocks fits to a lap that names no table.
  static void fitBlocks(const CurveTableEntry& entry, LapPoints& points) {
    if (entry.sampling == CurveSampling::PolynomialBlocks) {
      points.blocks = polynomialMoveTable(lapPolynomialSpans(entry, *points.curve));
      return;
    }
    if (entry.sampling == CurveSampling::SplineBlocks) {
      FittedSplineBlocks blocks = lapSplineBlocks(entry, *points.curve);
      points.blocks = splineMoveTable(blocks.data);
      points.blocksComment = splineBlocksComment(blocks);
      return;
    }
    FittedNurbsBlock block = lapFittedNurbs(entry, *points.curve);
    points.blocks = std::move(block.table);
    points.blockWeights = std::move(block.weights);
  }

  // What a lap's regions read from outside it, as the program has them
  // now; each value asked is added to `asked`.
  OutsideValue outsideOf(std::vector<double>& asked) {
    return [this, &asked](ValueId outside) -> std::optional<double> {
      const Instruction& definition = function_.definition(outside);
      double number =
          definition.opcode == Opcode::Param ? parameters_[definition.index] : value(outside);
      asked.push_back(number);
      return number;
    };
  }

  // The arcs an entry asks for, where a fit keeps them.
  static void askArcs(const CurveTableEntry& entry, LapPoints& points) {
    std::variant<LapArcs, std::string> fitted = askedLapArcs(entry, *points.curve);
    if (LapArcs* arcs = std::get_if<LapArcs>(&fitted)) {
      points.arcs = std::move(*arcs);
    }
  }

  const LapPoints& lapPoints(const Instruction& lap, const CurveTableEntry& entry, bool ramp) {
    LapPoints fresh;
    try {
      fresh.curve = lapCurve(function_, lap, entry, outsideOf(fresh.outside));
      std::vector<LapPoints>& known = lapPoints_[&lap];
      auto same = std::find_if(known.begin(), known.end(), [&](const LapPoints& points) {
        return std::equal(points.outside.begin(), points.outside.end(), fresh.outside.begin(),
                          fresh.outside.end(), [](double a, double b) {
                            return std::bit_cast<std::uint64_t>(a) ==
                                   std::bit_cast<std::uint64_t>(b);
                          });
      });
      if (same == known.end()) {
        if (known.size() >= maximumCurvesPerLap) {
          known.erase(known.begin());
        }
        if (entry.arcsAsked && !ramp) {
          askArcs(entry, fresh);
        }
        if (entry.sampling == CurveSampling::Arcs) {
          fresh.arcs = lapArcs(entry, *fresh.curve);
        } else if (entry.isBlocks()) {
          fitBlocks(entry, fresh);
        } else if (entry.sampling == CurveSampling::Steps && hasChosenSteps(entry)) {
          fresh.counted = withChosenSteps(entry, *fresh.curve);
        } else if (entry.sampling != CurveSampling::Steps) {
          fresh.parameters = lapParameters(entry, *fresh.curve);
        }
        known.push_back(std::move(fresh));
        same = known.end() - 1;
      }
      if (ramp && entry.sampling == CurveSampling::Steps) {
        if (same->shares.empty()) {
          same->shares = descentShares(entry, *same->curve);
        }
      } else if (ramp && entry.sampling != CurveSampling::Arcs && same->progress.empty()) {
        same->progress = lapProgress(entry, *same->curve, same->parameters);
      }
      return *same;
    } catch (const CurveLapError& error) {
      throw InterpreterError(error.what());
    }
  }

  void record(const Instruction& instruction) {
    std::array<double, 4> operands{};
    for (std::size_t k = 0; k < operands.size() && k < instruction.operands.size(); ++k) {
      operands[k] = value(instruction.operands[k]);
    }
    MachineEvent event = instruction.opcode == Opcode::Climb ? climbEvent(position_, operands[0])
                                                             : effectEvent(instruction, operands);
    if (isMove(event)) {
      position_ = {event.x, event.y, event.z};
    }
    recordAt(instruction, std::move(event));
  }

  static MachineEvent commentEvent(std::string text) {
    MachineEvent event;
    event.kind = MachineEvent::Kind::Comment;
    event.text = std::move(text);
    return event;
  }

  // The event, as made by `instruction` (its source and pass).
  void recordAt(const Instruction& instruction, MachineEvent event) {
    event.span = instruction.span;
    event.pass = instruction.pass;
    path_.events.push_back(std::move(event));
  }

  void recordArc(const Instruction& instruction) {
    auto operand = [&](std::size_t k) { return value(instruction.operands[k]); };
    MachineEvent event = arcMove(position_, static_cast<ArcTurn>(instruction.index), operand(0),
                                 operand(1), operand(2), operand(3), operand(4), operand(5));
    position_ = {event.x, event.y, event.z};
    event.span = instruction.span;
    event.pass = instruction.pass;
    path_.events.push_back(std::move(event));
  }

  void recordNurbs(const Instruction& instruction) {
    recordBlocks(instruction, Opcode::Nurbs, instruction.index, function_.tables[instruction.index],
                 value(instruction.operands[0]), value(instruction.operands[1]),
                 operandValues(instruction, 2));
  }

  void recordSpline(const Instruction& instruction) {
    recordBlocks(instruction, Opcode::Spline, instruction.index,
                 function_.tables[instruction.index], value(instruction.operands[0]),
                 value(instruction.operands[1]), {});
  }

  // The values of the instruction's operands from `first` on.
  std::vector<double> operandValues(const Instruction& instruction, std::size_t first) {
    std::vector<double> values;
    for (std::size_t k = first; k < instruction.operands.size(); ++k) {
      values.push_back(value(instruction.operands[k]));
    }
    return values;
  }

  // The moves of a NURBS block, of spline blocks or of cubic spans
  // (move.nurbs, move.spline, or a curve.lap cut as them, or as
  // move.polynomials) from `data` (table `table`'s, or what a lap that
  // names none is fitted to) at height z; a NURBS block's `weights`.
  void recordBlocks(const Instruction& instruction, Opcode kind, std::uint32_t table,
                    std::span<const double> data, double z, double feed,
                    const std::vector<double>& weights) {
    std::size_t first = path_.events.size();
    if (kind == Opcode::Nurbs) {
      nurbsMove(position_, data, z, feed, weights, path_.events);
    } else if (kind == Opcode::Spline) {
      splineMove(table, data, z, feed, path_.events);
    } else {
      std::string problem;
      std::optional<std::vector<PolynomialMove>> spans = readPolynomialMoveTable(data, &problem);
      if (!spans) {
        throw InterpreterError(problem);
      }
      for (PolynomialMove span : *spans) {
        span.end.z() += z;
        polynomialMove(position_, span, feed, path_.events);
        position_ = {span.end.x(), span.end.y(), span.end.z()};
      }
    }
    madeBy(instruction, first);
  }

  // The events from `first` on as made by `instruction`, which ends where
  // the last of them does.
  void madeBy(const Instruction& instruction, std::size_t first) {
    for (std::size_t k = first; k < path_.events.size(); ++k) {
      path_.events[k].span = instruction.span;
      path_.events[k].pass = instruction.pass;
    }
    const MachineEvent& end = path_.events.back();
    position_ = {end.x, end.y, end.z};
  }

  void recordPolynomial(const Instruction& instruction) {
    std::array<double, 12> values{};
    for (std::size_t k = 0; k < values.size(); ++k) {
      values[k] = value(instruction.operands[k]);
    }
    std::size_t first = path_.events.size();
    polynomialMove(position_, polynomialMoveOf(values), value(instruction.operands[12]),
                   path_.events);
    madeBy(instruction, first);
  }

  const Function& function_;
  const InterpreterOptions& options_;
  MachineEventSink* sink_;
  std::array<double, 3> position_{0, 0, 0};
  std::vector<double> values_;
  std::vector<double> parameters_;
  ToolPath path_;
  std::size_t steps_ = 0;
  SweepPass passTrip_; // the trip of the pass loop being run, if any
  // The point the last curve.point gave.
  std::array<double, 3> lapPoint_{0, 0, 0};
  std::array<double, 2> lapToCentre_{0, 0}; // of an arc region's point
  double lapWalkStep_ = 0;                  // of a walked region's point
  // The curves a lap kept, the latest last.
  static constexpr std::size_t maximumCurvesPerLap = 8;
  std::map<const Instruction*, std::vector<LapPoints>> lapPoints_;
  LegalisedEntries legalisedEntries_{function_, [this](ValueId id) { return value(id); }};
  std::map<std::uint32_t, std::vector<OffsetRegionGrowth>> offsetGrowth_; // by curve
};

} // namespace

ToolPath interpret(const Function& function, const InterpreterOptions& options) {
  return Interpreter(function, options).run();
}

void interpret(const Function& function, MachineEventSink& sink,
               const InterpreterOptions& options) {
  Interpreter(function, options, &sink).run();
}

} // namespace cncc::ir
