#include "cncc/ir/verifier.h"

#include "cncc/ir/nurbs_move.h"
#include "cncc/ir/polynomial_move.h"
#include "cncc/ir/printer.h"
#include "cncc/ir/spline_move.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <optional>
#include <set>
#include <span>

namespace cncc::ir {

namespace {

// The operand types an operation expects.
ValueType operandType(Opcode opcode, std::size_t operand) {
  switch (opcode) {
  case Opcode::And:
  case Opcode::Or:
  case Opcode::Not:
  case Opcode::If:
    return ValueType::Bool;
  case Opcode::Select:
    return operand == 0 ? ValueType::Bool : ValueType::F64;
  default:
    return ValueType::F64;
  }
}

std::string_view typeName(ValueType type) {
  switch (type) {
  case ValueType::None:
    return "none";
  case ValueType::F64:
    return "f64";
  case ValueType::Bool:
    return "bool";
  }
  return "?";
}

class Verifier {
public:
  explicit Verifier(const Function& function) : function_(function) {}

  std::vector<std::string> run() {
    if (function_.valueTypes.size() != function_.definitions.size()) {
      problem("value types and definitions disagree in size");
      return problems_;
    }
    for (std::size_t curve = 0; curve < function_.curves.size(); ++curve) {
      verifyCurve(fmt::format("curve @{}", curve), function_.curves[curve]);
    }
    std::vector<bool> visible(function_.valueTypes.size(), false);
    verifyRegion(function_.body, visible);
    if (placed_.size() != function_.instructions.size()) {
      problem(fmt::format("{} instructions are in no region",
                          function_.instructions.size() - placed_.size()));
    }
    return problems_;
  }

private:
  void problem(std::string message) { problems_.push_back(std::move(message)); }

  // `visible` holds the values defined so far on the way to this point.
  // `owner`: the operation whose region it is (the body: none); a loop's
  // body alone may end in loop.next, and a curve.lap's regions end in
  // curve.point, curve.arc or curve.walk, which appear nowhere else.
  void verifyRegion(const Region& region, std::vector<bool>& visible,
                    std::optional<Opcode> owner = std::nullopt) {
    std::vector<ValueId> definedHere;
    bool lapRegion = owner == Opcode::CurveLap;
    if (lapRegion && (region.instructions.empty() ||
                      region.instructions.back() >= function_.instructions.size() ||
                      !endsLapRegion(function_.instructions[region.instructions.back()].opcode))) {
      problem("a curve.lap region does not end with curve.point, curve.arc or curve.walk");
    }
    for (InstructionId id : region.instructions) {
      bool last = id == region.instructions.back();
      if (id < function_.instructions.size() &&
          function_.instructions[id].opcode == Opcode::LoopNext &&
          !(owner == Opcode::Loop && last)) {
        problem(fmt::format("instruction {} (loop.next) is not the last of a loop's body", id));
      }
      if (id < function_.instructions.size() && endsLapRegion(function_.instructions[id].opcode) &&
          !(lapRegion && last)) {
        problem(fmt::format("instruction {} ({}) is not the last of a curve.lap region", id,
                            opcodeInfo(function_.instructions[id].opcode).spelling));
      }
      if (id >= function_.instructions.size() || !placed_.insert(id).second) {
        problem(fmt::format("instruction {} is missing or placed twice", id));
        continue;
      }
      const Instruction& instruction = function_.instructions[id];
      verifyInstruction(id, instruction, visible);
      if (instruction.result.valid() && instruction.result.index < visible.size()) {
        if (!hasRegionVariable(instruction.opcode)) {
          visible[instruction.result.index] = true;
          definedHere.push_back(instruction.result);
        }
      }
    }
    for (ValueId value : definedHere) {
      visible[value.index] = false; // out of scope after the region
    }
  }

