// The printed macro programs mean what the IR means: each program runs in a
// small evaluator (macro_evaluator.h) and its feed moves are compared with
// the IR interpreter's, for the examples this version lowers, both
// controllers, and the three ways of passing parameters.
#include "macro_evaluator.h"

#include "cncc/backends/controller_profile.h"
#include "cncc/backends/macro_program.h"
#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/passes.h"
#include "cncc/lowering/lowering.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

namespace cncc {
namespace {

std::optional<ir::Function> lowerExample(const std::string& name) {
  frontend::SourceManager sources;
  frontend::DiagnosticEngine diagnostics;
  std::optional<frontend::FileId> file =
      sources.loadFile(std::string(CNCC_SOURCE_DIR) + "/examples/" + name);
  if (!file) {
    ADD_FAILURE() << "cannot read " << name;
    return std::nullopt;
  }
  frontend::CheckOptions options;
  options.importPaths = {CNCC_STDLIB_DIR};
  options.requirePart = true;
  frontend::CheckedProgram program = frontend::checkProgram(sources, *file, options, diagnostics);
  if (diagnostics.hasErrors() || program.selectedPart == nullptr) {
    ADD_FAILURE() << name << " does not check";
    return std::nullopt;
  }
  return ir::lowerPart(program, *program.selectedPart, diagnostics);
}

// The program printed from the function as the macro targets give it to
// the printer (after their passes before printing); the function itself
// stays the reference.
backends::MacroProgram printedProgram(ir::Function function,
                                      const backends::ControllerProfile& profile,
                                      const backends::MacroProgramOptions& options) {
  EXPECT_TRUE(ir::runPasses(function, backends::macroPassesBeforePrinting(), {}));
  return backends::writeMacroProgram(function, profile, options);
}

std::vector<ir::MachineEvent> feedMoves(const ir::ToolPath& path) {
  std::vector<ir::MachineEvent> moves;
  for (const ir::MachineEvent& event : path.events) {
    if (event.kind == ir::MachineEvent::Kind::Feed) {
      moves.push_back(event);
    }
  }
  return moves;
}

// Literal coordinates have 3 decimals and constants 8 digits: the printed
// program may differ from the host by rounding, never by more.
void expectSameFeedMoves(const ir::ToolPath& expected, const testing::MacroEvaluation& actual,
                         const std::string& what) {
  ASSERT_TRUE(actual.error.empty()) << what << ": " << actual.error;
  std::vector<ir::MachineEvent> host = feedMoves(expected);
  std::vector<testing::EvaluatedMove> controller;
  for (const testing::EvaluatedMove& move : actual.moves) {
    if (!move.rapid) {
      controller.push_back(move);
    }
  }
  ASSERT_EQ(controller.size(), host.size()) << what;
  double worst = 0;
  for (std::size_t i = 0; i < host.size(); ++i) {
    worst = std::max({worst, std::abs(controller[i].x - host[i].x),
                      std::abs(controller[i].y - host[i].y), std::abs(controller[i].z - host[i].z),
                      std::abs(controller[i].feed - host[i].feed)});
  }
  EXPECT_LT(worst, 5e-4) << what;
}

struct Case {
  const char* example;
  const char* profile;
};

class MacroSemantics : public ::testing::TestWithParam<Case> {};

TEST_P(MacroSemantics, MainProgramRunsTheSamePathAsTheIr) {
  std::optional<ir::Function> function = lowerExample(GetParam().example);
  ASSERT_TRUE(function);
  const backends::ControllerProfile* profile = backends::findControllerProfile(GetParam().profile);
  ASSERT_NE(profile, nullptr);
  backends::MacroProgram program = printedProgram(*function, *profile, {});
  ASSERT_TRUE(program.errors.empty()) << program.errors.front();
  expectSameFeedMoves(ir::interpret(*function), testing::evaluateMacroProgram(program.text),
                      GetParam().example);
}

// A macro called with every parameter changed (G65 arguments land in
// #1, #2, ...) runs the path the IR runs for those values.
TEST_P(MacroSemantics, CallableMacroUsesItsArguments) {
  std::optional<ir::Function> function = lowerExample(GetParam().example);
  ASSERT_TRUE(function);
  const backends::ControllerProfile* profile = backends::findControllerProfile(GetParam().profile);
  backends::MacroProgramOptions options;
  options.callable = true;
  backends::MacroProgram program = printedProgram(*function, *profile, options);
  ASSERT_TRUE(program.errors.empty()) << program.errors.front();
  std::vector<std::string> problems;
  std::vector<int> locals =
      backends::macroParameterVariables(function->parameters.size(), *profile, false, problems);
  ir::InterpreterOptions changed;
  std::map<int, double> arguments;
  for (std::size_t i = 0; i < function->parameters.size(); ++i) {
    double value = function->parameters[i].defaultValue * 1.25 + 0.5;
    changed.parameters[function->parameters[i].name] = value;
    arguments[locals[i]] = value;
  }
  expectSameFeedMoves(ir::interpret(*function, changed),
                      testing::evaluateMacroProgram(program.text, arguments), GetParam().example);
}

TEST_P(MacroSemantics, ParametersInCommonTakeTheirDefaultsWhenVacant) {
  std::optional<ir::Function> function = lowerExample(GetParam().example);
  ASSERT_TRUE(function);
  const backends::ControllerProfile* profile = backends::findControllerProfile(GetParam().profile);
  backends::MacroProgramOptions options;
  options.parametersInCommon = true;
  backends::MacroProgram program = printedProgram(*function, *profile, options);
  ASSERT_TRUE(program.errors.empty()) << program.errors.front();
  expectSameFeedMoves(ir::interpret(*function), testing::evaluateMacroProgram(program.text),
                      GetParam().example);
}

INSTANTIATE_TEST_SUITE_P(Examples, MacroSemantics,
                         ::testing::Values(Case{"s_profile.cdl", "m80"},
                                           Case{"s_profile.cdl", "fanuc"},
                                           Case{"archimedean_spiral.cdl", "fanuc"},
                                           Case{"archimedean_spiral.cdl", "m80"},
                                           Case{"polar_contour.cdl", "fanuc"}));

TEST(MacroEvaluator, FollowsLoopsJumpsAndVacantVariables) {
  testing::MacroEvaluation evaluation = testing::evaluateMacroProgram(
      "%\nO1\nIF [#1 EQ #0] THEN #1=2.\n#2=0\nWHILE [#2 LE #1] DO1\nIF [#2 EQ 1.] GOTO 5\n"
      "G1 X#2 Y[#2*2.+1.] Z-SQRT[4.] F100.\nN5\n#2=#2+1.\nEND1\nM30\n%\n");
  ASSERT_TRUE(evaluation.error.empty()) << evaluation.error;
  ASSERT_EQ(evaluation.moves.size(), 2u); // #2 = 0 and 2; 1 is jumped over
  EXPECT_DOUBLE_EQ(evaluation.moves[1].x, 2);
  EXPECT_DOUBLE_EQ(evaluation.moves[1].y, 5);
  EXPECT_DOUBLE_EQ(evaluation.moves[1].z, -2);
}

} // namespace
} // namespace cncc
