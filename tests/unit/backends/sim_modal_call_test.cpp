// G66 modal macro calls and the modal information #4001-#4120 on the
// virtual controller.
#include "cncc/backends/controller_profile.h"
#include "cncc/backends/virtual_controller.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

namespace cncc::backends::sim {
namespace {

using ::testing::HasSubstr;

SimulationResult run(const std::string& main, const std::string& macros = "") {
  return simulateProgram("%\nO1000\n" + main + "M30\n" + macros + "%\n",
                         *findControllerProfile("fanuc"));
}

double common(const SimulationResult& result, int variable) {
  if (result.error) {
    ADD_FAILURE() << result.error->line() << ": " << result.error->what();
    return 0;
  }
  return result.commonVariables.at(variable).value_or(-1);
}

std::string errorOf(const SimulationResult& result) {
  return result.error ? std::string(result.error->what()) : std::string("no error");
}

const std::string spotMacro = "O9000\n#100 = #100 + 1\nG91 G01 Z-#1\nG00 Z#1\nG90\nM99\n";

TEST(SimModalCall, EveryMoveCallsTheMacroUntilG67) {
  SimulationResult result = run(
      "#100 = 0\nG90 G00 X0. Y0. Z10. F100.\nG66 P9000 A2.\nX10.\nY10.\nG67\nX30.\n", spotMacro);
  EXPECT_EQ(common(result, 100), 2);
  // After the second call: its spot at (10, 10), then X30 with no call.
  const auto& events = result.path.events;
  ASSERT_GE(events.size(), 3u);
  EXPECT_DOUBLE_EQ(events[events.size() - 2].end.z, 10);
  EXPECT_DOUBLE_EQ(events[events.size() - 3].end.z, 8);
  EXPECT_DOUBLE_EQ(events.back().end.x, 30);
}

TEST(SimModalCall, BlocksWithoutAMoveAndTheMacrosOwnMovesDoNotCall) {
  SimulationResult result = run(
      "#100 = 0\nG90 G00 X0. Y0. Z10. F100.\nG66 P9000 A2.\n#1 = 5\nM08\nX5.\nG67\n", spotMacro);
  EXPECT_EQ(common(result, 100), 1);
  EXPECT_THAT(errorOf(run("G66 G00 P9000 A1.\n", spotMacro)),
              HasSubstr("G66 must be the only G code"));
}

TEST(SimModalInformation, MacrosSaveAndRestoreTheModes) {
  SimulationResult result = run("G90 G01 X0. Y0. F250.\n"
                                "G91\n"
                                "#100 = #4003\n"
                                "#101 = #4001\n"
                                "#102 = #4109\n"
                                "G90\n"
                                "G#100\n" // back to G91 the way macros restore it
                                "#103 = #4003\n"
                                "#104 = #4007 + #4008 + #4009 + #4016 + #4017\n");
  EXPECT_EQ(common(result, 100), 91);
  EXPECT_EQ(common(result, 101), 1);
  EXPECT_EQ(common(result, 102), 250);
  EXPECT_EQ(common(result, 103), 91);
  EXPECT_EQ(common(result, 104), 40 + 49 + 80 + 69 + 15);
}

TEST(SimModalInformation, WhatWasNeverCommandedIsRefused) {
  EXPECT_THAT(errorOf(run("#100 = #4001\n")), HasSubstr("G00, G01, G02 or G03 has not been"));
  EXPECT_THAT(errorOf(run("#100 = #4120\n")), HasSubstr("T has not been commanded"));
  EXPECT_THAT(errorOf(run("#100 = #4014\n")), HasSubstr("#4014 is not simulated"));
}

} // namespace
} // namespace cncc::backends::sim