  void verifyInstruction(InstructionId id, const Instruction& instruction,
                         std::vector<bool>& visible) {
    const OpcodeInfo& info = opcodeInfo(instruction.opcode);
    std::string where = fmt::format("instruction {} ({})", id, info.spelling);
    if (info.operandCount >= 0 &&
        instruction.operands.size() != static_cast<std::size_t>(info.operandCount)) {
      problem(fmt::format("{} has {} operands, needs {}", where, instruction.operands.size(),
                          info.operandCount));
    }
    for (std::size_t i = 0; i < instruction.operands.size(); ++i) {
      verifyOperand(where, instruction, i, visible);
    }
    verifyResult(where, id, instruction);
    verifyImmediates(where, instruction);
    verifyRegions(where, instruction, visible);
  }

  void verifyOperand(const std::string& where, const Instruction& instruction, std::size_t i,
                     const std::vector<bool>& visible) {
    ValueId operand = instruction.operands[i];
    if (!operand.valid() || operand.index >= visible.size()) {
      problem(fmt::format("{} uses an undefined value", where));
      return;
    }
    if (!visible[operand.index]) {
      problem(fmt::format("{} uses %{} where it is not visible", where, operand.index));
    }
    ValueType expected = operandType(instruction.opcode, i);
    ValueType actual = function_.valueTypes[operand.index];
    if (actual != expected) {
      problem(fmt::format("{} operand {} is {}, needs {}", where, i, typeName(actual),
                          typeName(expected)));
    }
  }

  void verifyResult(const std::string& where, InstructionId id, const Instruction& instruction) {
    ValueType expected = opcodeInfo(instruction.opcode).result;
    if (expected == ValueType::None) {
      if (instruction.result.valid()) {
        problem(fmt::format("{} has a result but the operation has none", where));
      }
      return;
    }
    if (!instruction.result.valid() || instruction.result.index >= function_.valueTypes.size() ||
        function_.definitions[instruction.result.index] != id ||
        function_.valueTypes[instruction.result.index] != expected) {
      problem(fmt::format("{} has a missing or inconsistent result", where));
    }
  }

  void verifyImmediates(const std::string& where, const Instruction& instruction) {
    if (instruction.opcode == Opcode::Param && instruction.index >= function_.parameters.size()) {
      problem(fmt::format("{} names parameter {}, which does not exist", where, instruction.index));
    }
    if (instruction.opcode == Opcode::Arc &&
        instruction.index > static_cast<std::uint32_t>(ArcTurn::CounterClockwise)) {
      problem(fmt::format("{} turns neither clockwise nor counter-clockwise", where));
    }
    if (instruction.opcode == Opcode::Nurbs && instruction.operands.size() >= 2) {
      checkNurbs(instruction.index, instruction.operands.size() - 2, where);
    }
    if (instruction.opcode == Opcode::Spline) {
      checkSpline(instruction.index, where);
    }
    if (instruction.opcode == Opcode::CurveLap) {
      checkCurveLap(instruction, where);
    }
    if (instruction.opcode == Opcode::TableLoad && instruction.index >= function_.tables.size()) {
      problem(fmt::format("{} names table {}, which does not exist", where, instruction.index));
    }
    // A function with a cut table (every lowered one) names its cuts; one
    // built by hand without may begin any.
    if (instruction.opcode == Opcode::CutBegin && !function_.cuts.empty() &&
        instruction.index >= function_.cuts.size()) {
      problem(fmt::format("{} begins cut {}, but the cut table has {}", where, instruction.index,
                          function_.cuts.size()));
    }
    checkSetting(instruction, where);
  }

