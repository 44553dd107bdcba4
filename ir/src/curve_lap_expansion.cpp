// `expand-curve-laps`: each curve.lap written out for a target that runs
// the host's choice of points. The lap's points are chosen once per curve
// table entry (lapParameters); consecutive points in one region make a run:
// a loop over a table of the region's parameters (and of the ramp's
// progress) whose body is the region's arithmetic and a feed move. A region
// the entry marks, whose points need no parameter, is tabled as points.
#include "curve_lap_rewriter.h"
#include "lap_cuts.h"

#include <array>
#include <map>

namespace cncc::ir {

namespace {

// The x, y and z of a run's points as tables, or a number where every
// point has the same.
struct HostPoints {
  std::array<std::optional<std::uint32_t>, 3> tables;
  std::array<double, 3> constant = {0, 0, 0};
};

struct Run {
  std::size_t region = 0;
  std::vector<double> locals;
  std::vector<double> progress;
  std::uint32_t localTable = 0;
  std::optional<std::uint32_t> progressTable;
  bool hostDecided = false;
  std::optional<HostPoints> host;
};

class CurveLapExpander : public LapRewriter {
public:
  explicit CurveLapExpander(const Function& source) : LapRewriter(source) {
    for (const std::vector<double>& table : source.tables) {
      tableEntries_ += table.size();
    }
  }

private:
  bool writes(std::uint32_t) const override { return true; }
  void writeLap(const Instruction& lap) override { expandLap(lap); }
  void writePoint(const Instruction& lap, const Instruction& point) override {
    feedToPoint(lap, point);
  }

  // The entry's points as numbers, a feed move each: where it asks for them
  // and a controller computes the program (the host's program is its
  // points either way; tables keep its IR small).
  bool asNumbers(const CurveTableEntry& entry) const {
    std::optional<std::uint32_t> cut = currentCut();
    return entry.pointsAsNumbers && !(cut && hostComputedCut(source_, *cut) != nullptr);
  }

  // An entry's points, chosen once, and their runs.
  struct EntryPoints {
    std::shared_ptr<const geom::Curve> curve;
    std::vector<double> parameters;
    std::vector<Run> runs;
  };

  std::vector<Run>& runsOf(const Instruction& lap, bool ramp) {
    auto known = entries_.find(lap.index);
    if (known != entries_.end()) {
      addProgressTables(known->second, lap, ramp);
      return known->second.runs;
    }
    const CurveTableEntry& entry = source_.curves[lap.index];
    EntryPoints& points = entries_[lap.index];
    points.curve = curveOf(lap);
    points.parameters = lapParameters(entry, *points.curve);
    std::vector<Run>& runs = points.runs;
    for (std::size_t i = 1; i < points.parameters.size(); ++i) {
      CurveLocation location = entry.locate(points.parameters[i]);
      if (runs.empty() || runs.back().region != location.region) {
        runs.push_back({location.region, {}, {}, 0, std::nullopt, false, std::nullopt});
      }
      runs.back().locals.push_back(location.local);
    }
    if (ramp) {
      fillProgress(points, entry);
    }
    if (asNumbers(entry)) {
      return runs; // written as numbers: neither table
    }
    // Each run's progress table follows its parameters' table.
    for (Run& run : runs) {
      run.localTable = addTable(run.locals);
      if (ramp) {
        run.progressTable = addTable(run.progress);
      }
    }
    return runs;
  }

  void fillProgress(EntryPoints& points, const CurveTableEntry& entry) {
    std::vector<double> progress = lapProgress(entry, *points.curve, points.parameters);
    std::size_t next = 1;
    for (Run& run : points.runs) {
      run.progress.assign(progress.begin() + static_cast<std::ptrdiff_t>(next),
                          progress.begin() + static_cast<std::ptrdiff_t>(next + run.locals.size()));
      next += run.locals.size();
    }
  }

