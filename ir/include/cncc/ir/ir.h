// The IR: the single meaning of a part. A Function per part, its parameters
// as inputs; SSA values of type f64 or bool; structured control flow (loops
// with an induction variable, if/else) because every controller language
// cncc targets is structured; side effects (moves, spindle, tool, comments)
// as explicit operations. Instructions live in one flat vector and refer to
// each other by index.
#pragma once

#include "cncc/frontend/source_span.h"
#include "cncc/ir/curve_table.h"
#include "cncc/ir/cut_geometry.h"
#include "cncc/ir/sweep_pass.h"

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::ir {

enum class Opcode {
#define CNCC_IR_OP(identifier, spelling, operands, result, traits, meaning) identifier,
#include "cncc/ir/ir_ops.def"
};

enum class ValueType { None, F64, Bool };

// What the passes may do with an operation (ir_ops.def explains each).
enum class OpcodeTraits { Pure, MayFail, Effect, Control };

struct OpcodeInfo {
  std::string_view spelling;
  int operandCount; // -1: any
  ValueType result;
  OpcodeTraits traits;
  std::string_view meaning;
};

const OpcodeInfo& opcodeInfo(Opcode opcode);
// Something the machine does (a move, the spindle, a comment...): kept, in order.
inline bool isEffect(Opcode opcode) {
  return opcodeInfo(opcode).traits == OpcodeTraits::Effect;
}
// Computes its result from its operands alone (table.load included, which
// may also stop the run: see mayFail).
inline bool isPure(Opcode opcode) {
  OpcodeTraits traits = opcodeInfo(opcode).traits;
  return traits == OpcodeTraits::Pure || traits == OpcodeTraits::MayFail;
}
inline bool mayFail(Opcode opcode) {
  return opcodeInfo(opcode).traits == OpcodeTraits::MayFail;
}

// The immediate of `move.arc` (Instruction::index): its turning direction.
enum class ArcTurn : std::uint32_t { Clockwise = 0, CounterClockwise = 1 };
// The immediate of `loop` (Instruction::index): what made the loop, for
// source maps (a loop the optimiser made keeps Statement).
enum class LoopRole : std::uint32_t {
  Statement = 0, // a `for` statement, or what its span's statement is
  Passes = 1,    // the passes of a cut's sweep
  Curve = 2      // the steps along a cut's curve
};
// The immediate of `coolant` (Instruction::index).
enum class CoolantMode : std::uint32_t { Off = 0, Flood = 1, Mist = 2, Through = 3 };
// "off", "flood", "mist", "through"; nullopt for another word.
std::string_view coolantModeName(CoolantMode mode);
std::optional<CoolantMode> coolantModeNamed(std::string_view name);
// Every opcode, in declaration order.
std::vector<Opcode> allOpcodes();

// An SSA value: the result of one instruction.
struct ValueId {
  static constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
  std::uint32_t index = none;
  bool valid() const { return index != none; }
  friend bool operator==(ValueId, ValueId) = default;
};

using InstructionId = std::uint32_t;

// A straight-line list of instructions; loops and ifs own nested regions.
struct Region {
  std::vector<InstructionId> instructions;
};

struct Instruction {
  Opcode opcode = Opcode::Const;
  std::vector<ValueId> operands;
  ValueId result;              // invalid when the operation has none
  double number = 0;           // Const value, ConstBool (0 or 1), Tool number, Origin code
                               // (54 .. 59, 54.1), Contouring tolerance (0: off),
                               // Compensation offset (left positive, 0: off)
  std::uint32_t index = 0;     // TableLoad, Nurbs, Spline: the table; Param: the parameter;
                               // CurveLap: the curve table's entry;
                               // CutBegin: the cut; Arc: its ArcTurn; Loop: its LoopRole;
                               // Tool: its length
                               // offset register; Origin 54.1: P; Coolant: its CoolantMode;
                               // Compensation: the radius register
  std::string text;            // Comment, Alarm: the text
  std::vector<Region> regions; // Loop: {body}; If: {then, else}; CurveLap: one per piece
                               // or NURBS knot span
  // The CDL statement it was lowered from (the part's name for the set-up
  // around the statements); not printed in the IR's text. What a source
  // map gives for the program lines printed from it.
  frontend::SourceSpan span;
  // The written-out pass of a cut's sweep it was lowered for (sweep_pass.h).
  SweepPass pass;
};

// The operations that end a curve.lap's region (and appear nowhere else).
inline bool endsLapRegion(Opcode opcode) {
  return opcode == Opcode::CurvePoint || opcode == Opcode::CurveArc || opcode == Opcode::CurveWalk;
}

// A copy of the instruction without its regions (a loop's or a lap's can
// hold thousands): what reading its operation and operands needs.
inline Instruction withoutRegions(const Instruction& instruction) {
  Instruction copy;
  copy.opcode = instruction.opcode;
  copy.operands = instruction.operands;
  copy.result = instruction.result;
  copy.number = instruction.number;
  copy.index = instruction.index;
  copy.text = instruction.text;
  copy.span = instruction.span;
  copy.pass = instruction.pass;
  return copy;
}

struct Parameter {
  std::string name;
  double defaultValue = 0;
  // Its default was read at compile time (a loop bound, a sampled curve...):
  // a program that lets it be edited must refuse any other value.
  bool fixed = false;
};

// How large a function may grow (a part of many cuts in unrolled loops):
// past either, compiling is refused.
inline constexpr std::size_t maximumInstructions = 5'000'000;
inline constexpr std::size_t maximumTableEntries = 20'000'000;
// Whether the function is past them, and the message that says so.
struct Function;
bool isTooLarge(const Function& function);
std::string functionTooLargeMessage();

// What a legalisation found that the part's author should hear of, though
// the program is right (a spline whose transitions make the control stop
// exactly; arcs asked for that no fit keeps, so chords are cut): the caller
// reports it at `span` and clears the list.
struct LegalisationWarning {
  enum class Kind { SplineExactStop, ArcsAsChords, ParameterFixed, SplineAsChords };
  Kind kind = Kind::SplineExactStop;
  frontend::SourceSpan span;
  std::string message;
};

struct Function {
  std::string name;
  std::vector<Parameter> parameters;
  // Constant tables, such as precomputed curve parameters.
  std::vector<std::vector<double>> tables;
  // The curves that `curve.lap` ops go along (curve_table.h).
  std::vector<CurveTableEntry> curves;
  // The part's cuts, indexed by cut.begin (a cut in an unrolled loop has
  // one per iteration): what verify measures and plots draw. In the text a
  // `cut @n` line each, without their curves and spans.
  std::vector<CutGeometry> cuts;
  std::vector<Instruction> instructions;
  // The type of each value, and the instruction that defines it.
  std::vector<ValueType> valueTypes;
  std::vector<InstructionId> definitions;
  Region body;
  // Not part of the program (not printed): the legalisations' warnings.
  std::vector<LegalisationWarning> warnings;

  const Instruction& definition(ValueId value) const {
    return instructions[definitions[value.index]];
  }
};

// The value a loop's variable advances to (the operand of the `loop.next`
// that ends its body); invalid for a loop that counts up by one.
ValueId loopAdvance(const Function& function, const Instruction& loop);

} // namespace cncc::ir
