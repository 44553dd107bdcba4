#include "cncc/lowering/literal_rounding.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <optional>

namespace cncc::ir::lowering {

namespace {

constexpr InstructionId noSource = std::numeric_limits<InstructionId>::max();
constexpr double degreesPerRadian = 180 / std::numbers::pi;

// An error and the instruction that rounds most of it.
struct Share {
  double size = 0;
  InstructionId source = noSource;
  double largestPart = 0;

  static Share of(double size, InstructionId source) { return {size, source, size}; }
  Share scaled(double factor) const { return {size * factor, source, largestPart * factor}; }
  Share plus(const Share& other) const {
    const Share& larger = other.largestPart > largestPart ? other : *this;
    return {size + other.size, larger.source, larger.largestPart};
  }
  Share larger(const Share& other) const { return other.size > size ? other : *this; }
};

// What is known of a value: how large it can be, the error the rounding of
// the numbers it is computed from gives it, and the part of that error
// which has gone through a periodic function.
struct Estimate {
  double magnitude = 0;
  Share rounding;
  Share throughAngle;
  // Computed from a curve's parameter (the variable of a loop along the
  // curve, a curve.lap's): the rounding of its step and of the factors it
  // is multiplied by moves every coordinate's point along the curve alike.
  bool alongCurve = false;
};

class RoundingPropagation {
public:
  RoundingPropagation(const Function& function, int digits)
      : function_(function), digits_(digits), estimates_(function.valueTypes.size()) {}

  std::vector<LiteralRoundingMove> run() {
    walk(function_.body);
    std::vector<LiteralRoundingMove> moves;
    for (const auto& [cut, move] : largest_) {
      moves.push_back(move);
    }
    return moves;
  }

private:
  void walk(const Region& region) {
    for (InstructionId id : region.instructions) {
      visit(id);
    }
  }

  const Estimate& of(ValueId value) const { return estimates_[value.index]; }

  Estimate number(double value, InstructionId id) const {
    return {
        std::abs(value), Share::of(std::abs(value - controllerReading(value, digits_)), id), {}};
  }

  void visit(InstructionId id) {
    const Instruction& instruction = function_.instructions[id];
    if (instruction.result.valid()) {
      estimates_[instruction.result.index] = estimate(id, instruction);
    }
    if (instruction.opcode == Opcode::CutBegin) {
      cut_ = instruction.index;
    }
    measureMove(instruction);
    for (const Region& region : instruction.regions) {
      walk(region);
    }
  }

  Estimate estimate(InstructionId id, const Instruction& instruction) {
    const std::vector<ValueId>& operands = instruction.operands;
    switch (instruction.opcode) {
    case Opcode::Const:
      return number(instruction.number, id);
    case Opcode::Param:
      return number(function_.parameters[instruction.index].defaultValue, id);
    case Opcode::TableLoad:
      return table(instruction.index, id);
    case Opcode::Add:
    case Opcode::Sub:
      return sum(of(operands[0]), of(operands[1]));
    case Opcode::Mul:
      return product(of(operands[0]), of(operands[1]));
    case Opcode::Div:
      return quotient(of(operands[0]), of(operands[1]));
    case Opcode::Neg:
    case Opcode::Abs:
      return of(operands[0]);
    case Opcode::Sqrt:
      return squareRoot(of(operands[0]));
    case Opcode::Sin:
    case Opcode::Cos:
    case Opcode::Tan:
      return periodic(operands[0], id);
    case Opcode::Loop: {
      Estimate bounds = larger(of(operands[0]), of(operands[1]));
      if (static_cast<LoopRole>(instruction.index) == LoopRole::Curve) {
        return {bounds.magnitude, {}, {}, true};
      }
      return bounds;
    }
    case Opcode::Select:
      return larger(of(operands[1]), of(operands[2]));
    case Opcode::CurveLap: {
      const CurveTableEntry& curve = function_.curves[instruction.index];
      return {std::max({std::abs(curve.from), std::abs(curve.to), 1.0}), {}, {}, true};
    }
    default:
      return other(instruction);
    }
  }

  // A phase added to a curve's parameter keeps its rounding.
  static Estimate sum(const Estimate& a, const Estimate& b) {
    return {a.magnitude + b.magnitude, a.rounding.plus(b.rounding),
            a.throughAngle.plus(b.throughAngle), a.alongCurve || b.alongCurve};
  }

  // d(ab) = b da + a db; a factor of a curve's parameter (a frequency)
  // rounds along the curve.
  static Estimate product(const Estimate& a, const Estimate& b) {
    Share rounding = b.alongCurve ? Share{} : a.rounding.scaled(b.magnitude);
    if (!a.alongCurve) {
      rounding = rounding.plus(b.rounding.scaled(a.magnitude));
    }
    return {a.magnitude * b.magnitude, rounding,
            a.throughAngle.scaled(b.magnitude).plus(b.throughAngle.scaled(a.magnitude)),
            a.alongCurve || b.alongCurve};
  }

  // d(a/b) = da / b - a db / b^2, b at its largest magnitude.
  static Estimate quotient(const Estimate& a, const Estimate& b) {
    if (!(b.magnitude > 0)) {
      return a;
    }
    double slope = a.magnitude / (b.magnitude * b.magnitude);
    Share rounding = b.alongCurve ? Share{} : a.rounding.scaled(1 / b.magnitude);
    if (!a.alongCurve) {
      rounding = rounding.plus(b.rounding.scaled(slope));
    }
    return {a.magnitude / b.magnitude, rounding,
            a.throughAngle.scaled(1 / b.magnitude).plus(b.throughAngle.scaled(slope)),
            a.alongCurve || b.alongCurve};
  }

