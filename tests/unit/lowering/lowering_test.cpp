#include "cncc/lowering/lowering.h"

#include "cncc/frontend/sema.h"
#include "cncc/frontend/source_manager.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/printer.h"
#include "cncc/ir/verifier.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <string>

namespace cncc::ir {
namespace {

struct Lowering {
  frontend::SourceManager sources;
  frontend::DiagnosticEngine diagnostics;
  std::optional<frontend::CheckedProgram> program;
  std::optional<Function> function;
};

std::unique_ptr<Lowering> lower(const std::string& text, const LoweringOptions& lowering = {}) {
  auto result = std::make_unique<Lowering>();
  frontend::FileId file = result->sources.addFile("test.cdl", text);
  frontend::CheckOptions options;
  options.importPaths = {CNCC_STDLIB_DIR};
  options.requirePart = true;
  result->program = frontend::checkProgram(result->sources, file, options, result->diagnostics);
  EXPECT_FALSE(result->diagnostics.hasErrors());
  if (result->program->selectedPart != nullptr) {
    result->function =
        lowerPart(*result->program, *result->program->selectedPart, result->diagnostics, lowering);
  }
  return result;
}

std::vector<MachineEvent> feeds(const ToolPath& path) {
  std::vector<MachineEvent> result;
  for (const MachineEvent& event : path.events) {
    if (event.kind == MachineEvent::Kind::Feed) {
      result.push_back(event);
    }
  }
  return result;
}

TEST(Lowering, PolarCircleLiesOnTheCurveAndFollowsItsParameter) {
  auto lowered = lower("part p(r0 = 10) {\n  units mm\n  tool 1 diameter=2 spindle=1000 feed=200\n"
                       "  safe z=3\n  curve polar(r = r0, t = 0 .. 2*pi) tolerance=0.01\n}\n");
  ASSERT_TRUE(lowered->function);
  EXPECT_TRUE(verifyFunction(*lowered->function).empty());
  ToolPath path = interpret(*lowered->function);
  std::vector<MachineEvent> moves = feeds(path);
  ASSERT_GT(moves.size(), 10u);
  for (const MachineEvent& move : moves) {
    EXPECT_NEAR(std::hypot(move.x, move.y), 10.0, 1e-9);
    EXPECT_EQ(move.z, 0.0);
    EXPECT_EQ(move.feed, 200.0);
  }
  // The IR computes the radius from the parameter: another value moves the path.
  InterpreterOptions options;
  options.parameters["r0"] = 12;
  for (const MachineEvent& move : feeds(interpret(*lowered->function, options))) {
    EXPECT_NEAR(std::hypot(move.x, move.y), 12.0, 1e-9);
  }
  // The work offset first (the program's header names the part), a rapid
  // to the safe height last, then contouring off and Z to the machine's
  // reference.
  EXPECT_EQ(path.events.front().kind, MachineEvent::Kind::Origin);
  ASSERT_GE(path.events.size(), 3u);
  const MachineEvent& lastMove = path.events[path.events.size() - 3];
  EXPECT_EQ(lastMove.kind, MachineEvent::Kind::Rapid);
  EXPECT_EQ(lastMove.z, 3.0);
  EXPECT_EQ(path.events[path.events.size() - 2].kind, MachineEvent::Kind::Contouring);
  EXPECT_EQ(path.events[path.events.size() - 2].number, 0.0);
  EXPECT_EQ(path.events.back().kind, MachineEvent::Kind::Home);
  // The printed IR parses back to the same text.
  std::string text = printFunction(*lowered->function);
  ParseError error;
  std::optional<Function> parsed = parseFunction(text, error);
  ASSERT_TRUE(parsed) << error.message;
  EXPECT_EQ(printFunction(*parsed), text);
}

TEST(Lowering, SweepPassesEndExactlyAtTheDepth) {
  auto lowered = lower("part p {\n  tool 1 diameter=2 feed=100\n  safe z=2\n"
                       "  curve line((0, 0), (10, 5)) sweep depth=2.5 step=1\n}\n");
  ASSERT_TRUE(lowered->function);
  EXPECT_TRUE(verifyFunction(*lowered->function).empty());
  std::vector<double> depths;
  for (const MachineEvent& move : feeds(interpret(*lowered->function))) {
    if (depths.empty() || depths.back() != move.z) {
      depths.push_back(move.z);
    }
  }
  EXPECT_EQ(depths, (std::vector<double>{-1, -2, -2.5}));
}

TEST(Lowering, NurbsSpansUseHornerAndStayOnTheCurve) {
  auto lowered = lower("part p(w = 2) {\n  tool 1 diameter=2 feed=100\n  safe z=2\n"
                       "  curve nurbs(degree=2, points=[(0,0), (10,10), (20,0), (30,10)], "
                       "weights=[1, w, 1, 1]) tolerance=0.01\n}\n");
  ASSERT_TRUE(lowered->function);
  EXPECT_TRUE(verifyFunction(*lowered->function).empty());
  std::string text = printFunction(*lowered->function);
  EXPECT_NE(text.find("table @1"), std::string::npos) << "one table per span";
  std::vector<MachineEvent> moves = feeds(interpret(*lowered->function));
  ASSERT_GT(moves.size(), 3u);
  EXPECT_NEAR(moves.front().x, 0, 1e-12);
  EXPECT_NEAR(moves.back().x, 30, 1e-9);
  EXPECT_NEAR(moves.back().y, 10, 1e-9);
}

TEST(Lowering, UnsupportedConstructIsAnErrorAtItsSpan) {
  auto lowered = lower("part p {\n  tool 1 diameter=2 feed=100\n  safe z=2\n"
                       "  curve line((0, 0), (10, 0)) sweep depth=2 step=1 entry=ramp\n}\n");
  EXPECT_FALSE(lowered->function);
  ASSERT_TRUE(lowered->diagnostics.hasErrors());
  const frontend::Diagnostic& diagnostic = lowered->diagnostics.diagnostics().back();
  EXPECT_NE(diagnostic.message.find("not supported by this version's lowering"), std::string::npos);
  EXPECT_TRUE(diagnostic.span.valid());
}

// The last diagnostic's kind and the text its span covers.
std::pair<frontend::DiagnosticKind, std::string> lastDiagnostic(const Lowering& lowered,
                                                                const std::string& text) {
  if (lowered.diagnostics.diagnostics().empty()) {
    return {};
  }
  const frontend::Diagnostic& diagnostic = lowered.diagnostics.diagnostics().back();
  return {diagnostic.kind,
          text.substr(diagnostic.span.begin, diagnostic.span.end - diagnostic.span.begin)};
}

TEST(Lowering, FeedsAndSpindleSpeedsWithinTheMachinesMaximum) {
  LoweringOptions machine;
  machine.maximumFeed = 5000;
  machine.maximumSpindleSpeed = 10000;
  auto part = [](const std::string& tool, const std::string& cut) {
    return "part p(f = 400) {\n  tool 1 diameter=6 " + tool +
           "\n  safe z=2\n  curve line((0, 0), (10, 0)) sweep depth=1 step=1 " + cut + "\n}\n";
  };
  EXPECT_TRUE(lower(part("spindle=10000 feed=5000", "feed=f"), machine)->function);
  for (auto [tool, cut, over] : std::vector<std::tuple<std::string, std::string, std::string>>{
           {"spindle=12000 feed=300", "", "12000"},
           {"spindle=8000 feed=300", "feed=6000", "6000"},
           {"spindle=8000 feed=2*f*10", "", "2*f*10"}}) {
    std::string text = part(tool, cut);
    auto lowered = lower(text, machine);
    EXPECT_FALSE(lowered->function) << text;
    auto [kind, quoted] = lastDiagnostic(*lowered, text);
    EXPECT_EQ(kind, frontend::DiagnosticKind::MachineLimit) << text;
    EXPECT_EQ(quoted, over);
  }
  // In an inch part the maximum feed is the machine's in inch/min.
  EXPECT_FALSE(lower("part p {\n  units inch\n  tool 1 diameter=0.25 feed=200\n  safe z=0.1\n"
                     "  curve line((0, 0), (1, 0)) sweep depth=0.1 step=0.1\n}\n",
                     machine)
                   ->function);
}

TEST(Lowering, RampOnAnOpenCurveIsRefused) {
  auto lowered = lower("part p {\n  tool 1 diameter=2 feed=100\n  safe z=2\n"
                       "  curve line((0, 0), (10, 5)) sweep depth=2 step=1 entry=ramp\n}\n");
  EXPECT_FALSE(lowered->function);
  EXPECT_TRUE(lowered->diagnostics.hasErrors());
}

} // namespace
} // namespace cncc::ir
