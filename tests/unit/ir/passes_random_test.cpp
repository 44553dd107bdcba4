// Every pass, and the default pipeline, on many random functions (loops,
// ifs, signed zeros, NaN-producing math, effects everywhere): the output
// verifies and the interpreter's tool path stays the same, bit for bit.
// fold-finite, which takes values to be finite, on random functions whose
// operations keep finite values finite: the path stays the same to 1e-9.
#include "cncc/ir/builder.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/printer.h"
#include "cncc/ir/verifier.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <random>

namespace cncc::ir {
namespace {

// Which operations a random function uses: all of them, or only those
// that keep finite operands finite (no division, root, logarithm, ..).
enum class Operations { All, KeepingFiniteValues };

class RandomFunction {
public:
  explicit RandomFunction(unsigned seed, Operations operations = Operations::All)
      : random_(seed), builder_("random"), operations_(operations) {}

  Function build() {
    builder_.addParameter("a", 1.5);
    builder_.addParameter("b", operations_ == Operations::All ? -0.0 : 0.0);
    builder_.addTable({0.25, -1, 4});
    Pools pools;
    pools.numbers = {builder_.parameter(0), builder_.parameter(1),
                     builder_.constant(operations_ == Operations::All ? -0.0 : 0.0)};
    pools.bools = {builder_.constantBool(true)};
    fillRegion(pools, 0);
    return builder_.finish();
  }

private:
  struct Pools {
    std::vector<ValueId> numbers;
    std::vector<ValueId> bools;
  };

  int below(int n) { return std::uniform_int_distribution<int>(0, n - 1)(random_); }
  template <typename T> T pick(const std::vector<T>& values) {
    return values[static_cast<std::size_t>(below(static_cast<int>(values.size())))];
  }
  ValueId number(const Pools& pools) { return pick(pools.numbers); }

  // The pools are copies, so values of a region are not used after it.
  void fillRegion(Pools pools, int depth) {
    int count = 3 + below(depth == 0 ? 25 : 8);
    for (int i = 0; i < count; ++i) {
      addInstruction(pools, depth);
    }
  }

  void addInstruction(Pools& pools, int depth) {
    static const std::vector<Opcode> unary = {Opcode::Neg,   Opcode::Abs, Opcode::Sqrt,
                                              Opcode::Sin,   Opcode::Ln,  Opcode::Floor,
                                              Opcode::Round, Opcode::Exp};
    static const std::vector<Opcode> binary = {Opcode::Add, Opcode::Sub,   Opcode::Mul,
                                               Opcode::Div, Opcode::Rem,   Opcode::Min,
                                               Opcode::Max, Opcode::Atan2, Opcode::Pow};
    static const std::vector<Opcode> comparisons = {Opcode::Lt, Opcode::Le, Opcode::Eq,
                                                    Opcode::Ne, Opcode::Ge, Opcode::Gt};
    static const std::vector<double> constants = {0, -0.0, 1, 2, 0.5, -3};
    static const std::vector<Opcode> finiteUnary = {Opcode::Neg, Opcode::Abs, Opcode::Sin,
                                                    Opcode::Floor, Opcode::Round};
    static const std::vector<Opcode> finiteBinary = {Opcode::Add, Opcode::Sub, Opcode::Mul,
                                                     Opcode::Min, Opcode::Max};
    // Not 1e-13, which fold-finite takes as 0: a comparison with it may
    // then go the other way (passes_fold_finite_test.cpp).
    static const std::vector<double> finiteConstants = {0, 1, 2, 0.5, -3};
    bool all = operations_ == Operations::All;
    switch (below(14)) {
    case 0:
      pools.numbers.push_back(builder_.constant(pick(all ? constants : finiteConstants)));
      return;
    case 1:
    case 2:
      pools.numbers.push_back(builder_.unary(pick(all ? unary : finiteUnary), number(pools)));
      return;
    case 3:
    case 4:
    case 5:
      pools.numbers.push_back(
          builder_.binary(pick(all ? binary : finiteBinary), number(pools), number(pools)));
      return;
    case 6:
      pools.bools.push_back(builder_.binary(pick(comparisons), number(pools), number(pools)));
      return;
    case 7:
      pools.bools.push_back(below(2) == 0 ? builder_.unary(Opcode::Not, pick(pools.bools))
                                          : builder_.binary(below(2) ? Opcode::And : Opcode::Or,
                                                            pick(pools.bools), pick(pools.bools)));
      return;
    case 8:
      pools.numbers.push_back(
          builder_.operation(Opcode::Select, {pick(pools.bools), number(pools), number(pools)}));
      return;
    case 9:
      pools.numbers.push_back(
          builder_.tableLoad(0, builder_.constant(static_cast<double>(below(3)))));
      return;
    case 10:
      addEffect(pools);
      return;
    case 11:
      if (depth < 3) {
        addIf(pools, depth);
        return;
      }
      addEffect(pools);
      return;
    default:
      if (depth < 3) {
        addLoop(pools, depth);
        return;
      }
      addEffect(pools);
      return;
    }
  }

  void addEffect(const Pools& pools) {
    switch (below(4)) {
    case 0:
      builder_.rapid(number(pools), number(pools), number(pools));
      return;
    case 1:
      builder_.comment("c");
      return;
    case 2:
      builder_.cutBegin(static_cast<std::uint32_t>(below(3)));
      return;
    default:
      builder_.feed(number(pools), number(pools), number(pools), number(pools));
      return;
    }
  }

