// The pass registry, running passes by name, and the default pipeline.
#include "cncc/ir/interpreter.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/printer.h"
#include "cncc/ir/verifier.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace cncc::ir {
namespace {

using ::testing::ElementsAre;

Function parsed(std::string_view text) {
  ParseError error;
  std::optional<Function> function = parseFunction(text, error);
  EXPECT_TRUE(function) << error.line << ": " << error.message;
  return function ? *function : Function{};
}

constexpr std::string_view smallFunction = R"(func @f(x = 1) {
  %x = param x
  %one = const 1
  %two = add %one, %one
  %again = add %one, %one
  %unused = mul %x, %again
  move.rapid %x, %two, %again
}
)";

TEST(PassesPipelineTest, EveryPassHasAStableNameAndIsFound) {
  std::vector<std::string_view> names;
  for (const Pass& pass : allPasses()) {
    names.push_back(pass.name);
    EXPECT_EQ(findPass(pass.name), &pass);
    EXPECT_FALSE(pass.description.empty());
  }
  EXPECT_THAT(names,
              ElementsAre("unroll-host-control", "choose-curve-blocks", "choose-controller-steps",
                          "split-arc-laps", "bound-controller-steps", "write-curve-blocks",
                          "fit-arcs", "expand-controller-loops", "expand-curve-laps", "fold", "cse",
                          "licm", "unroll", "unroll-no-larger", "dce", "drop-pass-depths",
                          "expand-whole-powers", "fold-finite"));
  EXPECT_EQ(findPass("inline"), nullptr);
  for (std::string_view name : defaultPipeline()) {
    EXPECT_NE(findPass(name), nullptr) << name;
  }
}

TEST(PassesPipelineTest, RunPassesCallsBackAfterEachPassInOrder) {
  Function function = parsed(smallFunction);
  std::vector<std::string> seen;
  std::vector<std::string> names = {"fold", "cse", "dce"};
  ASSERT_TRUE(runPasses(function, names, [&](std::string_view name, const Function& after) {
    seen.emplace_back(name);
    EXPECT_TRUE(verifyFunction(after).empty());
  }));
  EXPECT_THAT(seen, ElementsAre("fold", "cse", "dce"));
  EXPECT_EQ(printFunction(function), "func @f(x = 1) {\n"
                                     "  %0 = param x\n"
                                     "  %1 = const 2\n"
                                     "  move.rapid %0, %1, %1\n"
                                     "}\n");
}

TEST(PassesPipelineTest, UnknownNameRunsNothing) {
  Function function = parsed(smallFunction);
  std::string before = printFunction(function);
  std::string unknown;
  std::vector<std::string> names = {"fold", "vectorise"};
  EXPECT_FALSE(runPasses(function, names, {}, &unknown));
  EXPECT_EQ(unknown, "vectorise");
  EXPECT_EQ(printFunction(function), before);
}

TEST(PassesPipelineTest, DefaultPipelineReachesAFixedPoint) {
  Function function = parsed(smallFunction);
  runDefaultPipeline(function);
  std::string once = printFunction(function);
  EXPECT_EQ(instructionCount(function), 3u);
  for (const Pass& pass : allPasses()) {
    EXPECT_FALSE(pass.run(function)) << pass.name << " still changes the result";
  }
  EXPECT_EQ(printFunction(function), once);
}

// A loop whose variable advances by a step it computes: no pass unrolls it
// (its trip count is known only by running it) or moves its loop.next, and
// the path is the same after every pass.
TEST(PassesPipelineTest, AnAdvancingLoopKeepsItsPathThroughEveryPass) {
  Function function = parsed(R"(func @advance(step = 0.25) {
  %0 = const 0
  %1 = const 1
  %2 = param step
  %3 = loop %0, %1 {
    %4 = mul %2, %1
    %5 = add %3, %4
    %6 = min %5, %1
    move.feed %6, %4, %0, %1
    loop.next %6
  }
}
)");
  std::vector<MachineEvent> before = interpret(function).events;
  ASSERT_EQ(before.size(), 4u);
  std::vector<std::string> names;
  for (const Pass& pass : allPasses()) {
    names.emplace_back(pass.name);
  }
  ASSERT_TRUE(runPasses(function, names, [&](std::string_view name, const Function& after) {
    EXPECT_TRUE(verifyFunction(after).empty()) << name;
    std::vector<MachineEvent> events = interpret(after).events;
    ASSERT_EQ(events.size(), before.size()) << name;
    for (std::size_t i = 0; i < events.size(); ++i) {
      EXPECT_EQ(events[i].x, before[i].x) << name;
    }
  }));
  std::string text = printFunction(function);
  EXPECT_NE(text.find("loop.next"), std::string::npos) << text;
  EXPECT_EQ(text.find("move.feed"), text.rfind("move.feed")) << "not unrolled: " << text;
}

} // namespace
} // namespace cncc::ir
