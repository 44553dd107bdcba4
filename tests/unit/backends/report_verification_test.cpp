// cncc verify's library: macro programs run on the virtual controller with
// the parameters set as the operator sets them, the executed path matched
// to the reference's cuts and measured, operations counted per point; each
// target's executor (its TargetInfo).
#include "cncc/backends/controller_profile.h"
#include "cncc/backends/macro_program.h"
#include "cncc/backends/program_execution.h"
#include "cncc/backends/rs274.h"
#include "cncc/backends/sim_operation_count.h"
#include "cncc/backends/target_info.h"
#include "cncc/backends/tool_path_csv.h"
#include "cncc/backends/verification.h"
#include "cncc/geom/line_arc_curves.h"
#include "cncc/ir/builder.h"
#include "cncc/ir/interpreter.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>

namespace cncc::backends {
namespace {

using ir::Opcode;
using ir::ValueId;
using ::testing::HasSubstr;

constexpr double kDepth = 1;

// A circle of radius `radius` (a parameter) around the origin in 36 chords
// of 10 degrees, one cut, at depth 1.
ir::Function circle(double radius) {
  ir::FunctionBuilder builder("circle");
  ValueId r = builder.parameter(builder.addParameter("r", radius));
  ValueId zero = builder.constant(0);
  ValueId z = builder.constant(-kDepth);
  builder.tool(1, builder.constant(6));
  builder.spindle(builder.constant(2000));
  builder.rapid(r, zero, builder.constant(5));
  builder.cutBegin(0);
  builder.feed(r, zero, z, builder.constant(250));
  ValueId index = builder.beginLoop(builder.constant(1), builder.constant(36));
  ValueId angle = builder.binary(Opcode::Mul, index, builder.constant(std::numbers::pi / 18));
  ValueId x = builder.binary(Opcode::Mul, r, builder.unary(Opcode::Cos, angle));
  ValueId y = builder.binary(Opcode::Mul, r, builder.unary(Opcode::Sin, angle));
  builder.feed(x, y, z, builder.constant(250));
  builder.endLoop();
  builder.rapid(r, zero, builder.constant(5));
  return builder.finish();
}

// 36 chords of a circle of radius r sag by r (1 - cos 5 degrees).
double chordSagitta(double radius) {
  return radius * (1 - std::cos(std::numbers::pi / 36));
}

std::string macroText(const ir::Function& function, std::string_view profile,
                      const MacroProgramOptions& options = {}) {
  MacroProgram program = writeMacroProgram(function, *findControllerProfile(profile), options);
  EXPECT_TRUE(program.errors.empty());
  return program.text;
}

// The part's cuts and the host's run of it, with radius `radius`.
struct Reference {
  std::vector<ir::CutGeometry> cuts;
  ExecutedPath path;
};

Reference reference(double radius, double tolerance) {
  Reference result;
  ir::CutGeometry cut;
  cut.curve =
      std::make_shared<geom::ArcCurve>(Eigen::Vector2d(0, 0), radius, 0.0, 2 * std::numbers::pi);
  cut.tolerance = tolerance;
  result.cuts.push_back(cut);
  result.path = executedPathOfToolPath(ir::interpret(circle(radius)));
  return result;
}

VerificationReport verify(std::string_view target, ExecutionRequest execution,
                          const Reference& part) {
  return verifyProgram({std::string(target), findTargetInfo(target)->execute, std::move(execution),
                        part.path, part.cuts},
                       {});
}

TEST(Verification, PassesAMacroProgramWithinItsTolerance) {
  Reference part = reference(5, 0.025);
  ExecutionRequest execution;
  execution.text = macroText(circle(5), "fanuc");
  VerificationReport report = verify("fanuc", execution, part);
  ASSERT_FALSE(report.failure) << report.failure->message;
  EXPECT_TRUE(report.passed()) << formatVerification(report, {});
  ASSERT_EQ(report.statistics.cuts.size(), 1u);
  // The chords' sagitta, give or take the 0.001 mm the controller rounds to.
  EXPECT_NEAR(report.statistics.cuts[0].maxDeviation, chordSagitta(5), 0.001);
  EXPECT_EQ(report.statistics.cuts[0].feedMoves, 37u); // the plunge and 36 chords
  EXPECT_EQ(report.stray.count, 0u);
  EXPECT_TRUE(report.missedCuts.empty());
  EXPECT_EQ(report.blocks, countProgramBlocks(execution.text));
  EXPECT_LT(report.bytesWithoutComments, report.bytes);
  ASSERT_TRUE(report.operations);
  EXPECT_EQ(report.operations->feedMoves, 36u);
  // Per point: the loop test (37 tests for 36 points), the index step.
  EXPECT_GT(report.operations->perFeedMove(&sim::OperationCounts::comparisons), 1.0);
  EXPECT_LT(report.operations->perFeedMove(&sim::OperationCounts::comparisons), 1.1);
  EXPECT_GE(report.operations->perFeedMove(&sim::OperationCounts::functions), 2.0);
  EXPECT_GE(report.operations->perFeedMove(&sim::OperationCounts::assignments), 1.0);
  std::string text = formatVerification(report, {});
  EXPECT_THAT(text, HasSubstr("target: fanuc\n"));
  EXPECT_THAT(text, HasSubstr("operations per point: "));
  EXPECT_THAT(text, HasSubstr("tolerance 0.025 mm, within"));
  EXPECT_THAT(text, HasSubstr("verdict: PASSED\n"));
}

TEST(Verification, FailsACutBeyondItsTolerance) {
  Reference part = reference(5, 0.015);
  ExecutionRequest execution;
  execution.text = macroText(circle(5), "m80");
  VerificationReport report = verify("m80", execution, part);
  ASSERT_FALSE(report.failure);
  EXPECT_FALSE(report.passed());
  EXPECT_FALSE(report.statistics.cuts[0].withinTolerance());
  EXPECT_THAT(formatVerification(report, {}), HasSubstr("EXCEEDED"));
  EXPECT_THAT(formatVerification(report, {}), HasSubstr("verdict: FAILED\n"));
}

// The program is written for r = 5 and given r = 6 on the controller.
TEST(Verification, SetsParametersAsTheOperatorDoes) {
  Reference part = reference(6, 0.03);
  ExecutionRequest execution;
  execution.text = macroText(circle(5), "fanuc");
  execution.passing = ParameterPassing::EditedDefaults;
  execution.parameters = {{"r", 1, 6.0}};
  VerificationReport report = verify("fanuc", execution, part);
  ASSERT_FALSE(report.failure) << report.failure->message;
  EXPECT_TRUE(report.passed()) << formatVerification(report, {});
  EXPECT_NEAR(report.statistics.cuts[0].maxDeviation, chordSagitta(6), 0.001);

  MacroProgramOptions callable;
  callable.callable = true;
  execution.text = macroText(circle(5), "fanuc", callable);
  execution.passing = ParameterPassing::MacroArguments;
  execution.callable = true;
  report = verify("fanuc", execution, part);
  ASSERT_FALSE(report.failure) << report.failure->message;
  EXPECT_TRUE(report.passed()) << formatVerification(report, {});

  MacroProgramOptions common;
  common.parametersInCommon = true;
  execution.text = macroText(circle(5), "m80", common);
  execution.passing = ParameterPassing::CommonVariables;
  execution.callable = false;
  execution.parameters = {{"r", 500, 6.0}};
  report = verify("m80", execution, part);
  ASSERT_FALSE(report.failure) << report.failure->message;
  EXPECT_TRUE(report.passed()) << formatVerification(report, {});
}

TEST(Verification, FailsAProgramThatCutsSomethingElse) {
  // Run with the default r = 5 while the part asks for r = 6: every chord
  // is 1 mm off the reference path.
  Reference part = reference(6, 0.03);
  ExecutionRequest execution;
  execution.text = macroText(circle(5), "fanuc");
  VerificationReport report = verify("fanuc", execution, part);
  ASSERT_FALSE(report.failure);
  EXPECT_FALSE(report.passed());
  EXPECT_GT(report.stray.count, 30u);
  EXPECT_NEAR(report.stray.largestDistance, 1.0, 0.05);
  EXPECT_THAT(formatVerification(report, {}), HasSubstr("feed moves are off the part's path"));
}

TEST(Verification, ReportsAMissingParameterLine) {
  Reference part = reference(6, 0.03);
  ExecutionRequest execution;
  execution.text = macroText(circle(5), "fanuc");
  execution.passing = ParameterPassing::EditedDefaults;
  execution.parameters = {{"r", 7, 6.0}}; // the program has no `#7=`
  VerificationReport report = verify("fanuc", execution, part);
  ASSERT_TRUE(report.failure);
  EXPECT_THAT(report.failure->message, HasSubstr("#7"));
  EXPECT_FALSE(report.passed());
}

TEST(Verification, NamesTheLineTheControllerRefuses) {
  Reference part = reference(5, 0.03);
  ExecutionRequest execution;
  execution.text = "%\nO1000\nG0 X0. Y0. Z5.\n#1=1./0\nG1 X#1 F100.\nM30\n%\n";
  VerificationReport report = verify("fanuc", execution, part);
  ASSERT_TRUE(report.failure);
  EXPECT_EQ(report.failure->line, 4);
  EXPECT_FALSE(report.passed());
  std::string text = formatVerification(report, {});
  EXPECT_THAT(text, HasSubstr("the controller stopped the program: line 4: "));
  EXPECT_THAT(text, HasSubstr("verdict: FAILED\n"));
}

TEST(Verification, MissesACutTheProgramDoesNotCut) {
  Reference part = reference(5, 0.03);
  ExecutionRequest execution;
  execution.text = "%\nO1000\nG0 X5. Y0. Z5.\nM30\n%\n";
  VerificationReport report = verify("fanuc", execution, part);
  ASSERT_FALSE(report.failure);
  EXPECT_EQ(report.missedCuts.size(), 1u);
  EXPECT_FALSE(report.passed());
  EXPECT_THAT(formatVerification(report, {}), HasSubstr("NOT CUT"));
}

// Two cuts at the same depth over the same place (overlapping pockets): the
// first cut's chords run nearer to the second cut's line than to its own,
// yet within its allowance, so they stay with the first cut.
TEST(CutAssignment, KeepsMovesWithTheCurrentCutWhereALaterCutOverlapsIt) {
  auto feedTo = [](ExecutedPath& path, double x, double y, std::optional<std::size_t> cut) {
    path.moves.push_back({false, Eigen::Vector3d(x, y, -1), 100, cut});
  };
  auto rapidTo = [](ExecutedPath& path, double x, double y) {
    path.moves.push_back({true, Eigen::Vector3d(x, y, -1), 0, std::nullopt});
  };
  ExecutedPath reference;
  reference.start = Eigen::Vector3d(0, 0, -1);
  feedTo(reference, 20, 0, 0); // cut 0: (0, 0) to (20, 0)
  rapidTo(reference, 5, 0.004);
  feedTo(reference, 15, 0.004, 1); // cut 1: just beside cut 0's middle
  feedTo(reference, 15, 5, 1);
  ExecutedPath executed;
  executed.start = reference.start;
  feedTo(executed, 5, 0.004, std::nullopt);
  feedTo(executed, 15, 0.004, std::nullopt); // on cut 1's line, 0.004 from cut 0
  feedTo(executed, 20, 0, std::nullopt);
  rapidTo(executed, 15, 0.004);
  feedTo(executed, 15, 5, std::nullopt);
  StrayMoves stray = assignCuts(executed, reference, {0.01, 0.01}, 0.002);
  EXPECT_EQ(stray.count, 0u);
  std::vector<std::optional<std::size_t>> cuts;
  for (const ExecutedMove& move : executed.moves) {
    cuts.push_back(move.cut);
  }
  std::vector<std::optional<std::size_t>> expected = {0, 0, 0, std::nullopt, 1};
  EXPECT_EQ(cuts, expected);
}

// A cut whose path passes its own end earlier (a plunge down a line that a
// rising loop comes back to, as onto a rising helix), then a cut that plunges
// down the same line to that end and starts with a move shorter than the
// allowance. Nearest points alone put the second plunge and first move on the
// first cut's plunge line, before its end; followed in order, the first cut is
// finished when the second's plunge starts.
TEST(CutAssignment, GivesTheNextCutAPlungeThroughTheFinishedCutsPath) {
  auto moveTo = [](ExecutedPath& path, bool rapid, Eigen::Vector3d end,
                   std::optional<std::size_t> cut) {
    path.moves.push_back({rapid, end, rapid ? 0.0 : 100.0, cut});
  };
  std::vector<std::pair<Eigen::Vector3d, std::optional<std::size_t>>> feeds = {
      {{2, 0, -3}, 0}, {{2, 2, -2.5}, 0}, {{0, 2, -2}, 0},     {{0, 0, -1.5}, 0}, {{2, 0, -1}, 0},
      {{2, 0, 3}, {}}, {{2, 0, -1}, 1},   {{2.005, 0, -1}, 1}, {{6, 0, -1}, 1}};
  ExecutedPath reference;
  ExecutedPath executed;
  reference.start = executed.start = Eigen::Vector3d(2, 0, 3);
  std::vector<std::optional<std::size_t>> expected;
  for (const auto& [end, cut] : feeds) {
    bool rapid = !cut;
    moveTo(reference, rapid, end, cut);
    moveTo(executed, rapid, end, std::nullopt);
    expected.push_back(cut);
  }
  StrayMoves stray = assignCuts(executed, reference, {0.01, 0.01}, 0.002);
  EXPECT_EQ(stray.count, 0u);
  std::vector<std::optional<std::size_t>> cuts;
  for (const ExecutedMove& move : executed.moves) {
    cuts.push_back(move.cut);
  }
  EXPECT_EQ(cuts, expected);
}

TEST(Verification, ReadsTheJitTargetsToolPathBack) {
  Reference part = reference(5, 0.025);
  ExecutionRequest execution;
  execution.text = writeToolPathCsv(ir::interpret(circle(5)));
  VerificationReport report = verify("jit", execution, part);
  ASSERT_FALSE(report.failure);
  EXPECT_TRUE(report.passed()) << formatVerification(report, {});
  EXPECT_NEAR(report.statistics.cuts[0].maxDeviation, chordSagitta(5), 1e-5);
  EXPECT_FALSE(report.operations);

  execution.text = "x,y,z,feed,rapid\n1,2,3\n";
  report = verify("jit", execution, part);
  ASSERT_TRUE(report.failure);
  EXPECT_EQ(report.failure->line, 2);
}

TEST(Verification, HasAnExecutorForEachTargetItRuns) {
  for (std::string_view target :
       {"m80", "fanuc", "gcode", "jit", "sinumerik", "linuxcnc", "heidenhain"}) {
    const TargetInfo* info = findTargetInfo(target);
    ASSERT_NE(info, nullptr) << target;
    EXPECT_EQ(info->name, target);
    EXPECT_NE(info->execute, nullptr) << target;
  }
  EXPECT_EQ(findTargetInfo("no-such-target"), nullptr);
  EXPECT_THROW(verifyProgram({"no-such-target", nullptr, {}, {}, {}}, {}), std::invalid_argument);
}

// Sets an environment variable while it lives, then restores it.
class ScopedEnvironment {
public:
  ScopedEnvironment(const char* name, const std::string& value) : name_(name) {
    const char* old = std::getenv(name);
    if (old != nullptr) {
      old_ = old;
    }
    setenv(name, value.c_str(), 1);
  }
  ~ScopedEnvironment() {
    if (old_) {
      setenv(name_, old_->c_str(), 1);
    } else {
      unsetenv(name_);
    }
  }
  ScopedEnvironment(const ScopedEnvironment&) = delete;
  ScopedEnvironment& operator=(const ScopedEnvironment&) = delete;

private:
  const char* name_;
  std::optional<std::string> old_;
};

// A Python that cannot import LinuxCNC's module: Debian's without its site
// packages (a script in a fresh directory, removed with it).
class PythonWithoutTheModule {
public:
  PythonWithoutTheModule() {
    std::string pattern = (std::filesystem::temp_directory_path() / "cncc-python-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) {
      throw std::runtime_error("cannot create " + pattern);
    }
    directory_ = pattern;
    std::ofstream(path()) << "#!/bin/sh\nexec /usr/bin/python3 -S \"$@\"\n";
    std::filesystem::permissions(path(), std::filesystem::perms::owner_all);
  }
  ~PythonWithoutTheModule() { std::filesystem::remove_all(directory_); }
  PythonWithoutTheModule(const PythonWithoutTheModule&) = delete;
  PythonWithoutTheModule& operator=(const PythonWithoutTheModule&) = delete;