  // Its curve in the table, and three operands and a range and count for
  // each region whose steps the program computes, or a weight for each
  // control point of its NURBS block; blocks in a table that holds them.
  void checkCurveLap(const Instruction& lap, const std::string& where) {
    if (lap.index >= function_.curves.size()) {
      problem(fmt::format("{} names curve {}, which is not in the curve table", where, lap.index));
      return;
    }
    const CurveTableEntry& entry = function_.curves[lap.index];
    if (entry.sampling == CurveSampling::NurbsBlocks && !entry.blockTable &&
        lap.operands.size() != 3) {
      problem(fmt::format("{} has weights for a NURBS block that write-curve-blocks fits", where));
    }
    if (entry.isBlocks() && !entry.blockTable) {
      return; // fitted by write-curve-blocks, or the entry's own problem
    }
    if (entry.sampling == CurveSampling::NurbsBlocks) {
      checkNurbs(*entry.blockTable,
                 lap.operands.size() - std::min<std::size_t>(3, lap.operands.size()), where);
      return;
    }
    if (entry.sampling == CurveSampling::SplineBlocks) {
      checkSpline(*entry.blockTable, where);
    }
    if (entry.sampling == CurveSampling::PolynomialBlocks) {
      checkPolynomialSpans(*entry.blockTable, where);
    }
    for (std::size_t region = 0; region < lap.regions.size(); ++region) {
      const std::vector<InstructionId>& body = lap.regions[region].instructions;
      if (body.empty() || body.back() >= function_.instructions.size()) {
        continue; // the region's own problem
      }
      Opcode end = function_.instructions[body.back()].opcode;
      Opcode wanted = entry.arcRegion(region) != nullptr ? Opcode::CurveArc
                      : entry.isWalkRegion(region)       ? Opcode::CurveWalk
                                                         : Opcode::CurvePoint;
      if (endsLapRegion(end) && end != wanted) {
        problem(fmt::format("{}: its region {} ends in {} but its curve wants {}", where, region,
                            opcodeInfo(end).spelling, opcodeInfo(wanted).spelling));
      }
    }
    std::size_t wanted = entry.lapOperandCount();
    if (lap.operands.size() != wanted) {
      problem(fmt::format("{} has {} operands, its curve wants {}", where, lap.operands.size(),
                          wanted));
    }
  }

  void checkSetting(const Instruction& instruction, const std::string& where) {
    if (instruction.opcode == Opcode::Origin &&
        !isWorkOffsetCode(instruction.number, instruction.index)) {
      problem(
          fmt::format("{} is not a work offset (54 .. 59, or 54.1 with a number from 1)", where));
    }
    if (instruction.opcode == Opcode::Coolant &&
        instruction.index > static_cast<std::uint32_t>(CoolantMode::Through)) {
      problem(fmt::format("{} names no coolant mode", where));
    }
    if (instruction.opcode == Opcode::Compensation &&
        (!std::isfinite(instruction.number) ||
         (instruction.number == 0) != (instruction.index == 0))) {
      problem(fmt::format("{} needs a radius register and a finite offset, or neither", where));
    }
    if (instruction.opcode == Opcode::Contouring && !(instruction.number >= 0)) {
      problem(fmt::format("{} has a negative tolerance", where));
    }
  }

  static bool isWorkOffsetCode(double code, std::uint32_t extended) {
    if (code == 54.1) {
      return extended >= 1;
    }
    return extended == 0 && code >= 54 && code <= 59 && code == std::floor(code);
  }

  // Its table holds the block data of as many control points as it has
  // weights (nurbs_move.h).
  void checkNurbs(std::uint32_t table, std::size_t weights, const std::string& where) {
    if (table >= function_.tables.size()) {
      problem(fmt::format("{} names table {}, which does not exist", where, table));
      return;
    }
    std::string why;
    if (!readNurbsMoveTable(function_.tables[table], weights, &why)) {
      problem(fmt::format("{} with {} weights: {}", where, weights, why));
    }
  }

  // Its table holds spline blocks (spline_move.h).
  void checkSpline(std::uint32_t table, const std::string& where) {
    checkBlocksTable(table, where, [](std::span<const double> data, std::string* why) {
      return readSplineMoveTable(data, why).has_value();
    });
  }

  // Its table holds cubic spans (polynomial_move.h).
  void checkPolynomialSpans(std::uint32_t table, const std::string& where) {
    checkBlocksTable(table, where, [](std::span<const double> data, std::string* why) {
      return readPolynomialMoveTable(data, why).has_value();
    });
  }

  // The table exists and `read` reads it (else says why not).
  void checkBlocksTable(std::uint32_t table, const std::string& where,
                        bool (*read)(std::span<const double>, std::string*)) {
    std::string why;
    if (table >= function_.tables.size()) {
      problem(fmt::format("{} names table {}, which does not exist", where, table));
    } else if (!read(function_.tables[table], &why)) {
      problem(fmt::format("{}: {}", where, why));
    }
  }

