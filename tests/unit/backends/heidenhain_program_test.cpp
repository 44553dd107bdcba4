// The Heidenhain printer against the IR interpreter: a function with every
// operation the printer writes as jumps (min, max, select, floor, ceil,
// round, rem, atan2), loops, ifs with and/or, arcs and helices, printed as
// a TNC program, run on the virtual TNC with several parameter values
// edited into its FN 0 blocks, and compared move by move with the
// interpreter's run of the same values. Radius compensation printed as
// RR/R0 and run on the virtual TNC against the host's tool centre path. And
// the limits the printer names.
#include "cncc/backends/heidenhain_controller.h"
#include "cncc/backends/heidenhain_program.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/printer.h"
#include "cncc/ir/tool_centre_path.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace cncc::backends {
namespace {

using ::testing::HasSubstr;

constexpr const char* operations = R"(func @operations(a = 2.5, b = -1.25) {
  %a = param a
  %b = param b
  %zero = const 0
  %one = const 1
  %four = const 4
  %half = const 0.5
  %feed = const 100
  %i = loop %one, %four {
    %t = mul %i, %b
    %u = add %t, %a
    %m = min %u, %a
    %n = max %u, %half
    %f = floor %u
    %c = ceil %t
    %r = round %u
    %q = rem %u, %half
    %angle = atan2 %t, %u
    %gt = gt %u, %one
    %le = le %t, %b
    %both = and %gt, %le
    %s = select %both, %m, %n
    %x = add %s, %f
    %y = add %c, %r
    %w = add %q, %angle
    move.feed %x, %y, %w, %feed
    %either = or %gt, %le
    if %either {
      move.feed %y, %x, %zero, %feed
    } else {
      move.rapid %x, %x, %one
    }
  }
  %ten = const 10
  %centre = neg %a
  move.feed %ten, %zero, %zero, %feed
  move.arc ccw %ten, %zero, %b, %centre, %zero, %feed
  move.arc cw %ten, %zero, %b, %centre, %zero, %feed
}
)";

ir::Function parsed(const char* text) {
  ir::ParseError error;
  std::optional<ir::Function> function = ir::parseFunction(text, error);
  EXPECT_TRUE(function) << error.line << ": " << error.message;
  return function ? *function : ir::Function{};
}

std::vector<ir::MachineEvent> moves(const ir::ToolPath& path) {
  std::vector<ir::MachineEvent> result;
  for (const ir::MachineEvent& event : ir::flattenArcs(path, 1e-4).events) {
    // Rapids are left out: the TNC program splits them (Z first or last).
    if (event.kind == ir::MachineEvent::Kind::Feed) {
      result.push_back(event);
    }
  }
  return result;
}

void expectSameMoves(const ir::Function& function, const std::string& program, double a, double b,
                     const TncProfile& profile) {
  std::optional<std::string> edited = heidenhain::withEditedParameter(program, 1, a);
  ASSERT_TRUE(edited);
  edited = heidenhain::withEditedParameter(*edited, 2, b);
  ASSERT_TRUE(edited);
  heidenhain::TncRunOptions options;
  options.profile = profile;
  heidenhain::TncRun run = heidenhain::runTncProgram(*edited, options);
  ASSERT_FALSE(run.error) << run.error->line << ": " << run.error->message << "\n" << *edited;
  ir::Function withValues = function;
  withValues.parameters[0].defaultValue = a;
  withValues.parameters[1].defaultValue = b;
  std::vector<ir::MachineEvent> expected = moves(ir::interpret(withValues));
  std::vector<ir::MachineEvent> actual = moves(run.path);
  // The TNC's path starts where every axis is first known.
  ASSERT_GE(expected.size(), actual.size());
  expected.erase(expected.begin(), expected.end() - static_cast<std::ptrdiff_t>(actual.size()));
  for (std::size_t i = 0; i < actual.size(); ++i) {
    EXPECT_NEAR(actual[i].x, expected[i].x, 1e-4) << "move " << i << " a=" << a << " b=" << b;
    EXPECT_NEAR(actual[i].y, expected[i].y, 1e-4) << "move " << i;
    EXPECT_NEAR(actual[i].z, expected[i].z, 1e-4) << "move " << i;
  }
}