  // d(sqrt a) = da / (2 sqrt a).
  static Estimate squareRoot(const Estimate& a) {
    double root = std::sqrt(a.magnitude);
    double slope = root > 0 ? 1 / (2 * root) : 1;
    return {root, a.rounding.scaled(slope), a.throughAngle.scaled(slope), a.alongCurve};
  }

  static Estimate larger(const Estimate& a, const Estimate& b) {
    return {std::max(a.magnitude, b.magnitude), a.rounding.larger(b.rounding),
            a.throughAngle.larger(b.throughAngle), a.alongCurve || b.alongCurve};
  }

  // The relative error of the factor the controller multiplies an angle by
  // to have it in degrees: 180/pi rounded, or where the angle is a product
  // or quotient with a constant, that constant times 180/pi rounded (the
  // printers fold it into the conversion: `#3*114.59156`).
  double conversionRounding(ValueId angle) const {
    auto relative = [this](double factor) {
      return std::abs(controllerReading(factor, digits_) - factor) / std::abs(factor);
    };
    double largest = relative(degreesPerRadian);
    const Instruction& definition = function_.definition(angle);
    if (definition.opcode == Opcode::Mul || definition.opcode == Opcode::Div) {
      for (std::size_t side = 0; side < 2; ++side) {
        const Instruction& factor = function_.definition(definition.operands[side]);
        if (factor.opcode != Opcode::Const || factor.number == 0 ||
            (definition.opcode == Opcode::Div && side == 0)) {
          continue;
        }
        double folded = definition.opcode == Opcode::Mul ? factor.number * degreesPerRadian
                                                         : degreesPerRadian / factor.number;
        largest = std::max(largest, relative(folded));
      }
    }
    return largest;
  }

  // The angle's error, its own rounding and the rounding of its conversion
  // to degrees, passes to the sine or cosine at slope at most 1 (and never
  // past the 2 a cosine can change by); tan is taken at the same slope. The
  // conversion of a curve's parameter scales it: along the curve.
  Estimate periodic(ValueId angleValue, InstructionId id) const {
    const Estimate& angle = of(angleValue);
    Share error = angle.rounding.plus(angle.throughAngle);
    if (!angle.alongCurve) {
      error = error.plus(Share::of(angle.magnitude * conversionRounding(angleValue), id));
    }
    if (function_.instructions[id].opcode != Opcode::Tan) {
      error.size = std::min(error.size, 2.0);
    }
    return {1, {}, error};
  }

  // Any other operation: its operands' errors carried unscaled, the largest
  // of their magnitudes (comparisons and bools carry none).
  Estimate other(const Instruction& instruction) const {
    Estimate result;
    if (opcodeInfo(instruction.opcode).result != ValueType::F64) {
      return result;
    }
    for (ValueId operand : instruction.operands) {
      if (function_.valueTypes[operand.index] != ValueType::F64) {
        continue;
      }
      const Estimate& estimate = of(operand);
      result.magnitude = std::max(result.magnitude, estimate.magnitude);
      result.rounding = result.rounding.plus(estimate.rounding);
      result.throughAngle = result.throughAngle.plus(estimate.throughAngle);
      result.alongCurve = result.alongCurve || estimate.alongCurve;
    }
    return result;
  }

  // A table's entries: the largest, and the largest rounding among them
  // (worked out once per table).
  Estimate table(std::uint32_t index, InstructionId id) {
    auto found = tables_.find(index);
    if (found == tables_.end()) {
      Estimate entries;
      for (double entry : function_.tables[index]) {
        entries = larger(entries, number(entry, id));
      }
      found = tables_.emplace(index, entries).first;
    }
    Estimate result = found->second;
    result.rounding.source = id;
    return result;
  }

  // A feed move's point (an arc's end and centre, a curve point) moves by
  // the largest of its coordinates' errors that went through a periodic
  // function: an angle turned by d moves x = r cos a and y = r sin a
  // together by r d, where each is off by up to r d.
  void measureMove(const Instruction& instruction) {
    if (!cut_) {
      return;
    }
    std::size_t coordinates = 0;
    switch (instruction.opcode) {
    case Opcode::Feed:
    case Opcode::CurvePoint:
    case Opcode::CurveWalk:
    case Opcode::Polynomial:
      coordinates = 3;
      break;
    case Opcode::Arc:
    case Opcode::CurveArc:
      coordinates = 5;
      break;
    default:
      return;
    }
    Share largest;
    for (std::size_t c = 0; c < coordinates; ++c) {
      largest = largest.larger(of(instruction.operands[c]).throughAngle);
    }
    double movement = largest.size;
    if (!(movement > 0) || largest.source == noSource) {
      return;
    }
    LiteralRoundingMove& recorded = largest_[*cut_];
    if (movement > recorded.movement) {
      recorded = {*cut_, movement, largest.source};
    }
  }

  const Function& function_;
  int digits_;
  std::vector<Estimate> estimates_;
  std::map<std::uint32_t, Estimate> tables_;
  std::optional<std::uint32_t> cut_;
  std::map<std::uint32_t, LiteralRoundingMove> largest_;
};

} // namespace

std::vector<LiteralRoundingMove> trigonometricRoundingMoves(const Function& function, int digits) {
  return RoundingPropagation(function, digits).run();
}

} // namespace cncc::ir::lowering