  void addIf(const Pools& pools, int depth) {
    builder_.beginIf(pick(pools.bools));
    fillRegion(pools, depth + 1);
    builder_.beginElse();
    if (below(2) == 0) {
      fillRegion(pools, depth + 1);
    }
    builder_.endIf();
  }

  void addLoop(const Pools& pools, int depth) {
    static const std::vector<double> lows = {0, 1, 0.5, -0.0};
    static const std::vector<double> highs = {-1, 0, 2, 3, 9};
    ValueId low = builder_.constant(pick(lows));
    ValueId high = below(4) == 0 ? builder_.parameter(0) : builder_.constant(pick(highs));
    Pools inside = pools;
    inside.numbers.push_back(builder_.beginLoop(low, high));
    // Loads indexed by the induction variable stay in range for 0..2.
    fillRegion(inside, depth + 1);
    builder_.endLoop();
  }

  std::mt19937 random_;
  FunctionBuilder builder_;
  Operations operations_;
};

bool sameBits(double a, double b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b) ||
         (std::isnan(a) && std::isnan(b));
}

// Whether the two paths have the same events, each number as `same` says.
::testing::AssertionResult comparePaths(const ToolPath& expected, const ToolPath& actual,
                                        bool (*same)(double, double)) {
  if (expected.events.size() != actual.events.size()) {
    return ::testing::AssertionFailure()
           << expected.events.size() << " events became " << actual.events.size();
  }
  for (std::size_t i = 0; i < expected.events.size(); ++i) {
    const MachineEvent& a = expected.events[i];
    const MachineEvent& b = actual.events[i];
    if (a.kind != b.kind || a.text != b.text) {
      return ::testing::AssertionFailure() << "event " << i << " differs";
    }
    for (auto [x, y] :
         {std::pair{a.x, b.x}, std::pair{a.y, b.y}, std::pair{a.z, b.z}, std::pair{a.feed, b.feed},
          std::pair{a.number, b.number}, std::pair{a.diameter, b.diameter}}) {
      if (!same(x, y)) {
        return ::testing::AssertionFailure() << "event " << i << ": " << x << " became " << y;
      }
    }
  }
  return ::testing::AssertionSuccess();
}

::testing::AssertionResult samePath(const ToolPath& expected, const ToolPath& actual) {
  return comparePaths(expected, actual, sameBits);
}

TEST(PassesRandomTest, PassesKeepToolPathsOfRandomFunctions) {
  int checked = 0;
  for (unsigned seed = 1; seed <= 2000; ++seed) {
    Function original = RandomFunction(seed).build();
    ASSERT_TRUE(verifyFunction(original).empty()) << seed;
    ToolPath expected = interpret(original);
    for (const Pass& pass : allPasses()) {
      if (!pass.exact) {
        continue; // fold-finite: below, on functions of finite values
      }
      Function function = original;
      pass.run(function);
      std::vector<std::string> problems = verifyFunction(function);
      ASSERT_TRUE(problems.empty())
          << "seed " << seed << ", " << pass.name << ": " << problems.front() << "\n"
          << printFunction(function);
      ASSERT_TRUE(samePath(expected, interpret(function)))
          << "seed " << seed << ", " << pass.name << "\n"
          << printFunction(original);
    }
    Function function = original;
    runDefaultPipeline(function);
    ASSERT_TRUE(verifyFunction(function).empty()) << seed;
    ASSERT_TRUE(samePath(expected, interpret(function))) << "seed " << seed << ", pipeline\n"
                                                         << printFunction(original);
    EXPECT_LE(instructionCount(function), instructionCount(original)) << seed;
    ++checked;
  }
  EXPECT_EQ(checked, 2000);
}

// Each number of `actual` within 1e-9 of `expected`'s (relative to its
// size where that is above 1): fold-finite moves a number by what it takes
// as 0 or 1 (1e-12) at most, and a signed zero's sign.
::testing::AssertionResult closePath(const ToolPath& expected, const ToolPath& actual) {
  return comparePaths(expected, actual, [](double x, double y) {
    return std::abs(x - y) <= 1e-9 * std::max(1.0, std::abs(x));
  });
}

bool finitePath(const ToolPath& path) {
  for (const MachineEvent& event : path.events) {
    for (double number : {event.x, event.y, event.z, event.feed, event.number}) {
      if (!std::isfinite(number)) {
        return false;
      }
    }
  }
  return true;
}

TEST(PassesRandomTest, FoldFiniteKeepsToolPathsOfFunctionsOfFiniteValues) {
  int compared = 0;
  int changed = 0;
  for (unsigned seed = 1; seed <= 2000; ++seed) {
    Function original = RandomFunction(seed, Operations::KeepingFiniteValues).build();
    ToolPath expected = interpret(original);
    if (!finitePath(expected)) {
      continue; // a product that overflowed: the controller would alarm
    }
    Function function = original;
    changed += foldAssumingFinite(function) ? 1 : 0;
    std::vector<std::string> problems = verifyFunction(function);
    ASSERT_TRUE(problems.empty()) << "seed " << seed << ": " << problems.front();
    ASSERT_TRUE(closePath(expected, interpret(function))) << "seed " << seed << "\n"
                                                          << printFunction(original);
    EXPECT_FALSE(foldAssumingFinite(function)) << "seed " << seed << ": a second run changes it";
    ++compared;
  }
  EXPECT_GT(compared, 1900);
  EXPECT_GT(changed, 1000);
}

} // namespace
} // namespace cncc::ir
