// Register allocation: which values get variables, liveness over loops,
// reuse of dead variables, tables, and the limits.
#include "cncc/ir/builder.h"
#include "cncc/ir/register_allocation.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <string>

namespace cncc::ir {
namespace {

using ::testing::HasSubstr;

AllocationOptions optionsWith(std::vector<VariableSpan> variables,
                              std::vector<int> parameters = {}) {
  AllocationOptions options;
  options.variables = std::move(variables);
  options.parameterVariables = std::move(parameters);
  return options;
}

// Two values used twice each, the first dead before the second is made:
// the second reuses the first's variable.
TEST(RegisterAllocation, ReusesTheVariableOfADeadValue) {
  FunctionBuilder builder("reuse");
  ValueId side = builder.parameter(builder.addParameter("side", 10));
  ValueId zero = builder.constant(0);
  ValueId first = builder.binary(Opcode::Mul, side, builder.constant(2));
  builder.rapid(first, first, zero);
  ValueId second = builder.binary(Opcode::Mul, side, builder.constant(3));
  builder.rapid(second, second, zero);
  Function function = builder.finish();

  AllocationResult result = allocateVariables(function, optionsWith({{1, 33}}, {1}));
  ASSERT_TRUE(result.ok());
  const Allocation& allocation = result.allocation;
  EXPECT_EQ(allocation.variableOfValue[side.index], 1);
  EXPECT_EQ(allocation.variableOfValue[first.index], 2);
  EXPECT_EQ(allocation.variableOfValue[second.index], 2);
  EXPECT_EQ(allocation.usedVariables, (std::vector<int>{1, 2}));
}

// A value used once stays inline; a constant never takes a variable.
TEST(RegisterAllocation, KeepsSingleUseValuesInline) {
  FunctionBuilder builder("inline");
  ValueId side = builder.parameter(builder.addParameter("side", 10));
  ValueId two = builder.constant(2);
  ValueId x = builder.binary(Opcode::Mul, side, two);
  builder.rapid(x, two, two);
  Function function = builder.finish();

  AllocationResult result = allocateVariables(function, optionsWith({{1, 33}}, {1}));
  ASSERT_TRUE(result.ok());
  EXPECT_FALSE(result.allocation.inVariable(x));
  EXPECT_FALSE(result.allocation.inVariable(two));
}

// A value defined before a loop and read in it is live through the whole
// loop: the values made in the body get other variables, and so does the
// induction variable; after the loop its variable is free again.
TEST(RegisterAllocation, KeepsAValueReadInALoopLiveThroughTheLoop) {
  FunctionBuilder builder("loop");
  ValueId side = builder.parameter(builder.addParameter("side", 10));
  ValueId zero = builder.constant(0);
  ValueId scaled = builder.binary(Opcode::Mul, side, builder.constant(2)); // read in the loop
  ValueId index = builder.beginLoop(zero, builder.constant(9));
  ValueId step = builder.binary(Opcode::Add, index, builder.constant(0.5));
  ValueId twice = builder.binary(Opcode::Mul, step, step); // `step` used twice
  builder.feed(scaled, twice, zero, builder.constant(100));
  builder.endLoop();
  ValueId after = builder.binary(Opcode::Sub, side, builder.constant(1));
  builder.rapid(after, after, zero);
  Function function = builder.finish();

  AllocationResult result = allocateVariables(function, optionsWith({{1, 33}}, {1}));
  ASSERT_TRUE(result.ok());
  const Allocation& allocation = result.allocation;
  ASSERT_TRUE(allocation.inVariable(scaled)); // computed once, outside the loop
  ASSERT_TRUE(allocation.inVariable(index));
  ASSERT_TRUE(allocation.inVariable(step));
  int scaledVariable = allocation.variableOfValue[scaled.index];
  EXPECT_NE(allocation.variableOfValue[index.index], scaledVariable);
  EXPECT_NE(allocation.variableOfValue[step.index], scaledVariable);
  EXPECT_NE(allocation.variableOfValue[step.index], allocation.variableOfValue[index.index]);
  // After the loop, the lowest free variable is taken again.
  EXPECT_EQ(allocation.variableOfValue[after.index], 2);
}

// The induction variable of an outer loop lives through the inner loop.
TEST(RegisterAllocation, KeepsAnOuterInductionVariableThroughAnInnerLoop) {
  FunctionBuilder builder("nested");
  ValueId zero = builder.constant(0);
  ValueId outer = builder.beginLoop(zero, builder.constant(3));
  ValueId inner = builder.beginLoop(zero, builder.constant(4));
  ValueId sum = builder.binary(Opcode::Add, outer, inner);
  builder.feed(sum, sum, zero, builder.constant(100));
  builder.endLoop();
  builder.endLoop();
  Function function = builder.finish();

  AllocationResult result = allocateVariables(function, optionsWith({{1, 33}}));
  ASSERT_TRUE(result.ok());
  const Allocation& allocation = result.allocation;
  std::set<int> distinct = {allocation.variableOfValue[outer.index],
                            allocation.variableOfValue[inner.index],
                            allocation.variableOfValue[sum.index]};
  EXPECT_EQ(distinct.size(), 3u);
}

// A loop advancing by a value its body computes into a variable: that
// value takes the loop variable's own variable (no `#u=#next` to print),
// and after the loop the variables are free again.
TEST(RegisterAllocation, GivesTheNextValueOfAnAdvancingLoopItsVariable) {
  FunctionBuilder builder("advance");
  ValueId side = builder.parameter(builder.addParameter("side", 10));
  ValueId zero = builder.constant(0);
  ValueId one = builder.constant(1);
  ValueId u = builder.beginLoop(zero, one);
  ValueId step = builder.binary(Opcode::Mul, u, u);
  ValueId wider = builder.binary(Opcode::Add, step, builder.constant(0.25));
  ValueId next = builder.binary(Opcode::Min, builder.binary(Opcode::Add, u, wider), one);
  builder.feed(next, next, zero, builder.constant(100)); // `next` used twice, and by loop.next
  builder.endLoopAdvancingTo(next);
  ValueId after = builder.binary(Opcode::Sub, side, one);
  builder.rapid(after, after, zero);
  Function function = builder.finish();

  AllocationResult result = allocateVariables(function, optionsWith({{1, 33}}, {1}));
  ASSERT_TRUE(result.ok());
  const Allocation& allocation = result.allocation;
  ASSERT_TRUE(allocation.inVariable(next));
  EXPECT_EQ(allocation.variableOfValue[next.index], allocation.variableOfValue[u.index]);
  EXPECT_EQ(allocation.variableOfValue[after.index], 2);
}

// A loop whose next value comes from outside it (a parameter): the loop
// variable's variable is not kept for a value that never takes it.
TEST(RegisterAllocation, KeepsNoVariableForANextValueFromOutsideTheLoop) {
  FunctionBuilder builder("outside");
  ValueId side = builder.parameter(builder.addParameter("side", 10));
  ValueId zero = builder.constant(0);
  ValueId u = builder.beginLoop(zero, builder.constant(1));
  ValueId twice = builder.binary(Opcode::Add, u, u);
  builder.feed(twice, twice, zero, builder.constant(100));
  builder.endLoopAdvancingTo(side);
  ValueId after = builder.binary(Opcode::Sub, side, builder.constant(1));
  ValueId again = builder.binary(Opcode::Mul, after, after);
  builder.rapid(again, again, after);
  Function function = builder.finish();

  AllocationResult result = allocateVariables(function, optionsWith({{1, 33}}, {1}));
  ASSERT_TRUE(result.ok());
  const Allocation& allocation = result.allocation;
  // The loop's variables are free after it: `after` and `again` reuse them.
  EXPECT_EQ(allocation.usedVariables, (std::vector<int>{1, 2, 3}));
}

// A counting loop whose index is only read scaled, u = i * 0.25: with
// stepScaledLoops, u takes the index's variable, which steps by 0.25, and
// u has no variable of its own.
TEST(RegisterAllocation, StepsALoopWhoseIndexIsOnlyReadScaled) {
  FunctionBuilder builder("scaled");
  ValueId zero = builder.constant(0);
  ValueId index = builder.beginLoop(zero, builder.constant(8));
  ValueId u = builder.binary(Opcode::Mul, index, builder.constant(0.25));
  ValueId square = builder.binary(Opcode::Mul, u, u); // `u` read twice: a variable
  builder.feed(square, u, zero, builder.constant(100));
  builder.endLoop();
  Function function = builder.finish();

  AllocationOptions options = optionsWith({{1, 33}});
  AllocationResult counted = allocateVariables(function, options);
  ASSERT_TRUE(counted.ok());
  EXPECT_NE(counted.allocation.variableOfValue[u.index],
            counted.allocation.variableOfValue[index.index]);
  EXPECT_TRUE(counted.allocation.stepOfLoop.empty());
  EXPECT_EQ(counted.allocation.usedVariables, (std::vector<int>{1, 2}));

  options.stepScaledLoops = true;
  AllocationResult stepped = allocateVariables(function, options);
  ASSERT_TRUE(stepped.ok());
  const Allocation& allocation = stepped.allocation;
  ASSERT_TRUE(allocation.inVariable(index));
  EXPECT_EQ(allocation.variableOfValue[u.index], allocation.variableOfValue[index.index]);
  EXPECT_EQ(allocation.stepOfLoop, (std::map<std::uint32_t, double>{{index.index, 0.25}}));
  EXPECT_TRUE(allocation.isSteppedProduct(u));
  EXPECT_FALSE(allocation.isSteppedProduct(square));
  EXPECT_EQ(allocation.usedVariables, (std::vector<int>{1}));
}

// A loop from 1 to a bound in a variable whose index is only read as
// u = i / high: u takes the index's variable, recorded as a NaN step
// (the variable steps by 1 / high).
TEST(RegisterAllocation, StepsALoopFromOneByOneOverItsBound) {
  FunctionBuilder builder("fraction");
  ValueId points = builder.parameter(builder.addParameter("points", 10));
  ValueId zero = builder.constant(0);
  ValueId index = builder.beginLoop(builder.constant(1), points);
  ValueId u = builder.binary(Opcode::Div, index, points);
  ValueId square = builder.binary(Opcode::Mul, u, u);
  builder.feed(square, u, zero, builder.constant(100));
  builder.endLoop();
  Function function = builder.finish();

  AllocationOptions options = optionsWith({{1, 33}}, {1});
  options.stepScaledLoops = true;
  AllocationResult result = allocateVariables(function, options);
  ASSERT_TRUE(result.ok());
  const Allocation& allocation = result.allocation;
  EXPECT_EQ(allocation.variableOfValue[u.index], allocation.variableOfValue[index.index]);
  ASSERT_TRUE(allocation.stepOfLoop.contains(index.index));
  EXPECT_TRUE(std::isnan(allocation.stepOfLoop.at(index.index)));
  EXPECT_EQ(allocation.usedVariables, (std::vector<int>{1, 2}));
}

// A loop whose index is also read unscaled, or scaled by a value that is
// not a constant, keeps counting its index.
TEST(RegisterAllocation, DoesNotStepALoopWhoseIndexIsNotOnlyReadScaled) {
  FunctionBuilder builder("unscaled");
  ValueId side = builder.parameter(builder.addParameter("side", 10));
  ValueId zero = builder.constant(0);
  ValueId counted = builder.beginLoop(zero, builder.constant(8));
  ValueId u = builder.binary(Opcode::Mul, counted, builder.constant(0.25));
  builder.feed(u, counted, zero, builder.constant(100)); // the index itself is read
  builder.endLoop();
  ValueId byParameter = builder.beginLoop(zero, builder.constant(8));
  ValueId v = builder.binary(Opcode::Mul, byParameter, side); // scaled by a parameter
  builder.feed(v, v, zero, builder.constant(100));
  builder.endLoop();
  Function function = builder.finish();

  AllocationOptions options = optionsWith({{1, 33}}, {1});
  options.stepScaledLoops = true;
  AllocationResult result = allocateVariables(function, options);
  ASSERT_TRUE(result.ok());
  const Allocation& allocation = result.allocation;
  EXPECT_TRUE(allocation.stepOfLoop.empty());
  EXPECT_TRUE(allocation.steppedProducts.empty());
  EXPECT_NE(allocation.variableOfValue[u.index], allocation.variableOfValue[counted.index]);
  EXPECT_NE(allocation.variableOfValue[v.index], allocation.variableOfValue[byParameter.index]);
}

// A table takes consecutive variables that nothing else shares.
TEST(RegisterAllocation, PlacesATableInConsecutiveVariables) {
  FunctionBuilder builder("table");
  std::uint32_t table = builder.addTable({0.1, 0.2, 0.3, 0.4});
  ValueId zero = builder.constant(0);
  ValueId index = builder.beginLoop(zero, builder.constant(3));
  ValueId t = builder.tableLoad(table, index);
  builder.feed(t, t, zero, builder.constant(100));
  builder.endLoop();
  Function function = builder.finish();

  AllocationResult result = allocateVariables(function, optionsWith({{1, 3}, {100, 110}}));
  ASSERT_TRUE(result.ok());
  const Allocation& allocation = result.allocation;
  EXPECT_EQ(allocation.tableBase[table], 100); // #1-#3 are too few
  for (ValueId value : {index, t}) {
    int variable = allocation.variableOfValue[value.index];
    EXPECT_TRUE(variable < 100 || variable > 103) << variable;
  }
}

TEST(RegisterAllocation, ReportsTooFewVariablesWithTheCount) {
  FunctionBuilder builder("crowded");
  ValueId zero = builder.constant(0);
  std::vector<ValueId> values;
  for (int i = 0; i < 4; ++i) { // four values live at once
    ValueId base = i == 0 ? builder.constant(1) : values.back();
    values.push_back(builder.binary(Opcode::Add, base, builder.constant(i + 1.0)));
  }
  for (ValueId value : values) {
    builder.rapid(value, value, zero);
  }
  for (ValueId value : values) {
    builder.rapid(value, zero, zero);
  }
  Function function = builder.finish();

  AllocationResult result = allocateVariables(function, optionsWith({{1, 3}}));
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.failures[0].limit, "variables");
  EXPECT_EQ(result.failures[0].needed, 4);
  EXPECT_EQ(result.failures[0].available, 3);
  EXPECT_THAT(result.failures[0].message, HasSubstr("needs 4 variables"));
}

TEST(RegisterAllocation, ReportsATableLargerThanAnyRun) {
  FunctionBuilder builder("long table");
  std::uint32_t table = builder.addTable(std::vector<double>(40, 0.5));
  ValueId zero = builder.constant(0);
  ValueId index = builder.beginLoop(zero, builder.constant(39));
  builder.feed(builder.tableLoad(table, index), zero, zero, builder.constant(100));
  builder.endLoop();
  Function function = builder.finish();

  AllocationResult result = allocateVariables(function, optionsWith({{1, 33}, {100, 129}}));
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.failures[0].limit, "consecutive variables");
  EXPECT_EQ(result.failures[0].needed, 40);
  EXPECT_EQ(result.failures[0].available, 33);
}

