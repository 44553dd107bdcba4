// The target registry: every target `-t` takes is described by its
// TargetInfo alone, so a part compiled through nothing but that description
// (lowering, printing, running its program) keeps the part's tolerances.
#include "target_compile.h"

#include "cncc/backends/machine_file.h"
#include "cncc/backends/verification.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <set>

namespace cncc::backends {
namespace {

TEST(TargetRegistry, DescribesEachTargetOnceAndCompletely) {
  std::set<std::string_view> names;
  for (const TargetInfo* target : allTargetInfos()) {
    SCOPED_TRACE(target->name);
    EXPECT_TRUE(names.insert(target->name).second);
    EXPECT_EQ(findTargetInfo(target->name), target);
    EXPECT_FALSE(target->description.empty());
    EXPECT_NE(target->lowering, nullptr);
    EXPECT_NE(target->print, nullptr);
    if (!target->controllerProfile.empty()) {
      EXPECT_NE(findControllerProfile(target->controllerProfile), nullptr);
    }
    // A machine file may name exactly the targets with a built-in set-up.
    EXPECT_EQ(isMachineTarget(target->name), !target->machineSetup.empty());
    if (!target->machineSetup.empty()) {
      EXPECT_EQ(builtinMachineSetup(target->machineSetup).dialect, target->machineSetup);
    }
  }
  EXPECT_EQ(findTargetInfo("no-such-target"), nullptr);
  EXPECT_EQ(targetNameList([](const TargetInfo& target) { return target.tncProfiles; }),
            "heidenhain");
}

// The example compiled for `target` as its TargetInfo says, its program
// run by the target's executor and measured against the part run on the host.
VerificationReport compileAndVerify(const TargetInfo& target, const std::string& example) {
  std::unique_ptr<testing::CheckedExample> checked = testing::checkExample(example);
  std::optional<testing::TargetCompilation> compiled =
      checked ? testing::compileThroughTarget(target, *checked) : std::nullopt;
  if (!compiled) {
    return {};
  }
  EXPECT_FALSE(compiled->printed.text.empty());
  frontend::DiagnosticEngine diagnostics;
  std::optional<ir::LoweredPart> reference =
      ir::lowerPartWithCuts(*checked->program, *checked->program->selectedPart, diagnostics);
  if (!reference) {
    ADD_FAILURE() << "the part does not lower for the host";
    return {};
  }
  ExecutionRequest execution;
  execution.text = compiled->printed.text;
  return verifyProgram({std::string(target.name), target.execute, std::move(execution),
                        executedPathOfToolPath(ir::interpret(reference->function)),
                        reference->function.cuts},
                       {});
}

TEST(TargetRegistry, EveryTargetCompilesThroughItsDescriptionAlone) {
  for (const TargetInfo* target : allTargetInfos()) {
    for (const char* example : {"s_profile.cdl", "bolt_circle.cdl"}) {
      SCOPED_TRACE(fmt::format("{} on {}", example, target->name));
      ASSERT_NE(target->execute, nullptr);
      VerificationReport report = compileAndVerify(*target, example);
      EXPECT_FALSE(report.failure) << report.failure->message;
      EXPECT_TRUE(report.passed());
      EXPECT_GT(report.blocks, 0U);
    }
  }
}

// A program that does not fit its controller is not printed: the problem
// names the limit.
TEST(TargetRegistry, AProgramThatDoesNotFitIsAProblemNamingTheLimit) {
  const TargetInfo& fanuc = *findTargetInfo("fanuc");
  std::unique_ptr<testing::CheckedExample> checked = testing::checkExample("s_profile.cdl");
  ASSERT_NE(checked, nullptr);
  const frontend::PartItem& part = *checked->program->selectedPart;
  TargetSettings settings = testing::defaultSettings(fanuc, part);
  ControllerProfile tiny = *findControllerProfile("fanuc");
  tiny.maximumProgramNumber = 10; // O1000 is past it
  settings.controllerProfile = &tiny;
  std::optional<ir::LoweredPart> lowered = ir::lowerPartWithCuts(
      *checked->program, part, checked->diagnostics, fanuc.lowering(settings));
  ASSERT_TRUE(lowered);
  PrintedProgram printed = fanuc.print({lowered->function, nullptr, settings});
  ASSERT_FALSE(printed.problems.empty());
  EXPECT_NE(printed.problems.front().find("the part does not fit the fanuc profile"),
            std::string::npos)
      << printed.problems.front();
}

} // namespace
} // namespace cncc::backends
