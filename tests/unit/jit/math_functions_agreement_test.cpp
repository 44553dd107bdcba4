// One arithmetic (cncc/geom/math_functions.h): for every math function and
// inputs at the edges of its domain (0, -0, negatives, huge and tiny
// numbers), the front end's evaluation of a CDL constant, the IR's folding
// arithmetic, the interpreter and the JIT agree bit for bit, or the front
// end reports the input outside the domain where the IR computes a value
// that is not finite.
#include "jit_test_support.h"

#include "../frontend/checked_source.h"

#include "cncc/geom/math_functions.h"
#include "cncc/ir/arithmetic.h"
#include "cncc/ir/builder.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace cncc {
namespace {

using geom::MathFunction;
using geom::MathFunctionInfo;
using ir::FunctionBuilder;
using ir::Opcode;
using ir::ValueId;

const std::vector<double> kInputs = {0,   -0.0, 1,       -1,      0.5,    -0.5,
                                     2,   -8,   1.0 / 3, 1e-300,  1e300,  -1e300,
                                     710, -745, 3.25,    1.5e308, 0.9999, 100};

// The same number, NaN matching any NaN (the sign of a NaN is no value).
bool sameBits(double expected, double actual) {
  if (std::isnan(expected) || std::isnan(actual)) {
    return std::isnan(expected) && std::isnan(actual);
  }
  return std::bit_cast<std::uint64_t>(expected) == std::bit_cast<std::uint64_t>(actual);
}

// A CDL literal that reads back as exactly `value`.
std::string literal(double value) {
  std::string magnitude = fmt::format("{:.17g}", std::abs(value));
  return std::signbit(value) ? "-" + magnitude : magnitude;
}

std::string callText(const MathFunctionInfo& info, double a, double b) {
  if (info.function == MathFunction::Rem) {
    return fmt::format("({}) % ({})", literal(a), literal(b));
  }
  if (info.arity == 1) {
    return fmt::format("{}({})", info.name, literal(a));
  }
  return fmt::format("{}({}, {})", info.name, literal(a), literal(b));
}

Opcode opcodeOf(MathFunction function) {
  for (Opcode opcode : ir::allOpcodes()) {
    if (ir::mathFunctionOf(opcode) == function) {
      return opcode;
    }
  }
  ADD_FAILURE() << "no opcode computes " << geom::mathFunctionInfo(function).name;
  return Opcode::Const;
}

struct Case {
  double a = 0;
  double b = 0;
};

std::vector<Case> casesOf(const MathFunctionInfo& info) {
  std::vector<Case> cases;
  for (double a : kInputs) {
    if (info.arity == 1) {
      cases.push_back({a, 0});
      continue;
    }
    for (double b : kInputs) {
      cases.push_back({a, b});
    }
  }
  return cases;
}

// `feed(f(a, b), 0, 0)` for each case: the inputs in tables read by a loop
// whose bound is a parameter, so that LLVM computes them at run time.
ir::Function runFunction(const MathFunctionInfo& info, const std::vector<Case>& cases) {
  FunctionBuilder builder(std::string(info.name == "%" ? "rem" : info.name));
  std::vector<double> first;
  std::vector<double> second;
  for (const Case& c : cases) {
    first.push_back(c.a);
    second.push_back(c.b);
  }
  std::uint32_t firstTable = builder.addTable(first);
  std::uint32_t secondTable = builder.addTable(second);
  std::uint32_t count = builder.addParameter("count", static_cast<double>(cases.size()));
  ValueId last = builder.binary(Opcode::Sub, builder.parameter(count), builder.constant(1));
  ValueId index = builder.beginLoop(builder.constant(0), last);
  ValueId a = builder.tableLoad(firstTable, index);
  ValueId b = builder.tableLoad(secondTable, index);
  Opcode opcode = opcodeOf(info.function);
  ValueId result = info.arity == 1 ? builder.unary(opcode, a) : builder.binary(opcode, a, b);
  builder.feed(result, builder.constant(0), builder.constant(0), builder.constant(100));
  builder.endLoop();
  return builder.finish();
}

std::vector<double> fedValues(const ir::ToolPath& path) {
  std::vector<double> values;
  for (const ir::MachineEvent& event : path.events) {
    if (event.kind == ir::MachineEvent::Kind::Feed) {
      values.push_back(event.x);
    }
  }
  return values;
}

} // namespace
} // namespace cncc