  std::string path() const { return (directory_ / "python3").string(); }

private:
  std::filesystem::path directory_;
};

// A plunge and a line run by `executor`, for the LinuxCNC runs below; it
// must run.
ProgramExecution plungeAndLineOn(const TargetInfo& executor, ExecutionRequest& request) {
  request.text = "G21 G90\nT3 M6\nG0 X0 Y0 Z1\nG1 Z-1 F100\nG1 X10 Y5\nM2\n";
  ProgramExecution run = executor.execute(request);
  EXPECT_FALSE(run.failure) << run.failure->message;
  return run;
}

// A LinuxCNC program runs in LinuxCNC's interpreter, its Python module:
// its feed moves are the path, read within the program's own 5 decimals,
// and a program it refuses is a failure at its line.
TEST(Verification, LinuxcncProgramsRunInLinuxcncsInterpreter) {
  const TargetInfo* linuxcnc = findTargetInfo("linuxcnc");
  ASSERT_NE(linuxcnc, nullptr);
  ExecutionRequest request;
  ProgramExecution run = plungeAndLineOn(*linuxcnc, request);
  EXPECT_TRUE(run.notes.empty());
  ASSERT_FALSE(run.path.moves.empty());
  EXPECT_NEAR(run.path.moves.back().end.x(), 10, 1e-9);
  EXPECT_NEAR(run.path.moves.back().end.y(), 5, 1e-9);
  EXPECT_EQ(run.increment, 1e-5);
  request.text = "G21\nG1 X1 Y1\nM2\n"; // a feed move without a feed rate
  run = linuxcnc->execute(request);
  ASSERT_TRUE(run.failure);
  EXPECT_EQ(run.failure->message.rfind("LinuxCNC's interpreter: ", 0), 0u) << run.failure->message;
  EXPECT_EQ(run.failure->line, 2);
  EXPECT_EQ(run.failure->lineText, "G1 X1 Y1");
}

// Where the Python cannot import the module, the program runs in rs274,
// and the output says so; a program rs274 refuses is a failure that
// quotes rs274.
TEST(Verification, LinuxcncProgramsRunInRs274WithoutTheModule) {
  PythonWithoutTheModule python;
  ScopedEnvironment chosen("CNCC_LINUXCNC_PYTHON", python.path());
  const TargetInfo* linuxcnc = findTargetInfo("linuxcnc");
  ASSERT_NE(linuxcnc, nullptr);
  ExecutionRequest request;
  ProgramExecution run = plungeAndLineOn(*linuxcnc, request);
  ASSERT_EQ(run.notes.size(), 1u);
  EXPECT_THAT(run.notes[0], HasSubstr("No module named 'gcode'"));
  EXPECT_THAT(run.notes[0], HasSubstr("read from rs274, which prints 4 decimals"));
  EXPECT_NEAR(run.path.moves.back().end.x(), 10, 1e-9);
  EXPECT_EQ(run.increment, 1e-4);
  request.text = "G21\nG1 X1 Y1\nM2\n";
  run = linuxcnc->execute(request);
  ASSERT_TRUE(run.failure);
  EXPECT_EQ(run.failure->message.rfind("rs274: ", 0), 0u) << run.failure->message;
}

// 36 chords of a circle whose sagitta, 0.00999 mm, is just within the
// tolerance of 0.01 mm, every coordinate to 15 decimals: read at full
// precision the deviation is the sagitta. The radius ends in 0.000049, so
// that rs274's four decimals move the chords' ends on the axes 0.000049 mm
// in, and read the deviation as past the tolerance.
TEST(Verification, LinuxcncReadsTheInterpretersDoubles) {
  double radius = 2.625349;
  double sagitta = radius * (1 - std::cos(std::numbers::pi / 36));
  ASSERT_NEAR(sagitta, 0.00999, 1e-6);
  Reference part = reference(radius, 0.01);
  ExecutionRequest execution;
  execution.text =
      fmt::format("G21 G90\nT1 M6\nS2000 M3\nG0 X{0:.15f} Y0 Z5\nG1 Z-1 F250\n", radius);
  for (int k = 1; k <= 36; ++k) {
    double angle = k * std::numbers::pi / 18;
    execution.text +=
        fmt::format("G1 X{:.15f} Y{:.15f}\n", radius * std::cos(angle), radius * std::sin(angle));
  }
  execution.text += fmt::format("G0 X{:.15f} Y0 Z5\nM2\n", radius);
  VerificationReport module = verify("linuxcnc", execution, part);
  ASSERT_FALSE(module.failure) << module.failure->message;
  EXPECT_TRUE(module.notes.empty());
  EXPECT_NEAR(module.statistics.cuts[0].maxDeviation, sagitta, 1e-9);
  EXPECT_TRUE(module.passed()) << formatVerification(module, {});

  PythonWithoutTheModule python;
  ScopedEnvironment chosen("CNCC_LINUXCNC_PYTHON", python.path());
  VerificationReport rs274 = verify("linuxcnc", execution, part);
  ASSERT_FALSE(rs274.failure) << rs274.failure->message;
  EXPECT_GT(rs274.statistics.cuts[0].maxDeviation, 0.01);
  EXPECT_FALSE(rs274.passed());
  EXPECT_THAT(
      formatVerification(rs274, {}),
      HasSubstr("note: " + python.path() + " cannot import LinuxCNC's Python module gcode"));
}

// rs274 runs G41/G42 and reports the tool centre's moves; the diameter of
// `G41 D<n>` comes from the request's radii, and what rs274 refuses (an
// entry move not longer than the radius) fails the run.
TEST(Verification, LinuxcncCompensationRunsInRs274) {
  const TargetInfo* linuxcnc = findTargetInfo("linuxcnc");
  ASSERT_NE(linuxcnc, nullptr);
  ExecutionRequest request;
  request.text = "G21 G90\nT1 M6\nG0 X0 Y-10 Z0\nG1 X0 Y-10 F100\nG42 D7 X0 Y0\nG1 X10\n"
                 "G40 G1 X10 Y-10\nM2\n";
  request.toolRadii = {{7, 2}};
  ProgramExecution run = linuxcnc->execute(request);
  ASSERT_FALSE(run.failure) << run.failure->message;
  // Right of +X by 2 from (0, 0) to (10, 0), then the cancel move.
  bool offsetSide = false;
  for (const ExecutedMove& move : run.path.moves) {
    offsetSide |= std::abs(move.end.x() - 10) < 1e-9 && std::abs(move.end.y() + 2) < 1e-9;
  }
  EXPECT_TRUE(offsetSide);
  request.text = "G21 G90\nT1 M6\nG0 X0 Y-1 Z0\nG1 X0 Y-1 F100\nG42.1 D4 X0 Y0\nG1 X10\n"
                 "G40 G1 X10 Y-10\nM2\n";
  run = linuxcnc->execute(request);
  ASSERT_TRUE(run.failure);
  EXPECT_NE(run.failure->message.find("entry move is not greater than the tool radius"),
            std::string::npos)
      << run.failure->message;
}

TEST(Rs274, ToolTableHasEveryToolTheProgramNames) {
  EXPECT_EQ(rs274ToolTable("T1 M6\n(T9 IN A COMMENT)\nG0 X1\nt12 m6\nM2\n"),
            "T1 P1 D0 ;\nT12 P12 D0 ;\n");
}

TEST(Rs274, ToolTableHoldsTheCompensationDiametersInInches) {
  // `G41 D21` reads entry 21, which the program names nowhere else; rs274
  // keeps the table in inches whatever the program's units.
  EXPECT_EQ(rs274ToolTable("T1 M6\nG42 D21 X1\n", {{21, 3 * 25.4}}), "T1 P1 D0 ;\nT21 P21 D6 ;\n");
  EXPECT_EQ(rs274ToolTable("G20\nT2 M6\n", {{2, 0.25}}, true), "T2 P2 D0.5 ;\n");
}

TEST(OperationCounts, CountsEachKindOfOperationInABlock) {
  const ControllerProfile& fanuc = *findControllerProfile("fanuc");
  sim::ProgramText program =
      sim::readProgram("%\nO1\n#3=[#1+2.]*SIN[#2]-#[100+#4]\nIF [#3 GT 1.] THEN #5=-#3\n"
                       "G1 X[#1/2.] Y#2 F100.\nM30\n%\n",
                       fanuc);
  auto counts = [&](int line) {
    for (const sim::Block& block : program.blocks) {
      if (block.line == line) {
        return sim::countBlockOperations(block);
      }
    }
    ADD_FAILURE() << "no line " << line;
    return sim::OperationCounts{};
  };
  sim::OperationCounts assignment = counts(3);
  EXPECT_EQ(assignment.arithmetic, 4u); // + * - and the index's +
  EXPECT_EQ(assignment.functions, 1u);
  EXPECT_EQ(assignment.comparisons, 0u);
  EXPECT_EQ(assignment.assignments, 1u);
  sim::OperationCounts ifThen = counts(4);
  EXPECT_EQ(ifThen.comparisons, 1u);
  EXPECT_EQ(ifThen.arithmetic, 1u); // the negation
  EXPECT_EQ(ifThen.assignments, 1u);
  sim::OperationCounts words = counts(5);
  EXPECT_EQ(words.arithmetic, 1u);
  EXPECT_EQ(words.assignments, 0u);
}

} // namespace
} // namespace cncc::backends