TEST(HeidenhainProgram, RunsAsTheInterpreterForEditedParameters) {
  ir::Function function = parsed(operations);
  for (const TncProfile& profile : builtinTncProfiles()) {
    HeidenhainProgramOptions options;
    options.partName = "operations";
    options.profile = profile;
    HeidenhainProgram program = writeHeidenhainProgram(function, options);
    ASSERT_TRUE(program.errors.empty()) << program.errors.front();
    EXPECT_THAT(program.text, HasSubstr("0 BEGIN PGM operations MM\n"));
    EXPECT_THAT(program.text, HasSubstr("FN 0: Q1 = +2.5\n"));
    EXPECT_THAT(program.text, HasSubstr(" DR+"));
    EXPECT_THAT(program.text, HasSubstr(" IZ"));
    EXPECT_THAT(program.text, HasSubstr(profile.name == "tnc640" ? "QL" : "Q16"));
    for (double a : {2.5, -3.75, 7.5}) {
      for (double b : {-1.25, 1.5, 0.0}) {
        expectSameMoves(function, program.text, a, b, profile);
      }
    }
  }
}

TEST(HeidenhainProgram, NumbersEveryBlockFromZero) {
  HeidenhainProgramOptions options;
  options.partName = "operations";
  HeidenhainProgram program = writeHeidenhainProgram(parsed(operations), options);
  ASSERT_TRUE(program.errors.empty());
  int expected = 0;
  std::size_t begin = 0;
  while (begin < program.text.size()) {
    EXPECT_EQ(program.text.compare(begin, std::to_string(expected).size() + 1,
                                   std::to_string(expected) + " "),
              0);
    ++expected;
    begin = program.text.find('\n', begin) + 1;
  }
  EXPECT_THAT(program.text, HasSubstr(std::to_string(expected - 1) + " END PGM operations MM\n"));
}

TEST(HeidenhainProgram, RefusesMorePartParametersThanTheProfileHas) {
  ir::Function function = parsed(operations);
  function.parameters.resize(60, ir::Parameter{"p", 1, false});
  HeidenhainProgramOptions options;
  HeidenhainProgram program = writeHeidenhainProgram(function, options);
  ASSERT_FALSE(program.errors.empty());
  EXPECT_THAT(program.errors.front(), HasSubstr("60 parameters"));
  EXPECT_THAT(program.errors.front(), HasSubstr("Q1-Q59"));
  EXPECT_TRUE(program.text.empty());
}

TEST(HeidenhainProgram, RefusesMoreLabelsThanTheControlHas) {
  HeidenhainProgramOptions options;
  options.profile.maximumLabel = 5;
  HeidenhainProgram program = writeHeidenhainProgram(parsed(operations), options);
  ASSERT_FALSE(program.errors.empty());
  EXPECT_THAT(program.errors.front(), HasSubstr("LBL 1-LBL 5"));
}

TEST(HeidenhainProgram, RefusesANumberBeyondTheControlsFormat) {
  ir::Function function = parsed(operations);
  function.parameters[0].defaultValue = 2e9;
  HeidenhainProgram program = writeHeidenhainProgram(function, {});
  ASSERT_FALSE(program.errors.empty());
  EXPECT_THAT(program.errors.front(), HasSubstr("999999999"));
}

// move.polynomial as SPL, a coefficient beyond 9.99999999 rescaled with
// an exponent word, run on the virtual TNC as the interpreter runs it.
TEST(HeidenhainProgram, PrintsPolynomialSpansAsSplineBlocks) {
  ir::Function function = parsed(R"(func @spans() {
  %zero = const 0
  %safe = const 5
  %feed = const 400
  %startX = const 130
  %depth = const -1
  %k3x = const 4
  %k2x = const -2.5
  %k1x = const 128.5
  %k3y = const 0.75
  %k2y = const -0.25
  %k1y = const -0.5
  move.rapid %startX, %zero, %safe
  move.feed %startX, %zero, %depth, %feed
  move.polynomial %zero, %zero, %depth, %k3x, %k2x, %k1x, %k3y, %k2y, %k1y, %zero, %zero, %zero, %feed
}
)");
  HeidenhainProgramOptions options;
  options.partName = "spans";
  HeidenhainProgram program = writeHeidenhainProgram(function, options);
  ASSERT_TRUE(program.errors.empty()) << program.errors.front();
  EXPECT_THAT(program.text, HasSubstr(" SPL X+0 Y+0 Z-1 K3X+4 K2X-2.5 K1X+1.285 E+2 K3Y+0.75 "
                                      "K2Y-0.25 K1Y-0.5 K3Z+0 K2Z+0 K1Z+0"));
  heidenhain::TncRun run = heidenhain::runTncProgram(program.text);
  ASSERT_FALSE(run.error) << run.error->message;
  std::vector<ir::MachineEvent> expected = moves(ir::interpret(function));
  std::vector<ir::MachineEvent> actual = moves(run.path);
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < actual.size(); ++i) {
    EXPECT_NEAR(actual[i].x, expected[i].x, 1e-9) << i;
    EXPECT_NEAR(actual[i].y, expected[i].y, 1e-9) << i;
  }
}

