// lapCurve: a curve.lap's whole curve, from its table entry's geometry or,
// without one (a function read from text), from its regions interpreted.
// Each region is compiled once into steps whose operands are its own
// results, the region's parameter or numbers read from outside the lap, so
// the curve owns everything it evaluates and may outlive the function.
#include "cncc/geom/composite_curve.h"
#include "cncc/geom/function_curve.h"
#include "cncc/geom/geometry_error.h"
#include "cncc/ir/curve_lap.h"

#include "passes/evaluate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <fmt/format.h>
#include <map>

namespace cncc::ir {

namespace detail {

// Where a step's operand comes from.
struct StepOperand {
  enum class Kind { Result, Parameter, Number };
  Kind kind = Kind::Number;
  std::size_t step = 0; // Result: the step that computes it
  double number = 0;    // Number: its value
};

struct Step {
  Instruction instruction; // opcode and immediates; operands are `operands`
  std::vector<StepOperand> operands = {};
};

// One region as steps, and the curve.point's operands (and a curve.arc's
// offset to the centre).
struct RegionProgram {
  std::vector<Step> steps;
  std::array<StepOperand, 3> point;
  std::array<StepOperand, 2> toCentre;
  // The tables its table.loads read, at their indices (evaluate() reads them).
  std::shared_ptr<const Function> tables;
  frontend::SourceSpan curveSpan;
};

} // namespace detail

namespace {

using detail::RegionProgram;
using detail::Step;
using detail::StepOperand;

[[noreturn]] void degenerate(const CurveTableEntry& entry, const std::string& message) {
  throw CurveLapError(CurveLapError::Kind::DegenerateCurve, entry.curveSpan, message);
}

class RegionCompiler {
public:
  RegionCompiler(const Function& function, const Instruction& lap, const CurveTableEntry& entry,
                 const OutsideValue& outside, std::shared_ptr<const Function> tables)
      : function_(function), lap_(lap), entry_(entry), outside_(outside),
        tables_(std::move(tables)) {}

  std::shared_ptr<const RegionProgram> compile(const Region& region) {
    auto program = std::make_shared<RegionProgram>();
    program->tables = tables_;
    program->curveSpan = entry_.curveSpan;
    std::map<std::uint32_t, StepOperand> known; // values of the region so far
    bool pointRead = false;
    for (InstructionId id : region.instructions) {
      const Instruction& instruction = function_.instructions[id];
      if (pointRead) {
        degenerate(entry_, "a curve.lap region goes on after its curve.point");
      }
      switch (instruction.opcode) {
      case Opcode::CurvePoint:
      case Opcode::CurveArc:  // its point; the centre follows from the points
      case Opcode::CurveWalk: // its point; the step is the walk's
        for (std::size_t k = 0; k < 3; ++k) {
          program->point[k] = operand(instruction.operands[k], known);
        }
        for (std::size_t k = 0; k < 2 && instruction.opcode == Opcode::CurveArc; ++k) {
          program->toCentre[k] = operand(instruction.operands[3 + k], known);
        }
        pointRead = true;
        continue;
      case Opcode::Param:
        known[instruction.result.index] = {StepOperand::Kind::Number, 0,
                                           outsideValue(instruction.result)};
        continue;
      default:
        break;
      }
      if (!isPure(instruction.opcode)) {
        degenerate(entry_, fmt::format("a curve.lap region holds '{}', which does not compute "
                                       "a point of the curve",
                                       opcodeInfo(instruction.opcode).spelling));
      }
      Step step;
      step.instruction.opcode = instruction.opcode;
      step.instruction.number = instruction.number;
      step.instruction.index = instruction.index;
      std::vector<double> numbers;
      for (ValueId value : instruction.operands) {
        step.operands.push_back(operand(value, known));
        if (step.operands.back().kind == StepOperand::Kind::Number) {
          numbers.push_back(step.operands.back().number);
        }
      }
      // Arithmetic on numbers only is a number (the same evaluation, once).
      if (numbers.size() == step.operands.size()) {
        std::optional<double> folded = passes::evaluate(*tables_, step.instruction, numbers);
        if (folded) {
          known[instruction.result.index] = {StepOperand::Kind::Number, 0, *folded};
          continue;
        }
      }
      known[instruction.result.index] = {StepOperand::Kind::Result, program->steps.size(), 0};
      program->steps.push_back(std::move(step));
    }
    if (!pointRead) {
      degenerate(entry_, "a curve.lap region does not end with curve.point");
    }
    return program;
  }

private:
  StepOperand operand(ValueId value, const std::map<std::uint32_t, StepOperand>& known) const {
    auto found = known.find(value.index);
    if (found != known.end()) {
      return found->second;
    }
    if (value == lap_.result) {
      return {StepOperand::Kind::Parameter, 0, 0};
    }
    return {StepOperand::Kind::Number, 0, outsideValue(value)};
  }