// sqrt(sqrt(sqrt(sqrt(x)))) with two bracket levels allowed: values move to
// variables until every statement fits.
TEST(RegisterAllocation, SplitsExpressionsDeeperThanTheBracketLimit) {
  FunctionBuilder builder("deep");
  ValueId x = builder.parameter(builder.addParameter("x", 2));
  ValueId value = x;
  std::vector<ValueId> chain;
  for (int i = 0; i < 4; ++i) {
    value = builder.unary(Opcode::Sqrt, value);
    chain.push_back(value);
  }
  ValueId zero = builder.constant(0);
  builder.rapid(value, zero, zero);
  Function function = builder.finish();

  AllocationOptions options = optionsWith({{1, 33}}, {1});
  options.maximumBracketDepth = 2;
  AllocationResult result = allocateVariables(function, options);
  ASSERT_TRUE(result.ok());
  int inVariables = 0;
  for (ValueId link : chain) {
    inVariables += result.allocation.inVariable(link) ? 1 : 0;
  }
  EXPECT_GE(inVariables, 1);
  EXPECT_LT(inVariables, 4);

  options.maximumBracketDepth = 0; // not even one function bracket
  AllocationResult impossible = allocateVariables(function, options);
  ASSERT_FALSE(impossible.ok());
  EXPECT_EQ(impossible.failures[0].limit, "bracket nesting");
}