  void verifyRegions(const std::string& where, const Instruction& instruction,
                     std::vector<bool>& visible) {
    std::optional<std::size_t> expected = regionsNeeded(instruction);
    if (expected && instruction.regions.size() != *expected) {
      problem(
          fmt::format("{} has {} regions, needs {}", where, instruction.regions.size(), *expected));
      return;
    }
    bool hasVariable = hasRegionVariable(instruction.opcode) && instruction.result.valid() &&
                       instruction.result.index < visible.size();
    if (hasVariable) {
      visible[instruction.result.index] = true;
    }
    for (const Region& region : instruction.regions) {
      verifyRegion(region, visible, instruction.opcode);
    }
    if (hasVariable) {
      visible[instruction.result.index] = false;
    }
  }

  // A loop's variable and a curve.lap's parameter: visible in its regions only.
  static bool hasRegionVariable(Opcode opcode) {
    return opcode == Opcode::Loop || opcode == Opcode::CurveLap;
  }

  // nullopt: a curve.lap whose curve is missing (reported already).
  std::optional<std::size_t> regionsNeeded(const Instruction& instruction) const {
    switch (instruction.opcode) {
    case Opcode::Loop:
      return 1;
    case Opcode::If:
      return 2;
    case Opcode::CurveLap:
      if (instruction.index >= function_.curves.size()) {
        return std::nullopt;
      }
      return function_.curves[instruction.index].regionCount();
    default:
      return 0;
    }
  }

  // The entry's layout is what locate() and the lap's points rely on.
  void verifyCurve(const std::string& where, const CurveTableEntry& entry) {
    if (entry.pieces.empty()) {
      problem(fmt::format("{} has no pieces", where));
    }
    if (!std::isfinite(entry.from) || !std::isfinite(entry.to) || !(entry.from <= entry.to)) {
      problem(
          fmt::format("{} runs over {} .. {}, not a finite range", where, entry.from, entry.to));
    }
    // Counts the cut gave, or blocks through the points samples= chose.
    bool countsGiven =
        (entry.sampling == CurveSampling::Steps || entry.isBlocks()) && entry.amount == 0;
    if (!std::isfinite(entry.amount) || !(entry.amount > 0 || countsGiven)) {
      problem(fmt::format("{} chooses its points by {}, which is not a positive number", where,
                          entry.amount));
    }
    for (std::size_t piece = 0; piece < entry.pieces.size(); ++piece) {
      verifyPiece(fmt::format("{} piece {}", where, piece), entry.pieces[piece]);
      if (piece > 0 && !(entry.pieces[piece - 1].start <= entry.pieces[piece].start)) {
        problem(fmt::format("{} piece {} starts before the piece ahead of it", where, piece));
      }
    }
    if (!(entry.progressFrom >= 0 && entry.progressShare >= 0 &&
          entry.progressFrom + entry.progressShare <= 1 + 1e-12)) {
      problem(fmt::format("{} descends from {} by a share of {}, not within the longer lap's",
                          where, entry.progressFrom, entry.progressShare));
    }
    if (entry.chosenParameters) {
      verifyChosenParameters(where, entry, *entry.chosenParameters);
    }
    verifyArcs(where, entry);
    verifyArcsAsked(where, entry);
    verifySteps(where, entry);
    bool level = entry.sampling == CurveSampling::Arcs || entry.isBlocks();
    bool notPoints = level || entry.sampling == CurveSampling::Steps;
    // Spline blocks the legalisation fits go through (or after) chosen points.
    bool chosenAllowed = !notPoints || entry.splineFit;
    // A lap in steps may be a share of a longer descent (its regions'
    // heights are descentShares'); arcs and blocks are level.
    if ((entry.chosenParameters && !chosenAllowed) ||
        (level && (entry.progressFrom != 0 || entry.progressShare != 1))) {
      problem(fmt::format("{} is cut by {} but has chosen points or a share of a descent", where,
                          curveSamplingName(entry.sampling)));
    }
    verifyBlockTable(where, entry);
    for (const CurveTableEntry::ParameterWeight& weight : entry.parameterWeights) {
      if (weight.parameter >= function_.parameters.size()) {
        problem(fmt::format("{} has the weight of point {} the parameter {}, but {} parameters",
                            where, weight.point, weight.parameter, function_.parameters.size()));
      }
    }
    std::size_t regions = entry.regionCount();
    for (std::size_t region : entry.hostPointRegions) {
      if (region >= regions) {
        problem(fmt::format("{} has its points of region {} on the host, but {} regions", where,
                            region, regions));
      }
    }
  }

