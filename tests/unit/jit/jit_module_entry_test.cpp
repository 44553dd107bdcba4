// The entry point of the loadable JIT module: the tool path, or the error's
// kind and its text, as the driver reports them.
#include "jit_test_support.h"

#include "cncc/backends/jit_module.h"
#include "cncc/ir/builder.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace cncc {
namespace {

using backends::JitModuleStatus;
using ir::FunctionBuilder;
using ir::ValueId;

// Moves to the element of table {10, 20, 30} at the parameter `index`.
ir::Function tableReader(double defaultIndex) {
  FunctionBuilder builder("table");
  std::uint32_t table = builder.addTable({10, 20, 30});
  std::uint32_t index = builder.addParameter("index", defaultIndex);
  ValueId zero = builder.constant(0);
  ValueId element = builder.tableLoad(table, builder.parameter(index));
  builder.feed(element, zero, zero, builder.constant(100));
  return builder.finish();
}

TEST(JitModuleEntry, IsLookedUpUnderItsName) {
  EXPECT_STREQ(backends::jitModuleEntryName, "cncc_jit_module_run_v1");
}

TEST(JitModuleEntry, RunsTheFunctionWithItsDefaults) {
  ir::Function function = tableReader(2);
  ir::ToolPath path;
  std::string error;
  ASSERT_EQ(cncc_jit_module_run_v1(function, path, error), JitModuleStatus::Ran) << error;
  ASSERT_EQ(path.events.size(), 1u);
  EXPECT_EQ(path.events[0].x, 30);
  EXPECT_TRUE(jit_test::samePaths(ir::interpret(function), path));
}

TEST(JitModuleEntry, RunErrorHasTheInterpretersMessage) {
  ir::Function function = tableReader(7);
  ir::ToolPath path;
  std::string error;
  EXPECT_EQ(cncc_jit_module_run_v1(function, path, error), JitModuleStatus::RunError);
  jit_test::RunOutcome interpreted = jit_test::outcomeOf([&] { return ir::interpret(function); });
  ASSERT_TRUE(interpreted.failed);
  EXPECT_EQ(error, interpreted.error);
}

TEST(JitModuleEntry, FunctionThatDoesNotVerifyIsACompileError) {
  FunctionBuilder builder("broken");
  ValueId zero = builder.constant(0);
  builder.rapid(zero, zero, zero);
  ir::Function function = builder.finish();
  function.instructions.back().operands.pop_back();
  ir::ToolPath path;
  std::string error;
  EXPECT_EQ(cncc_jit_module_run_v1(function, path, error), JitModuleStatus::CompileError);
  EXPECT_THAT(error, ::testing::StartsWith("the IR does not verify"));
}

} // namespace
} // namespace cncc