TEST(RegisterAllocation, GivesOperationsWrittenAsStatementsAVariable) {
  FunctionBuilder builder("min");
  ValueId a = builder.parameter(builder.addParameter("a", 1));
  ValueId b = builder.binary(Opcode::Mul, a, builder.constant(3));
  ValueId smaller = builder.binary(Opcode::Min, a, b);
  ValueId zero = builder.constant(0);
  builder.rapid(smaller, zero, zero);
  Function function = builder.finish();

  AllocationOptions options = optionsWith({{1, 33}}, {1});
  options.statementOpcodes = {Opcode::Min};
  AllocationResult result = allocateVariables(function, options);
  ASSERT_TRUE(result.ok());
  EXPECT_TRUE(result.allocation.inVariable(smaller));
  EXPECT_TRUE(result.allocation.inVariable(b)); // written twice by min
  // `b` is read after the result is first written: no sharing.
  EXPECT_NE(result.allocation.variableOfValue[b.index],
            result.allocation.variableOfValue[smaller.index]);
}

} // namespace
} // namespace cncc::ir

namespace cncc::ir {
namespace {

// A statement `#n=expr` has its own length limit: the same chain of
// additions splits in a move's address words, not in an assignment.
TEST(RegisterAllocation, GivesAssignmentsTheirOwnLengthLimit) {
  FunctionBuilder builder("long");
  ValueId x = builder.parameter(builder.addParameter("x", 2));
  ValueId sum = x;
  std::vector<ValueId> chain;
  for (int i = 0; i < 6; ++i) {
    sum = builder.binary(Opcode::Add, sum, builder.binary(Opcode::Mul, x, x));
    chain.push_back(sum);
  }
  ValueId zero = builder.constant(0);
  builder.rapid(sum, sum, zero); // used twice: `#n=sum`, then X#n Y#n
  Function function = builder.finish();

  auto inVariables = [&](const AllocationResult& result) {
    int count = 0;
    for (std::size_t i = 0; i + 1 < chain.size(); ++i) {
      count += result.allocation.inVariable(chain[i]) ? 1 : 0;
    }
    return count;
  };
  AllocationOptions options = optionsWith({{1, 33}}, {1});
  options.maximumBracketDepth = 100; // only the length limits count here
  options.maximumInlineOperations = 4;
  AllocationResult tight = allocateVariables(function, options);
  ASSERT_TRUE(tight.ok());
  EXPECT_GT(inVariables(tight), 0);

  options.maximumAssignmentOperations = 100;
  AllocationResult roomy = allocateVariables(function, options);
  ASSERT_TRUE(roomy.ok());
  EXPECT_TRUE(roomy.allocation.inVariable(sum));
  EXPECT_EQ(inVariables(roomy), 0);
}

} // namespace
} // namespace cncc::ir