namespace cncc::geom {
// Names the parameter of a failing test.
void PrintTo(const MathFunctionInfo& info, std::ostream* out) {
  *out << info.name;
}
} // namespace cncc::geom

namespace cncc {
namespace {

class MathFunctionAgreement : public ::testing::TestWithParam<MathFunctionInfo> {};

TEST_P(MathFunctionAgreement, FrontEndFoldingInterpreterAndJitAgree) {
  const MathFunctionInfo& info = GetParam();
  std::vector<Case> cases = casesOf(info);
  ir::Function function = runFunction(info, cases);
  std::vector<double> interpreted = fedValues(ir::interpret(function));
  std::vector<double> compiled = fedValues(backends::CompiledFunction(function).run());
  ASSERT_EQ(interpreted.size(), cases.size());
  ASSERT_EQ(compiled.size(), cases.size());
  Opcode opcode = opcodeOf(info.function);
  for (std::size_t i = 0; i < cases.size(); ++i) {
    double a = cases[i].a;
    double b = cases[i].b;
    double expected = geom::computeMath(info.function, a, b);
    std::string text = callText(info, a, b);
    std::optional<double> folded =
        info.arity == 1 ? ir::unaryResult(opcode, a) : ir::binaryResult(opcode, a, b);
    ASSERT_TRUE(folded.has_value()) << text;
    EXPECT_TRUE(sameBits(expected, *folded)) << text << ": folding gives " << *folded;
    EXPECT_TRUE(sameBits(expected, interpreted[i]))
        << text << ": the interpreter gives " << interpreted[i];
    EXPECT_TRUE(sameBits(expected, compiled[i])) << text << ": the JIT gives " << compiled[i];

    auto checked = frontend::test_support::check(
        "const v = " + text + "\n" + frontend::test_support::part("  curve line((0, 0), (1, 1))"));
    const frontend::Declaration* constant = checked->find("v");
    ASSERT_NE(constant, nullptr) << text;
    if (geom::outsideDomain(a, b, expected)) {
      // Outside the domain: a diagnostic at the call, no value.
      EXPECT_FALSE(checked->names().empty()) << text << " is outside the domain";
      EXPECT_TRUE(!constant->value || constant->value->isError()) << text;
      continue;
    }
    ASSERT_TRUE(checked->names().empty()) << text << ": " << checked->names().front();
    ASSERT_TRUE(constant->value.has_value()) << text;
    EXPECT_TRUE(sameBits(expected, constant->value->number))
        << text << ": the front end gives " << constant->value->number;
  }
}

std::string functionName(const ::testing::TestParamInfo<MathFunctionInfo>& info) {
  return info.param.function == MathFunction::Rem ? "rem" : std::string(info.param.name);
}

INSTANTIATE_TEST_SUITE_P(EveryMathFunction, MathFunctionAgreement,
                         ::testing::ValuesIn(geom::mathFunctions), functionName);

TEST(MathFunctionTable, EveryMathOpcodeIsInTheTable) {
  int mathOpcodes = 0;
  for (Opcode opcode : ir::allOpcodes()) {
    if (std::optional<MathFunction> function = ir::mathFunctionOf(opcode)) {
      ++mathOpcodes;
      EXPECT_EQ(geom::mathFunctionInfo(*function).arity, ir::opcodeInfo(opcode).operandCount)
          << ir::opcodeInfo(opcode).spelling << " takes another number of operands";
    }
  }
  EXPECT_EQ(mathOpcodes, static_cast<int>(geom::mathFunctions.size()));
}

} // namespace
} // namespace cncc