  // A ramp lap of an entry first met in a level one (not what the lowering
  // writes, but a valid function): the progress tables then, from the
  // points already chosen.
  void addProgressTables(EntryPoints& points, const Instruction& lap, bool ramp) {
    const CurveTableEntry& entry = source_.curves[lap.index];
    if (!ramp || points.runs.empty() || points.runs.front().progressTable) {
      return;
    }
    if (asNumbers(entry)) {
      if (points.runs.front().progress.empty()) {
        fillProgress(points, entry);
      }
      return;
    }
    fillProgress(points, entry);
    for (Run& run : points.runs) {
      run.progressTable = addTable(run.progress);
    }
  }

  std::uint32_t addTable(std::vector<double> values) {
    tableEntries_ += values.size();
    output_.tables.push_back(std::move(values));
    return static_cast<std::uint32_t>(output_.tables.size() - 1);
  }

  void expandLap(const Instruction& lap) {
    bool ramp = isRamp(lap);
    std::vector<Run>& runs = runsOf(lap, ramp);
    for (Run& run : runs) {
      emitRun(lap, run, ramp);
    }
    if (output_.instructions.size() > maximumInstructions || tableEntries_ > maximumTableEntries) {
      throw CurveLapError(CurveLapError::Kind::ProgramTooLarge, lap.span,
                          functionTooLargeMessage());
    }
  }

  // The run's points on the host when its region is marked and needs no
  // parameter; decided once per run.
  const HostPoints* hostPoints(const Instruction& lap, Run& run) {
    if (run.hostDecided) {
      return run.host ? &*run.host : nullptr;
    }
    run.hostDecided = true;
    const std::vector<std::size_t>& marked = source_.curves[lap.index].hostPointRegions;
    if (run.locals.size() < 2 ||
        std::find(marked.begin(), marked.end(), run.region) == marked.end()) {
      return nullptr;
    }
    std::array<std::vector<double>, 3> coordinates;
    auto constantOnly = [&](ValueId value) { return passes::constantValue(source_, value); };
    try {
      LapRegionEvaluator region(source_, lap, run.region, constantOnly);
      for (double local : run.locals) {
        Eigen::Vector3d point = region(local);
        for (int c = 0; c < 3; ++c) {
          coordinates[c].push_back(point[c]);
        }
      }
    } catch (const CurveLapError&) {
      return nullptr; // a parameter moves the points: the program evaluates them
    }
    HostPoints points;
    for (int c = 0; c < 3; ++c) {
      const std::vector<double>& values = coordinates[c];
      if (std::all_of(values.begin(), values.end(),
                      [&](double value) { return value == values.front(); })) {
        points.constant[c] = values.front(); // no table of one number
      } else {
        points.tables[c] = addTable(values);
      }
    }
    run.host = points;
    return &*run.host;
  }

  // The run's points computed here, a feed move to each as numbers (at the
  // compiled values: what the regions read is fixed, bound-controller-steps).
  void emitRunAsNumbers(const Instruction& lap, const Run& run, bool ramp) {
    auto compiled = [&](ValueId value) { return outsideValue(value); };
    LapRegionEvaluator region(source_, lap, run.region, compiled);
    for (std::size_t i = 0; i < run.locals.size(); ++i) {
      Eigen::Vector3d point = region(run.locals[i]);
      Operand progress{ValueId{}, ramp ? run.progress[i] : 1.0};
      emitFeed(lap,
               {Operand{ValueId{}, point.x()}, Operand{ValueId{}, point.y()},
                Operand{ValueId{}, point.z()}},
               ramp, progress);
    }
  }

  void emitRun(const Instruction& lap, Run& run, bool ramp) {
    if (asNumbers(source_.curves[lap.index])) {
      emitRunAsNumbers(lap, run, ramp);
      return;
    }
    ValueId last = constant(static_cast<double>(run.locals.size()) - 1);
    ValueId first = constant(0);
    index_ = beginLapLoop(lap, first, last);
    run_ = &run;
    ramp_ = ramp;
    if (const HostPoints* host = hostPoints(lap, run)) {
      std::array<Operand, 3> point;
      for (int c = 0; c < 3; ++c) {
        point[c] = host->tables[c] ? Operand{load(*host->tables[c]), 0}
                                   : Operand{ValueId{}, host->constant[c]};
      }
      emitFeed(lap, point, ramp_, tableProgress());
    } else {
      replace(lap.result, load(run.localTable));
      rewriteRegion(lap.regions[run.region]);
    }
    endRegions();
  }