  // Blocks name their table, or are fitted by the legalisation (SPL spans
  // and a NURBS block without more; spline blocks by their fit's settings,
  // through the chosen points where samples= chose them or a ramp's last
  // chord leads in).
  void verifyBlockTable(const std::string& where, const CurveTableEntry& entry) {
    bool spline = entry.sampling == CurveSampling::SplineBlocks;
    if (entry.blockTable && !entry.isBlocks()) {
      problem(fmt::format("{} is cut by {} and names a table of blocks", where,
                          curveSamplingName(entry.sampling)));
    }
    if (entry.splineFit && (!spline || entry.blockTable)) {
      problem(fmt::format("{} is cut by {}{} and says how spline blocks are fitted", where,
                          curveSamplingName(entry.sampling),
                          entry.blockTable ? " from a table" : ""));
    }
    if (spline && !entry.blockTable && !entry.splineFit) {
      problem(fmt::format("{} is cut by spline blocks and names neither a table of them nor how "
                          "they are fitted",
                          where));
    }
    bool needsPoints = entry.splineFit && (entry.amount == 0 || entry.splineFit->afterRamp);
    if (needsPoints && !entry.chosenParameters) {
      problem(fmt::format("{} fits spline blocks {} but has no chosen points", where,
                          entry.amount == 0 ? "through the points samples= chose"
                                            : "after a ramp's last chord"));
    }
  }

  // A grid belongs to arcs and to the blocks write-curve-blocks fits.
  void verifyArcs(const std::string& where, const CurveTableEntry& entry) {
    bool gridded = entry.sampling == CurveSampling::Arcs || entry.isBlocks();
    if (!std::isfinite(entry.grid) || entry.grid < 0 || (!gridded && entry.grid != 0)) {
      problem(fmt::format("{} has the grid {}, which is not a grid of arcs or fitted blocks of "
                          "zero or more",
                          where, entry.grid));
    }
  }

  // Arcs asked in place of chords within a tolerance or steps whose counts
  // are numbers (a fit at the values compiled with).
  void verifyArcsAsked(const std::string& where, const CurveTableEntry& entry) {
    if (!entry.arcsAsked) {
      return;
    }
    const ArcsAsked& asked = *entry.arcsAsked;
    bool chords =
        entry.sampling == CurveSampling::ChordTolerance || entry.sampling == CurveSampling::Steps;
    bool computed = std::find(entry.regionSteps.begin(), entry.regionSteps.end(), 0) !=
                        entry.regionSteps.end() ||
                    !entry.walkRegions.empty() || entry.offsetGrowth.has_value();
    if (!chords || computed) {
      problem(fmt::format("{} asks for arcs but is cut by {}{}", where,
                          curveSamplingName(entry.sampling),
                          computed ? " the program computes" : ""));
    }
    if (!std::isfinite(asked.tolerance) || !(asked.tolerance > 0) || !std::isfinite(asked.grid) ||
        asked.grid < 0 || !(asked.largestRadius > 0)) {
      problem(fmt::format("{} asks for arcs within {} on the grid {} up to the radius {}, not a "
                          "positive tolerance, a grid of zero or more and a positive radius",
                          where, asked.tolerance, asked.grid, asked.largestRadius));
    }
  }

  // Regions of the entry, each later than the one before.
  void verifyRegionList(const std::string& where, const CurveTableEntry& entry,
                        const std::vector<std::size_t>& regions, std::string_view what) {
    std::size_t count = entry.regionCount();
    for (std::size_t k = 0; k < regions.size(); ++k) {
      if (regions[k] >= count || (k > 0 && regions[k] <= regions[k - 1])) {
        problem(fmt::format("{} has {} region {} that is not a later region of it", where, what,
                            regions[k]));
      }
    }
  }

