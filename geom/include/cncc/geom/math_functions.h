// The math functions of CDL and of the IR in one table: name, arity, the
// function that computes it and the C library function the JIT calls for
// it. Every place that computes one reads it here (the front end's
// evaluator, IR folding (fold and fold-finite) and the interpreter through
// ir/arithmetic.h, the JIT), so a value computed at compile time
// is the value computed at run time, bit for bit.
//
// The domain rule, the same for every function: where the operands are
// finite and the result is not (ln(0) = -inf, ln(-1), sqrt(-1), asin(2),
// pow(0, -1), pow(-8, 1/3), exp(1000), fmod(x, 0)), the operation is
// outside its domain. The front end reports it at compile time, a
// diagnostic at the call (non-finite-value); IR arithmetic keeps IEEE
// values (NaN, -inf), because both sides of a select are computed, and the
// interpreter and the JIT stop where such a value reaches a move, a loop
// bound or a table index; a controller raises its alarm (LANGUAGE.md, Math).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace cncc::geom {

enum class MathFunction : std::uint8_t {
  Sin,
  Cos,
  Tan,
  Asin,
  Acos,
  Atan,
  Atan2,
  Sqrt,
  Abs,
  Min,
  Max,
  Pow,
  Exp,
  Ln,
  Floor,
  Ceil,
  Round,
  Rem, // CDL's `%` operator, the IR's rem: fmod
};

struct MathFunctionInfo {
  MathFunction function;
  std::string_view name; // as CDL calls it; `%` for the remainder (an operator)
  int arity;
  double (*compute)(double, double); // the second operand unused where arity is 1
  // The C library function the JIT calls; empty where the JIT's own
  // instruction computes the same exactly (fabs, sqrt, floor, min, ...).
  std::string_view cFunction;
  std::array<std::string_view, 2> parameters; // as named arguments name them
  std::string_view description;               // for hovers and completion
};

// In CDL's order of the builtins; MathFunction indexes it.
inline constexpr std::array<MathFunctionInfo, 18> mathFunctions = {{
    {MathFunction::Sin,
     "sin",
     1,
     [](double x, double) { return std::sin(x); },
     "sin",
     {"x", ""},
     "sine of an angle in radians"},
    {MathFunction::Cos,
     "cos",
     1,
     [](double x, double) { return std::cos(x); },
     "cos",
     {"x", ""},
     "cosine of an angle in radians"},
    {MathFunction::Tan,
     "tan",
     1,
     [](double x, double) { return std::tan(x); },
     "tan",
     {"x", ""},
     "tangent of an angle in radians"},
    {MathFunction::Asin,
     "asin",
     1,
     [](double x, double) { return std::asin(x); },
     "asin",
     {"x", ""},
     "arc sine, in radians"},
    {MathFunction::Acos,
     "acos",
     1,
     [](double x, double) { return std::acos(x); },
     "acos",
     {"x", ""},
     "arc cosine, in radians"},
    {MathFunction::Atan,
     "atan",
     1,
     [](double x, double) { return std::atan(x); },
     "atan",
     {"x", ""},
     "arc tangent, in radians"},
    {MathFunction::Atan2,
     "atan2",
     2,
     [](double y, double x) { return std::atan2(y, x); },
     "atan2",
     {"y", "x"},
     "angle of the point (x, y), in radians, -pi .. pi"},
    {MathFunction::Sqrt,
     "sqrt",
     1,
     [](double x, double) { return std::sqrt(x); },
     "",
     {"x", ""},
     "square root"},
    {MathFunction::Abs,
     "abs",
     1,
     [](double x, double) { return std::abs(x); },
     "",
     {"x", ""},
     "absolute value"},
    // As std::min and std::max: the first unless the second is beyond it.
    {MathFunction::Min,
     "min",
     2,
     [](double a, double b) { return b < a ? b : a; },
     "",
     {"a", "b"},
     "the smaller of two numbers"},
    {MathFunction::Max,
     "max",
     2,
     [](double a, double b) { return a < b ? b : a; },
     "",
     {"a", "b"},
     "the larger of two numbers"},
    {MathFunction::Pow,
     "pow",
     2,
     [](double a, double b) { return std::pow(a, b); },
     "pow",
     {"base", "exponent"},
     "base raised to exponent (also written base ^ exponent)"},
    {MathFunction::Exp,
     "exp",
     1,
     [](double x, double) { return std::exp(x); },
     "exp",
     {"x", ""},
     "e raised to x"},
    {MathFunction::Ln,
     "ln",
     1,
     [](double x, double) { return std::log(x); },
     "log",
     {"x", ""},
     "natural logarithm"},
    {MathFunction::Floor,
     "floor",
     1,
     [](double x, double) { return std::floor(x); },
     "",
     {"x", ""},
     "largest whole number not above x"},
    {MathFunction::Ceil,
     "ceil",
     1,
     [](double x, double) { return std::ceil(x); },
     "",
     {"x", ""},
     "smallest whole number not below x"},
    {MathFunction::Round,
     "round",
     1,
     [](double x, double) { return std::round(x); },
     "",
     {"x", ""},
     "nearest whole number, halves away from zero"},
    {MathFunction::Rem,
     "%",
     2,
     [](double a, double b) { return std::fmod(a, b); },
     "fmod",
     {"a", "b"},
     "remainder of a / b, with the sign of a"},
}};

constexpr bool mathFunctionsInOrder() {
  for (std::size_t i = 0; i < mathFunctions.size(); ++i) {
    if (static_cast<std::size_t>(mathFunctions[i].function) != i) {
      return false;
    }
  }
  return true;
}
static_assert(mathFunctionsInOrder(), "mathFunctions is indexed by MathFunction");

constexpr const MathFunctionInfo& mathFunctionInfo(MathFunction function) {
  return mathFunctions[static_cast<std::size_t>(function)];
}

// The function CDL calls `name`; null for any other name.
constexpr const MathFunctionInfo* findMathFunction(std::string_view name) {
  for (const MathFunctionInfo& info : mathFunctions) {
    if (info.name == name) {
      return &info;
    }
  }
  return nullptr;
}

inline double computeMath(MathFunction function, double a, double b = 0) {
  return mathFunctionInfo(function).compute(a, b);
}

// The domain rule: finite operands, a result that is not finite.
inline bool outsideDomain(double a, double b, double result) {
  return std::isfinite(a) && std::isfinite(b) && !std::isfinite(result);
}

} // namespace cncc::geom