  ValueId load(std::uint32_t table) {
    Instruction instruction;
    instruction.opcode = Opcode::TableLoad;
    instruction.index = table;
    return emit(instruction, {index_});
  }

  // The region's curve.point: a feed move there, raised by the lap's height.
  void feedToPoint(const Instruction& lap, const Instruction& point) {
    std::vector<ValueId> operands = mappedOperands(point);
    emitFeed(lap, {operandOf(operands[0]), operandOf(operands[1]), operandOf(operands[2])}, ramp_,
             tableProgress());
  }

  // The ramp's progress at the loop's point: its table.
  Operand tableProgress() {
    return ramp_ ? Operand{load(*run_->progressTable), 0} : Operand{ValueId{}, 1.0};
  }

  void emitFeed(const Instruction& lap, const std::array<Operand, 3>& point, bool ramp,
                const Operand& progress) {
    Operand to = operandOf(mapped(lap.operands[1]));
    Operand z = to;
    if (ramp) {
      Operand from = operandOf(mapped(lap.operands[0]));
      Operand rise = from.isNumber() && to.isNumber() ? Operand{ValueId{}, to.number - from.number}
                                                      : Operand{binary(Opcode::Sub, to, from), 0};
      z = add(from, multiply(rise, progress));
    }
    ValueId x = valueOf(point[0]);
    ValueId y = valueOf(point[1]);
    ValueId height = valueOf(add(z, point[2]));
    emitFeedMove(lap, x, y, height);
  }

  std::map<std::uint32_t, EntryPoints> entries_;
  Run* run_ = nullptr;
  bool ramp_ = false;
  ValueId index_;
  std::size_t tableEntries_ = 0;
};

bool readsTable(const Instruction& instruction) {
  return instruction.opcode == Opcode::TableLoad || instruction.opcode == Opcode::Nurbs ||
         instruction.opcode == Opcode::Spline;
}

// Once no curve.lap is left, the tables of blocks no move reads (the cubic
// spans, written out as numbers) go, and the others are numbered again.
void dropUnreadBlockTables(Function& function) {
  std::vector<bool> keep(function.tables.size(), true);
  for (const CurveTableEntry& entry : function.curves) {
    if (entry.blockTable && *entry.blockTable < keep.size()) {
      keep[*entry.blockTable] = false;
    }
  }
  for (const Instruction& instruction : function.instructions) {
    if (readsTable(instruction) && instruction.index < keep.size()) {
      keep[instruction.index] = true;
    }
  }
  std::vector<std::uint32_t> renumbered(function.tables.size(), 0);
  std::vector<std::vector<double>> kept;
  for (std::size_t table = 0; table < function.tables.size(); ++table) {
    renumbered[table] = static_cast<std::uint32_t>(kept.size());
    if (keep[table]) {
      kept.push_back(std::move(function.tables[table]));
    }
  }
  function.tables = std::move(kept);
  for (Instruction& instruction : function.instructions) {
    if (readsTable(instruction) && instruction.index < renumbered.size()) {
      instruction.index = renumbered[instruction.index];
    }
  }
}

} // namespace

bool expandCurveLaps(Function& function) {
  bool blocks = writeCurveBlocks(function);
  bool fitted = fitLapArcs(function);
  bool stepped = expandControllerLoops(function);
  bool expanded = hasCurveLap(function);
  if (expanded) {
    CurveLapExpander expander(function);
    function = expander.run();
  }
  std::size_t tables = function.tables.size();
  dropUnreadBlockTables(function);
  function.curves.clear();
  return blocks || fitted || stepped || expanded || function.tables.size() != tables;
}

} // namespace cncc::ir