  // A constant's value is its own; anything else is asked of `outside`.
  double outsideValue(ValueId value) const {
    const Instruction& definition = function_.definition(value);
    if (definition.opcode == Opcode::Const || definition.opcode == Opcode::ConstBool) {
      return definition.number;
    }
    std::optional<double> number = outside_ ? outside_(value) : std::nullopt;
    if (!number) {
      degenerate(entry_,
                 fmt::format("the curve's points depend on a value not known here (the result "
                             "of '{}', outside the points' arithmetic)",
                             opcodeInfo(definition.opcode).spelling));
    }
    return *number;
  }

  const Function& function_;
  const Instruction& lap_;
  const CurveTableEntry& entry_;
  const OutsideValue& outside_;
  std::shared_ptr<const Function> tables_;
};

double operandValue(const StepOperand& operand, const std::vector<double>& results,
                    double parameter) {
  switch (operand.kind) {
  case StepOperand::Kind::Result:
    return results[operand.step];
  case StepOperand::Kind::Parameter:
    return parameter;
  case StepOperand::Kind::Number:
    break;
  }
  return operand.number;
}

// + - * / and negation, most of a region's steps, without the general
// evaluation's operand list (the same arithmetic as binaryResult's).
std::optional<double> plainArithmetic(const Step& step, const std::vector<double>& results,
                                      double parameter) {
  auto operand = [&](std::size_t k) { return operandValue(step.operands[k], results, parameter); };
  std::size_t count = step.operands.size();
  switch (step.instruction.opcode) {
  case Opcode::Neg:
    return count == 1 ? std::optional<double>(-operand(0)) : std::nullopt;
  case Opcode::Add:
    return count == 2 ? std::optional<double>(operand(0) + operand(1)) : std::nullopt;
  case Opcode::Sub:
    return count == 2 ? std::optional<double>(operand(0) - operand(1)) : std::nullopt;
  case Opcode::Mul:
    return count == 2 ? std::optional<double>(operand(0) * operand(1)) : std::nullopt;
  case Opcode::Div:
    return count == 2 ? std::optional<double>(operand(0) / operand(1)) : std::nullopt;
  default:
    return std::nullopt;
  }
}

// The region's steps at its parameter, computed as the interpreter does;
// their results (kept between calls: a search asks millions of points).
const std::vector<double>& runRegionSteps(const RegionProgram& program, double parameter) {
  thread_local std::vector<double> results;
  thread_local std::vector<double> operands;
  results.assign(program.steps.size(), 0.0);
  for (std::size_t k = 0; k < program.steps.size(); ++k) {
    const Step& step = program.steps[k];
    if (std::optional<double> plain = plainArithmetic(step, results, parameter)) {
      results[k] = *plain;
      continue;
    }
    operands.clear();
    for (const StepOperand& operand : step.operands) {
      operands.push_back(operandValue(operand, results, parameter));
    }
    std::optional<double> result = passes::evaluate(*program.tables, step.instruction, operands);
    if (!result && step.instruction.opcode == Opcode::TableLoad) {
      throw CurveLapError(CurveLapError::Kind::NonFiniteValue, program.curveSpan,
                          fmt::format("the curve's points read table @{} at index {}, outside "
                                      "its entries",
                                      step.instruction.index, operands.empty() ? 0 : operands[0]));
    }
    results[k] = result.value_or(NAN); // the interpreter's value for no fixed result
  }
  return results;
}

// The region's point at its parameter.
Eigen::Vector3d evaluateRegion(const RegionProgram& program, double parameter) {
  const std::vector<double>& results = runRegionSteps(program, parameter);
  return {operandValue(program.point[0], results, parameter),
          operandValue(program.point[1], results, parameter),
          operandValue(program.point[2], results, parameter)};
}

// A NURBS piece in its own parameter: each knot span's region at the span's
// u in [0, 1]; the span boundaries are its breakpoints.
class SpannedPieceCurve : public geom::FunctionCurve {
public:
  SpannedPieceCurve(const CurvePieceLayout& piece,
                    std::vector<std::shared_ptr<const RegionProgram>> spans)
      : FunctionCurve({piece.from, piece.to},
                      [layout = piece, programs = spans](double s) {
                        std::size_t span = 0;
                        while (span + 1 < layout.spans.size() &&
                               layout.spans[span + 1].first <= s) {
                          ++span;
                        }
                        auto [spanFrom, spanTo] = layout.spans[span];
                        double u = std::clamp((s - spanFrom) / (spanTo - spanFrom), 0.0, 1.0);
                        return evaluateRegion(*programs[span], u);
                      }),
        layout_(piece) {}

