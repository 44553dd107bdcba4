// Folding computes what the interpreter computes, for every operation and
// for awkward inputs (signed zeros, infinities, NaN, halves, big numbers).
#include "cncc/ir/builder.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/printer.h"
#include "cncc/ir/verifier.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <limits>

namespace cncc::ir {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

constexpr double inputs[] = {0.0,
                             -0.0,
                             1.0,
                             -1.0,
                             0.5,
                             -2.5,
                             3.0,
                             1e300,
                             -1e-300,
                             std::numeric_limits<double>::infinity(),
                             std::numeric_limits<double>::quiet_NaN()};

// One feed move whose x is `opcode` applied to the inputs: as constants
// (for folding) or, with `asParameters`, as parameters (run time).
Function oneOperation(Opcode opcode, double a, double b, bool asParameters) {
  FunctionBuilder builder("f");
  std::uint32_t first = builder.addParameter("a", a);
  std::uint32_t second = builder.addParameter("b", b);
  ValueId left = asParameters ? builder.parameter(first) : builder.constant(a);
  ValueId right = asParameters ? builder.parameter(second) : builder.constant(b);
  ValueId zero = builder.constant(0);
  ValueId result;
  if (opcodeInfo(opcode).operandCount == 1) {
    result = builder.unary(opcode, left);
  } else {
    result = builder.binary(opcode, left, right);
  }
  ValueId x = result;
  if (opcodeInfo(opcode).result == ValueType::Bool) {
    x = builder.operation(Opcode::Select, {result, builder.constant(1), zero});
  }
  builder.feed(x, zero, zero, zero);
  return builder.finish();
}

bool isArithmetic(Opcode opcode) {
  int operands = opcodeInfo(opcode).operandCount;
  bool numeric = opcode != Opcode::And && opcode != Opcode::Or && opcode != Opcode::Not;
  return numeric && (operands == 1 || operands == 2) && opcode != Opcode::TableLoad &&
         opcode != Opcode::Loop && opcodeInfo(opcode).result != ValueType::None;
}

TEST(PassesFoldTest, FoldedValuesAreTheInterpretersBitForBit) {
  int folded = 0;
  for (Opcode opcode : allOpcodes()) {
    if (!isArithmetic(opcode)) {
      continue;
    }
    for (double a : inputs) {
      for (double b : inputs) {
        double atRunTime = interpret(oneOperation(opcode, a, b, true)).events[0].x;
        Function function = oneOperation(opcode, a, b, false);
        std::size_t before = instructionCount(function);
        foldConstants(function);
        eliminateDeadCode(function);
        ASSERT_TRUE(verifyFunction(function).empty());
        double folding = interpret(function).events[0].x;
        EXPECT_EQ(std::bit_cast<std::uint64_t>(atRunTime) ==
                          std::bit_cast<std::uint64_t>(folding) ||
                      (std::isnan(atRunTime) && std::isnan(folding)),
                  true)
            << opcodeInfo(opcode).spelling << "(" << a << ", " << b << ")";
        folded += instructionCount(function) < before ? 1 : 0;
      }
    }
  }
  EXPECT_GT(folded, 1000);
}

// a + -b, -b + a, a - -b, x * -1, a + b * -c, b * -c + a and a - b * -c
// are rewritten
// as a - b, a + b, -x and a -/+ b * c: the same bits for every a and b the
// parameters hold (signed zeros, infinities and NaN included).
TEST(PassesFoldTest, NegationsBecomeSubtractionsBitForBit) {
  enum Form {
    PlusNegated,
    NegatedPlus,
    MinusNegated,
    TimesMinusOne,
    PlusProduct,
    ProductPlus,
    MinusProduct
  };
  auto build = [](Form form, double a, double b) {
    FunctionBuilder builder("f");
    ValueId left = builder.parameter(builder.addParameter("a", a));
    ValueId right = builder.parameter(builder.addParameter("b", b));
    ValueId negated = builder.unary(Opcode::Neg, right);
    ValueId product = builder.binary(Opcode::Mul, right, builder.constant(-2.5));
    ValueId result;
    switch (form) {
    case PlusNegated:
      result = builder.binary(Opcode::Add, left, negated);
      break;
    case NegatedPlus:
      result = builder.binary(Opcode::Add, negated, left);
      break;
    case MinusNegated:
      result = builder.binary(Opcode::Sub, left, negated);
      break;
    case TimesMinusOne:
      result = builder.binary(Opcode::Mul, builder.constant(-1), left);
      break;
    case PlusProduct:
      result = builder.binary(Opcode::Add, left, product);
      break;
    case ProductPlus:
      result = builder.binary(Opcode::Add, product, left);
      break;
    case MinusProduct:
      result = builder.binary(Opcode::Sub, left, product);
      break;
    }
    ValueId zero = builder.constant(0);
    builder.feed(result, zero, zero, zero);
    return builder.finish();
  };
  for (Form form : {PlusNegated, NegatedPlus, MinusNegated, TimesMinusOne, PlusProduct, ProductPlus,
                    MinusProduct}) {
    Function sample = build(form, 1, 2);
    foldConstants(sample);
    eliminateDeadCode(sample);
    std::string text = printFunction(sample);
    EXPECT_THAT(text, Not(HasSubstr("-1\n"))) << text;
    EXPECT_THAT(text, Not(HasSubstr("-2.5"))) << text;
    if (form != TimesMinusOne) {
      EXPECT_THAT(text, Not(HasSubstr("neg"))) << text;
    }
    for (double a : inputs) {
      for (double b : inputs) {
        Function function = build(form, a, b);
        double before = interpret(function).events[0].x;
        foldConstants(function);
        ASSERT_TRUE(verifyFunction(function).empty());
        double after = interpret(function).events[0].x;
        EXPECT_TRUE(std::bit_cast<std::uint64_t>(before) == std::bit_cast<std::uint64_t>(after) ||
                    (std::isnan(before) && std::isnan(after)))
            << text << " at a = " << a << ", b = " << b;
      }
    }
  }
}

TEST(PassesFoldTest, NonFiniteResultsStayOperations) {
  Function function = oneOperation(Opcode::Div, 1, 0, false);
  foldConstants(function);
  EXPECT_THAT(printFunction(function), HasSubstr("div"));
  EXPECT_THAT(printFunction(function), Not(HasSubstr("inf")));
}

TEST(PassesFoldTest, LogicWithConstants) {
  FunctionBuilder builder("logic");
  ValueId x = builder.parameter(builder.addParameter("x", 1));
  ValueId zero = builder.constant(0);
  ValueId condition = builder.binary(Opcode::Lt, x, zero);
  ValueId yes = builder.constantBool(true);
  ValueId no = builder.constantBool(false);
  ValueId both = builder.binary(Opcode::And, condition, yes);                     // condition
  ValueId either = builder.binary(Opcode::Or, condition, yes);                    // true
  ValueId never = builder.binary(Opcode::And, no, condition);                     // false
  ValueId negated = builder.unary(Opcode::Not, builder.unary(Opcode::Not, both)); // condition
  ValueId first = builder.operation(Opcode::Select, {negated, x, zero});
  ValueId second = builder.operation(Opcode::Select, {either, x, zero});
  ValueId third = builder.operation(Opcode::Select, {never, x, zero});
  builder.feed(first, second, third, zero);
  Function function = builder.finish();
  foldConstants(function);
  eliminateDeadCode(function);
  EXPECT_EQ(printFunction(function), "func @logic(x = 1) {\n"
                                     "  %0 = param x\n"
                                     "  %1 = const 0\n"
                                     "  %2 = lt %0, %1\n"
                                     "  %3 = select %2, %0, %1\n"
                                     "  move.feed %3, %0, %1, %1\n"
                                     "}\n");
}

} // namespace
} // namespace cncc::ir