TEST(HeidenhainProgram, BlankSurroundsTheFeedMoves) {
  auto event = [](ir::MachineEvent::Kind kind, double x, double y, double z) {
    ir::MachineEvent made;
    made.kind = kind;
    made.x = x;
    made.y = y;
    made.z = z;
    return made;
  };
  ir::ToolPath path;
  path.events.push_back(event(ir::MachineEvent::Kind::Rapid, 50, 50, 10));
  path.events.push_back(event(ir::MachineEvent::Kind::Feed, 0, 0, -2));
  ir::MachineEvent circle = event(ir::MachineEvent::Kind::Arc, 0, 0, -2);
  circle.centreX = 5;
  path.events.push_back(circle);
  std::optional<HeidenhainBlank> blank = heidenhainBlank(path);
  ASSERT_TRUE(blank);
  EXPECT_NEAR(blank->minX, 0, 1e-9);
  // The arc in chords within 0.01 mm.
  EXPECT_NEAR(blank->maxX, 10, 0.011);
  EXPECT_NEAR(blank->minY, -5, 0.011);
  EXPECT_NEAR(blank->maxY, 5, 0.011);
  EXPECT_EQ(blank->minZ, -2);
  EXPECT_EQ(blank->maxZ, 0);
}

TEST(HeidenhainProgram, RadiusCompensationRunsAsTheHostOffsetsIt) {
  // Right of a line, a tangent arc (outside: radius 12), a line, and a
  // convex corner the TNC goes round on an arc, as the host's offset does;
  // register 3 is tool 3, whose R the tool table holds.
  ir::Function function = parsed(R"(func @compensated() {
  %zero = const 0
  %diameter = const 4
  %feed = const 100
  %below = const -10
  %ten = const 10
  %twenty = const 20
  %thirty = const 30
  tool 3 length 3, %diameter
  move.rapid %zero, %below, %zero
  compensation right 3 2
  move.feed %zero, %zero, %zero, %feed
  move.feed %twenty, %zero, %zero, %feed
  move.arc ccw %thirty, %ten, %zero, %zero, %ten, %feed
  move.feed %thirty, %twenty, %zero, %feed
  move.feed %ten, %twenty, %zero, %feed
  compensation off
  move.feed %ten, %thirty, %zero, %feed
}
)");
  HeidenhainProgramOptions options;
  options.partName = "compensated";
  HeidenhainProgram program = writeHeidenhainProgram(function, options);
  ASSERT_TRUE(program.errors.empty()) << program.errors.front();
  EXPECT_THAT(program.text, HasSubstr(" L Y+0 RR F100\n"));
  EXPECT_THAT(program.text, HasSubstr(" L Y+30 R0\n"));
  heidenhain::TncRunOptions run;
  run.toolRadii[3] = 2;
  heidenhain::TncRun executed = heidenhain::runTncProgram(program.text, run);
  ASSERT_FALSE(executed.error) << executed.error->line << ": " << executed.error->message << "\n"
                               << program.text;
  std::vector<ir::MachineEvent> expected = moves(ir::toolCentrePath(ir::interpret(function)));
  std::vector<ir::MachineEvent> actual = moves(executed.path);
  ASSERT_EQ(actual.size(), expected.size()) << program.text;
  for (std::size_t i = 0; i < actual.size(); ++i) {
    EXPECT_NEAR(actual[i].x, expected[i].x, 1e-9) << i;
    EXPECT_NEAR(actual[i].y, expected[i].y, 1e-9) << i;
  }
}

} // namespace
} // namespace cncc::backends