  std::vector<double> breakpoints() const override {
    std::vector<double> result{layout_.from};
    for (auto [spanFrom, spanTo] : layout_.spans) {
      for (double knot : {spanFrom, spanTo}) {
        if (knot > result.back() && knot < layout_.to) {
          result.push_back(knot);
        }
      }
    }
    result.push_back(layout_.to);
    return result;
  }

private:
  CurvePieceLayout layout_;
};

// The tables the regions read, at their indices; the others left empty.
std::shared_ptr<const Function> tablesRead(const Function& function, const Instruction& lap) {
  auto tables = std::make_shared<Function>();
  tables->tables.resize(function.tables.size());
  for (const Region& region : lap.regions) {
    for (InstructionId id : region.instructions) {
      const Instruction& instruction = function.instructions[id];
      if (instruction.opcode == Opcode::TableLoad && instruction.index < function.tables.size()) {
        tables->tables[instruction.index] = function.tables[instruction.index];
      }
    }
  }
  return tables;
}

std::shared_ptr<const geom::Curve> pieceCurve(const CurveTableEntry& entry, std::size_t piece,
                                              RegionCompiler& compiler, const Instruction& lap) {
  const CurvePieceLayout& layout = entry.pieces[piece];
  if (!(layout.from < layout.to)) {
    degenerate(entry, fmt::format("piece {} of the curve has no length of parameter ({} .. {})",
                                  piece, layout.from, layout.to));
  }
  std::vector<std::shared_ptr<const RegionProgram>> programs;
  for (std::size_t span = 0; span < layout.regionCount(); ++span) {
    programs.push_back(compiler.compile(lap.regions[entry.regionOf(piece, span)]));
  }
  if (layout.spans.empty()) {
    return std::make_shared<geom::FunctionCurve>(
        geom::ParameterRange{layout.from, layout.to},
        [program = programs.front()](double s) { return evaluateRegion(*program, s); });
  }
  return std::make_shared<SpannedPieceCurve>(layout, std::move(programs));
}

bool nearlyEqual(double a, double b) {
  return std::abs(a - b) <= 1e-9 * std::max(1.0, std::max(std::abs(a), std::abs(b)));
}

// A composite curve's parameter starts at 0 and gives each piece its own
// length: the entry's layout must say the same for locate() to agree.
void checkComposedLayout(const CurveTableEntry& entry) {
  double start = 0;
  for (std::size_t piece = 0; piece < entry.pieces.size(); ++piece) {
    const CurvePieceLayout& layout = entry.pieces[piece];
    if (!nearlyEqual(layout.start, start)) {
      degenerate(entry, fmt::format("piece {} of the curve starts at {} in the table but at {} "
                                    "after the pieces before it",
                                    piece, layout.start, start));
    }
    start += layout.to - layout.from;
  }
  if (!nearlyEqual(entry.from, 0) || !nearlyEqual(entry.to, start)) {
    degenerate(entry, fmt::format("the curve runs over {} .. {} in the table but its pieces "
                                  "over 0 .. {}",
                                  entry.from, entry.to, start));
  }
}

} // namespace

LapRegionEvaluator::LapRegionEvaluator(const Function& function, const Instruction& lap,
                                       std::size_t region, const OutsideValue& outside) {
  RegionCompiler compiler(function, lap, function.curves[lap.index], outside,
                          tablesRead(function, lap));
  program_ = compiler.compile(lap.regions[region]);
}

Eigen::Vector3d LapRegionEvaluator::operator()(double t) const {
  return evaluateRegion(*program_, t);
}

Eigen::Vector2d LapRegionEvaluator::toCentre(double t) const {
  const std::vector<double>& results = runRegionSteps(*program_, t);
  return {operandValue(program_->toCentre[0], results, t),
          operandValue(program_->toCentre[1], results, t)};
}

std::shared_ptr<const geom::Curve> lapCurve(const Function& function, const Instruction& lap,
                                            const OutsideValue& outside) {
  if (lap.opcode != Opcode::CurveLap || lap.index >= function.curves.size()) {
    throw CurveLapError(CurveLapError::Kind::DegenerateCurve, lap.span,
                        "a curve.lap names no entry of the curve table");
  }
  return lapCurve(function, lap, function.curves[lap.index], outside);
}

std::shared_ptr<const geom::Curve> lapCurve(const Function& function, const Instruction& lap,
                                            const CurveTableEntry& entry,
                                            const OutsideValue& outside) {
  if (entry.geometry) {
    return entry.geometry;
  }
  if (entry.pieces.empty() || lap.regions.size() != entry.regionCount()) {
    degenerate(entry, fmt::format("the curve.lap has {} regions, its curve {}", lap.regions.size(),
                                  entry.regionCount()));
  }
  RegionCompiler compiler(function, lap, entry, outside, tablesRead(function, lap));
  std::vector<std::shared_ptr<const geom::Curve>> pieces;
  for (std::size_t piece = 0; piece < entry.pieces.size(); ++piece) {
    pieces.push_back(pieceCurve(entry, piece, compiler, lap));
  }
  if (pieces.size() == 1) {
    const CurvePieceLayout& piece = entry.pieces.front();
    if (!nearlyEqual(entry.from, piece.from) || !nearlyEqual(entry.to, piece.to)) {
      degenerate(entry, fmt::format("the curve runs over {} .. {} in the table but its piece "
                                    "over {} .. {}",
                                    entry.from, entry.to, piece.from, piece.to));
    }
    return pieces.front(); // its own parameter is the whole curve's
  }
  checkComposedLayout(entry);
  try {
    return std::make_shared<geom::CompositeCurve>(std::move(pieces), pathJoinTolerance);
  } catch (const geom::GeometryError& error) {
    degenerate(entry, fmt::format("the curve's pieces do not join: {}", error.what()));
  }
}

} // namespace cncc::ir