namespace cncc::ir {
namespace {

// a*b + c*d + a*c + b*d with the parameters in #100-#103: counted as `#nn`
// the move's expression fits its limit, counted as the `#100` it prints it
// does not, so it is split once they are numbered.
TEST(RegisterAllocation, CountsTheVariablesAStatementReadsAsNumbered) {
  FunctionBuilder builder("reads");
  std::vector<ValueId> parameters;
  for (const char* name : {"a", "b", "c", "d"}) {
    parameters.push_back(builder.parameter(builder.addParameter(name, 1)));
  }
  auto product = [&](int left, int right) {
    return builder.binary(Opcode::Mul, parameters[left], parameters[right]);
  };
  ValueId first = builder.binary(Opcode::Add, product(0, 1), product(2, 3));
  ValueId second = builder.binary(Opcode::Add, first, product(0, 2));
  ValueId sum = builder.binary(Opcode::Add, second, product(1, 3));
  ValueId zero = builder.constant(0);
  builder.rapid(sum, zero, zero);
  Function function = builder.finish();

  // 7 operations and 8 reads: 31 counted as `#nn`, 39 as `#100`.
  AllocationOptions options = optionsWith({{200, 299}}, {100, 101, 102, 103});
  options.maximumBracketDepth = 100;
  options.maximumInlineOperations = 35;
  options.estimatedReadCharacters = 3;
  options.readCharacters = [](int) { return 3; };
  AllocationResult estimated = allocateVariables(function, options);
  ASSERT_TRUE(estimated.ok());
  EXPECT_FALSE(estimated.allocation.inVariable(first));
  EXPECT_FALSE(estimated.allocation.inVariable(second));

  options.readCharacters = [](int variable) {
    return 1 + static_cast<int>(std::to_string(variable).size());
  };
  AllocationResult numbered = allocateVariables(function, options);
  ASSERT_TRUE(numbered.ok());
  // The move reads `sum` from a variable, and `#n=sum` is split again.
  EXPECT_TRUE(numbered.allocation.inVariable(sum));
  EXPECT_TRUE(numbered.allocation.inVariable(first) || numbered.allocation.inVariable(second));

  // A limit no split meets: the limit's error, not a loop.
  options.maximumInlineOperations = 6;
  AllocationResult impossible = allocateVariables(function, options);
  ASSERT_FALSE(impossible.ok());
  EXPECT_EQ(impossible.failures[0].limit, "inline operations");
}

} // namespace
} // namespace cncc::ir