  // Steps: a count for each region (0: computed by the program; ?: chosen
  // by the legalisation).
  void verifySteps(const std::string& where, const CurveTableEntry& entry) {
    if (entry.sampling != CurveSampling::Steps) {
      if (!entry.regionSteps.empty() || !entry.arcRegions.empty() || !entry.walkRegions.empty() ||
          entry.offsetGrowth) {
        problem(fmt::format("{} has step counts, arcs, walks or an offset's growth but is not "
                            "cut in steps",
                            where));
      }
      return;
    }
    if (entry.offsetGrowth) {
      const OffsetStepGrowth& growth = *entry.offsetGrowth;
      if (std::fabs(growth.side) != 1 || !(growth.compiledRadius > 0) ||
          !(growth.largestRadius >= growth.compiledRadius)) {
        problem(fmt::format("{} grows its counts with the radius on side {} from radius {} below "
                            "{}, not a side of 1 or -1 and a positive radius below the largest",
                            where, growth.side, growth.compiledRadius, growth.largestRadius));
      }
    }
    std::vector<std::size_t> arcs;
    for (const ArcRegion& arc : entry.arcRegions) {
      arcs.push_back(arc.region);
    }
    verifyRegionList(where, entry, arcs, "an arc");
    verifyRegionList(where, entry, entry.walkRegions, "a walked");
    for (std::size_t region : entry.walkRegions) {
      if (entry.arcRegion(region) != nullptr) {
        problem(fmt::format("{} has region {} both an arc and walked", where, region));
      }
    }
    bool counted = entry.regionSteps.size() == entry.regionCount();
    for (int steps : entry.regionSteps) {
      counted = counted && steps >= stepsChosenByLegalisation && steps <= maximumStepsPerRegion;
    }
    if (!counted) {
      problem(fmt::format("{} has {} step counts for {} regions, not each ? or 0 .. {}", where,
                          entry.regionSteps.size(), entry.regionCount(), maximumStepsPerRegion));
    }
    // The legalisation chooses uniform steps of a piece's own parameter
    // within the entry's amount: not an arc's blocks, a walk, or a count
    // the cut gave.
    for (std::size_t region = 0; region < entry.regionSteps.size(); ++region) {
      bool chosen = entry.regionSteps[region] == stepsChosenByLegalisation;
      bool choosable =
          entry.arcRegion(region) == nullptr && !entry.isWalkRegion(region) && entry.amount > 0;
      if (chosen && !choosable) {
        problem(fmt::format("{} leaves the count of region {} to the legalisation, which chooses "
                            "uniform steps within a tolerance only",
                            where, region));
      }
    }
  }

  // What lapParameters gives: at least two points along the curve.
  void verifyChosenParameters(const std::string& where, const CurveTableEntry& entry,
                              const std::vector<double>& parameters) {
    bool inOrder = parameters.size() >= 2;
    for (std::size_t k = 0; inOrder && k < parameters.size(); ++k) {
      inOrder = parameters[k] >= entry.from && parameters[k] <= entry.to &&
                (k == 0 || parameters[k - 1] <= parameters[k]);
    }
    if (!inOrder) {
      problem(fmt::format("{} has {} chosen parameters, not two or more in order within {} .. {}",
                          where, parameters.size(), entry.from, entry.to));
    }
  }

  void verifyPiece(const std::string& where, const CurvePieceLayout& piece) {
    if (!std::isfinite(piece.start) || !std::isfinite(piece.from) || !std::isfinite(piece.to) ||
        !(piece.from <= piece.to)) {
      problem(fmt::format("{} at {} runs over {} .. {}, not a finite range", where, piece.start,
                          piece.from, piece.to));
      return;
    }
    double reached = piece.from;
    for (auto [spanFrom, spanTo] : piece.spans) {
      if (!(spanFrom >= reached && spanFrom < spanTo && spanTo <= piece.to)) {
        problem(fmt::format("{} has knot span {} .. {}, not increasing within {} .. {}", where,
                            spanFrom, spanTo, piece.from, piece.to));
        return;
      }
      reached = spanTo;
    }
  }

  const Function& function_;
  std::vector<std::string> problems_;
  std::set<InstructionId> placed_;
};

} // namespace

std::vector<std::string> verifyFunction(const Function& function) {
  return Verifier(function).run();
}

} // namespace cncc::ir
