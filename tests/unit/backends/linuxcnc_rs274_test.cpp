// Every example compiled for LinuxCNC and run by LinuxCNC's own interpreter
// (`rs274 -g`): the path it reports is measured against each cut's true
// curve. The moves are given their cuts by walking the IR interpreter's tool
// path in step with rs274's; every pass of every cut must stay within the
// cut's tolerance. rs274 prints four decimals, so the measurement allows
// for that rounding (half a unit of the last digit on each axis) and for
// nothing else. Without rs274 installed the tests fail (CNCC_FIND_RS274).
#include "linuxcnc_rs274.h"
#include "target_compile.h"

#include "cncc/backends/linuxcnc_canon.h"
#include "cncc/backends/linuxcnc_program.h"
#include "cncc/backends/macro_program.h"
#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/geom/deviation.h"
#include "cncc/ir/builder.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/verifier.h"
#include "cncc/lowering/lowering.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

namespace cncc {
namespace {

// Half a unit of rs274's fourth decimal on each of three axes.
const double printRounding = 0.5e-4 * std::sqrt(3.0);
// How far a point rs274 reports may lie from the host's: its rounding and
// the program's own (five decimals, twelve digits).
constexpr double matchDistance = 2e-4;

struct Compiled {
  std::unique_ptr<testing::CheckedExample> checked;
  std::optional<ir::LoweredPart> lowered; // after the target's passes
  ir::ToolPath path;                      // the final IR run
  std::string text;
  // The part as the host targets lower it, every loop unrolled: one true
  // curve for each cut the program makes (a controller loop makes one cut
  // statement cut many curves).
  std::optional<ir::LoweredPart> truth;
  ir::ToolPath truthPath;
};

// The example's part compiled as `cncc FILE -t linuxcnc [--macro]` does.
std::unique_ptr<Compiled> compile(const std::string& file, const std::string& part,
                                  const frontend::ParameterDefines& defines = {},
                                  bool callable = false) {
  auto result = std::make_unique<Compiled>();
  result->checked = testing::checkSource("examples/" + file, part, defines);
  if (!result->checked) {
    return nullptr;
  }
  const frontend::CheckedProgram& program = *result->checked->program;
  const backends::TargetInfo& linuxcnc = *backends::findTargetInfo("linuxcnc");
  backends::TargetSettings settings = testing::defaultSettings(linuxcnc, *program.selectedPart);
  settings.sourceName = file;
  settings.macroCall = callable;
  std::optional<testing::TargetCompilation> compiled =
      testing::compileThroughTarget(linuxcnc, *result->checked, settings);
  if (!compiled || !compiled->printed.problems.empty()) {
    return nullptr;
  }
  frontend::DiagnosticEngine diagnostics;
  result->truth = ir::lowerPartWithCuts(program, *program.selectedPart, diagnostics);
  if (!result->truth) {
    ADD_FAILURE() << file << " does not lower for the host";
    return nullptr;
  }
  result->truthPath = ir::interpret(result->truth->function);
  result->lowered = std::move(compiled->lowered);
  result->path = std::move(compiled->programmed);
  result->text = std::move(compiled->printed.text);
  return result;
}

// One pass: the feed moves between rapids within one cut.
struct Pass {
  std::size_t cut = 0;
  bool ramp = false;
  std::vector<Eigen::Vector3d> points;
};

// The host's feed moves, each with the pass it belongs to.
struct HostFeed {
  Eigen::Vector3d end;
  std::size_t pass = 0;
  bool arc = false; // rs274 reports an arc as chords on the way to its end
};

void hostPasses(const ir::ToolPath& path, std::vector<HostFeed>& feeds, std::vector<Pass>& passes) {
  std::optional<std::size_t> cut;
  bool newPass = true;
  for (const ir::MachineEvent& event : path.events) {
    switch (event.kind) {
    case ir::MachineEvent::Kind::CutBegin:
      cut = static_cast<std::size_t>(event.number);
      newPass = true;
      break;
    case ir::MachineEvent::Kind::Rapid:
      newPass = true;
      break;
    case ir::MachineEvent::Kind::Comment:
      if (event.text == "ramp" && !passes.empty()) {
        passes.back().ramp = true;
      }
      break;
    case ir::MachineEvent::Kind::Feed:
    case ir::MachineEvent::Kind::Arc:
      ASSERT_TRUE(cut.has_value()) << "a feed move outside every cut";
      if (newPass) {
        passes.push_back({*cut, false, {}});
        newPass = false;
      }
      feeds.push_back({{event.x, event.y, event.z},
                       passes.size() - 1,
                       event.kind == ir::MachineEvent::Kind::Arc});
      break;
    default:
      break;
    }
  }
}

// rs274's feed moves into the host's passes, in step: a host move rs274
// does not report must be one that goes nowhere (the program leaves out a
// line whose words are all in force).
void fillPasses(const backends::ExecutedPath& executed, const std::vector<HostFeed>& feeds,
                std::vector<Pass>& passes) {
  std::size_t next = 0;
  auto reaches = [&](const backends::ExecutedMove& move) {
    return (feeds[next].end - move.end).lpNorm<Eigen::Infinity>() <= matchDistance;
  };
  for (const backends::ExecutedMove& move : executed.moves) {
    if (move.rapid) {
      continue;
    }
    while (next < feeds.size() && !reaches(move) && !feeds[next].arc) {
      bool nowhere = next > 0 && (feeds[next].end - feeds[next - 1].end).norm() < 1e-9;
      ASSERT_TRUE(nowhere) << "rs274 has no move to (" << feeds[next].end.transpose()
                           << "); it reports (" << move.end.transpose() << ")";
      ++next;
    }
    ASSERT_LT(next, feeds.size()) << "rs274 reports a move the host does not make: ("
                                  << move.end.transpose() << ")";
    passes[feeds[next].pass].points.push_back(move.end);
    if (reaches(move)) {
      ++next; // else a chord of the arc on its way
    }
  }
  ASSERT_EQ(next, feeds.size()) << "rs274 stops before the host's path ends";
}

// A curve seen from above: its z set to 0.
class PlanView : public geom::Curve {
public:
  explicit PlanView(const geom::Curve& curve) : curve_(curve) {}
  geom::ParameterRange domain() const override { return curve_.domain(); }
  Eigen::Vector3d point(double t) const override { return flat(curve_.point(t)); }
  Eigen::Vector3d derivative(double t) const override { return flat(curve_.derivative(t)); }
  Eigen::Vector3d secondDerivative(double t) const override {
    return flat(curve_.secondDerivative(t));
  }
  std::vector<double> breakpoints() const override { return curve_.breakpoints(); }

private:
  static Eigen::Vector3d flat(Eigen::Vector3d v) {
    v.z() = 0;
    return v;
  }
  const geom::Curve& curve_;
};

// A pass runs at the curve's own z plus its depth (the plunge's offset
// from the curve's start); a ramped pass descends on purpose and is
// measured in plan.
double passDeviation(const Pass& pass, const geom::Curve& curve) {
  std::vector<Eigen::Vector3d> polyline = pass.points;
  double offset = polyline.front().z() - curve.point(curve.domain().t0).z();
  for (Eigen::Vector3d& point : polyline) {
    point.z() = pass.ramp ? 0 : point.z() - offset;
  }
  PlanView plan(curve);
  const geom::Curve& reference = pass.ramp ? static_cast<const geom::Curve&>(plan) : curve;
  return geom::measureDeviation(polyline, reference, {1e-6}).maxDeviation();
}

// Runs the program and checks every cut; `what` names the case.
// `host` is what the program does as the IR interpreter runs it; `truth`
// the part lowered for the host, whose passes (the same, in the same
// order) name the true curves.
void expectWithinTolerance(const ir::ToolPath& host, const Compiled& truth,
                           const std::string& program, const std::string& rs274,
                           const std::string& what) {
  const std::vector<ir::CutGeometry>& cuts = truth.truth->function.cuts;
  testing::Rs274Run run = testing::runRs274(rs274, program, testing::toolTableOf(host));
  ASSERT_EQ(run.exitCode, 0) << what << ": rs274 failed:\n" << run.errors << run.canon;
  backends::ExecutedPath executed;
  ASSERT_NO_THROW(executed = backends::readLinuxcncCanon(run.canon)) << what;
  std::vector<HostFeed> feeds, truthFeeds;
  std::vector<Pass> passes, truthPasses;
  ASSERT_NO_FATAL_FAILURE(hostPasses(host, feeds, passes));
  ASSERT_NO_FATAL_FAILURE(hostPasses(truth.truthPath, truthFeeds, truthPasses));
  ASSERT_EQ(passes.size(), truthPasses.size()) << what << ": the host cuts other passes";
  ASSERT_NO_FATAL_FAILURE(fillPasses(executed, feeds, passes)) << what;
  std::vector<double> worst(cuts.size(), 0);
  for (std::size_t i = 0; i < passes.size(); ++i) {
    Pass& pass = passes[i];
    pass.cut = truthPasses[i].cut;
    ASSERT_LT(pass.cut, cuts.size());
    ASSERT_FALSE(pass.points.empty());
    if (!std::isnan(cuts[pass.cut].tolerance)) {
      worst[pass.cut] = std::max(worst[pass.cut], passDeviation(pass, *cuts[pass.cut].curve));
    }
  }
  std::cout << what << ": " << executed.moves.size() << " moves from rs274, " << cuts.size()
            << " cuts\n";
  for (std::size_t k = 0; k < cuts.size(); ++k) {
    if (std::isnan(cuts[k].tolerance)) {
      continue; // samples= or spacing= chose the points; there is no promise
    }
    std::cout << "  cut " << k << ": deviation " << std::setprecision(6) << worst[k]
              << ", tolerance " << cuts[k].tolerance << "\n";
    EXPECT_LE(worst[k], cuts[k].tolerance + printRounding) << what << ", cut " << k;
  }
}

struct ExampleCase {
  std::string file;
  std::string part;
};

void PrintTo(const ExampleCase& example, std::ostream* out) {
  *out << example.file << (example.part.empty() ? "" : " -p ") << example.part;
}

class EveryExampleOnLinuxcnc : public ::testing::TestWithParam<ExampleCase> {};

TEST_P(EveryExampleOnLinuxcnc, Rs274RunsItWithinEveryCutsTolerance) {
  CNCC_FIND_RS274(rs274);
  std::unique_ptr<Compiled> compiled = compile(GetParam().file, GetParam().part);
  ASSERT_TRUE(compiled);
  expectWithinTolerance(compiled->path, *compiled, compiled->text, *rs274,
                        GetParam().file + " " + GetParam().part);
}

// The subroutine (--macro) of every example, called with the defaults as
// its arguments, cuts the same part.
TEST_P(EveryExampleOnLinuxcnc, Rs274RunsItsSubroutineCalledWithTheDefaults) {
  CNCC_FIND_RS274(rs274);
  std::unique_ptr<Compiled> compiled = compile(GetParam().file, GetParam().part, {}, true);
  ASSERT_TRUE(compiled);
  const std::string end = "\nM2\n";
  ASSERT_TRUE(compiled->text.ends_with(end));
  std::string program = compiled->text.substr(0, compiled->text.size() - end.size() + 1);
  std::string name(compiled->checked->program->selectedPart->name);
  std::transform(name.begin(), name.end(), name.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  program += "o<" + name + "> call";
  for (const ir::Parameter& parameter : compiled->lowered->function.parameters) {
    std::ostringstream value;
    value << std::fixed << std::setprecision(12) << parameter.defaultValue;
    program += " [" + value.str() + "]";
  }
  program += "\nM2\n";
  expectWithinTolerance(compiled->path, *compiled, program, *rs274,
                        GetParam().file + " " + GetParam().part + " --macro");
}

INSTANTIATE_TEST_SUITE_P(
    Examples, EveryExampleOnLinuxcnc,
    ::testing::Values(ExampleCase{"archimedean_spiral.cdl", ""}, ExampleCase{"bolt_circle.cdl", ""},
                      ExampleCase{"cam_profile.cdl", ""},
                      ExampleCase{"helix_bore.cdl", "bore_plate_mm"},
                      ExampleCase{"helix_bore.cdl", "bore_plate_inch"},
                      ExampleCase{"polar_contour.cdl", ""}, ExampleCase{"rosette_plate.cdl", ""},
                      ExampleCase{"s_profile.cdl", ""}),
    [](const ::testing::TestParamInfo<ExampleCase>& info) {
      std::string name = info.param.part.empty() ? info.param.file : info.param.part;
      return name.substr(0, name.find('.'));
    });

// A parameter set at the top of the program to another value: rs274 runs
// the part that value makes, within its tolerance. The host runs the same
// IR with the new value; the true curves are the part lowered with it.
struct EditCase {
  std::string file;
  std::string parameter;
  double value;
};

void PrintTo(const EditCase& edit, std::ostream* out) {
  *out << edit.file << " " << edit.parameter << "=" << edit.value;
}

class EditedParameterOnLinuxcnc : public ::testing::TestWithParam<EditCase> {};

TEST_P(EditedParameterOnLinuxcnc, Rs274RunsTheEditedPartWithinTolerance) {
  CNCC_FIND_RS274(rs274);
  const EditCase& edit = GetParam();
  std::unique_ptr<Compiled> compiled = compile(edit.file, "");
  ASSERT_TRUE(compiled);
  const ir::Function& function = compiled->lowered->function;
  std::size_t index = 0;
  while (index < function.parameters.size() && function.parameters[index].name != edit.parameter) {
    ++index;
  }
  ASSERT_LT(index, function.parameters.size()) << edit.parameter;
  std::string name = backends::linuxcncParameterNames(function.parameters)[index];
  std::string line = "#<" + name + "> = ";
  std::size_t at = compiled->text.find("\n" + line);
  ASSERT_NE(at, std::string::npos) << "no line sets " << line;
  std::size_t end = compiled->text.find('\n', at + 1);
  std::string edited = compiled->text.substr(0, at + 1) + line + std::to_string(edit.value) +
                       compiled->text.substr(end);
  ir::InterpreterOptions values;
  values.parameters[edit.parameter] = edit.value;
  ir::ToolPath host = ir::interpret(function, values);
  std::unique_ptr<Compiled> reference = compile(edit.file, "", {{edit.parameter, edit.value}});
  ASSERT_TRUE(reference);
  // The edit changes the path: the parameter is read by the program.
  std::vector<HostFeed> before, after;
  std::vector<Pass> unused;
  hostPasses(compiled->path, before, unused);
  unused.clear();
  hostPasses(host, after, unused);
  bool changed = before.size() != after.size();
  for (std::size_t i = 0; !changed && i < before.size(); ++i) {
    changed = (before[i].end - after[i].end).norm() > 1e-6;
  }
  EXPECT_TRUE(changed) << edit.parameter << " = " << edit.value << " moves nothing";
  expectWithinTolerance(host, *reference, edited, *rs274,
                        edit.file + " " + edit.parameter + "=" + std::to_string(edit.value));
}

INSTANTIATE_TEST_SUITE_P(
    Examples, EditedParameterOnLinuxcnc,
    ::testing::Values(
        EditCase{"archimedean_spiral.cdl", "a", 2}, EditCase{"bolt_circle.cdl", "holes", 5},
        EditCase{"bolt_circle.cdl", "hole", 12}, EditCase{"archimedean_spiral.cdl", "b", 1.5},
        EditCase{"s_profile.cdl", "w6", 2}, EditCase{"s_profile.cdl", "w6", 8},
        EditCase{"s_profile.cdl", "depth", 5}, EditCase{"s_profile.cdl", "step", 1.5},
        EditCase{"polar_contour.cdl", "depth", 4}, EditCase{"rosette_plate.cdl", "petals", 8},
        EditCase{"rosette_plate.cdl", "holes", 3}, EditCase{"rosette_plate.cdl", "finish", 0}),
    [](const ::testing::TestParamInfo<EditCase>& info) {
      std::string name = info.param.file;
      return name.substr(0, name.find('.')) + "_" + info.param.parameter + "_" +
             std::to_string(info.index);
    });

// The circle of radius r, 72 chords, at depth d: both parameters are read
// where the moves are computed.
ir::Function circle() {
  ir::FunctionBuilder builder("circle");
  ir::ValueId radius = builder.parameter(builder.addParameter("r", 5));
  ir::ValueId depth = builder.parameter(builder.addParameter("d", 1));
  builder.tool(1, builder.constant(6));
  ir::ValueId zero = builder.constant(0);
  ir::ValueId z = builder.unary(ir::Opcode::Neg, depth);
  builder.rapid(radius, zero, builder.constant(5));
  ir::ValueId index = builder.beginLoop(builder.constant(0), builder.constant(72));
  ir::ValueId angle = builder.binary(ir::Opcode::Mul, index, builder.constant(M_PI / 36));
  builder.feed(builder.binary(ir::Opcode::Mul, radius, builder.unary(ir::Opcode::Cos, angle)),
               builder.binary(ir::Opcode::Mul, radius, builder.unary(ir::Opcode::Sin, angle)), z,
               builder.constant(200));
  builder.endLoop();
  return builder.finish();
}

// `text` with its first `from` replaced by `to` (unchanged without one).
std::string replaceOnce(std::string text, const std::string& from, const std::string& to) {
  std::size_t at = text.find(from);
  if (at != std::string::npos) {
    text.replace(at, from.size(), to);
  }
  return text;
}

// The program keeps its parameters symbolic: editing the line that sets
// one at the top changes the path rs274 runs.
TEST(LinuxcncOnRs274, EditingAParameterAtTheTopChangesThePart) {
  CNCC_FIND_RS274(rs274);
  backends::LinuxcncProgram program = backends::writeLinuxcncProgram(circle(), {});
  ASSERT_TRUE(program.errors.empty());
  std::string edited = replaceOnce(program.text, "#<_r> = 5.\n", "#<_r> = 7.5\n");
  edited = replaceOnce(edited, "#<_d> = 1.\n", "#<_d> = 2.\n");
  ASSERT_NE(edited, program.text);
  testing::Rs274Run run =
      testing::runRs274(*rs274, edited, testing::toolTableOf(ir::interpret(circle())));
  ASSERT_EQ(run.exitCode, 0) << run.errors;
  backends::ExecutedPath path = backends::readLinuxcncCanon(run.canon);
  int feeds = 0;
  for (const backends::ExecutedMove& move : path.moves) {
    if (!move.rapid) {
      ++feeds;
      EXPECT_NEAR(move.end.head<2>().norm(), 7.5, 1e-4);
      EXPECT_EQ(move.end.z(), -2);
    }
  }
  EXPECT_EQ(feeds, 73);
}

// A macro is a subroutine: called with arguments, it cuts what they say.
TEST(LinuxcncOnRs274, TheSubroutineTakesTheParametersAsArguments) {
  CNCC_FIND_RS274(rs274);
  backends::LinuxcncProgramOptions options;
  options.partName = "circle";
  options.callable = true;
  backends::LinuxcncProgram program = backends::writeLinuxcncProgram(circle(), options);
  ASSERT_TRUE(program.errors.empty());
  // The subroutine and a main program calling it, in one file.
  ASSERT_TRUE(program.text.ends_with("\nM2\n"));
  std::string text = program.text.substr(0, program.text.size() - 3);
  text += "o<circle> call [3] [0.5]\nM2\n";
  testing::Rs274Run run =
      testing::runRs274(*rs274, text, testing::toolTableOf(ir::interpret(circle())));
  ASSERT_EQ(run.exitCode, 0) << run.errors;
  backends::ExecutedPath path = backends::readLinuxcncCanon(run.canon);
  int feeds = 0;
  for (const backends::ExecutedMove& move : path.moves) {
    if (!move.rapid) {
      ++feeds;
      EXPECT_NEAR(move.end.head<2>().norm(), 3, 1e-4);
      EXPECT_EQ(move.end.z(), -0.5);
    }
  }
  EXPECT_EQ(feeds, 73);
}

} // namespace
} // namespace cncc
