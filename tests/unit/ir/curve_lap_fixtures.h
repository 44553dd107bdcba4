// What the curve.lap tests share: two functions as text (a circle lap, a
// path of two pieces), parsing them, and reading their paths.
#pragma once

#include "cncc/geom/line_arc_curves.h"
#include "cncc/ir/builder.h"
#include "cncc/ir/curve_lap.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/ir.h"
#include "cncc/ir/printer.h"
#include "cncc/ir/verifier.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <string_view>
#include <vector>

namespace cncc::ir::curve_lap_test {
inline constexpr double pi = std::numbers::pi;

// A circle of radius r (a parameter) about the origin, one lap at z = -1.
inline constexpr std::string_view circleText = R"(func @circle(r = 5) {
  curve @0 chords 0.01 over 0 .. 6.283185307179586 {
    piece at 0 over 0 .. 6.283185307179586
  }
  %0 = param r
  %1 = const 500
  %2 = const -1
  %3 = const 0
  move.rapid %0, %3, %3
  %4 = curve.lap @0, %2, %2, %1 {
    %5 = cos %4
    %6 = mul %0, %5
    %7 = sin %4
    %8 = mul %0, %7
    curve.point %6, %8, %3
  }
}
)";

// A line along x from 0 to 13: a piece over 0 .. 10, then a NURBS-like
// piece of three knot spans, each its own region at u in [0, 1]; a ramp
// lap from z = 0 down to z = -1 by eight points at equal parameter steps.
inline constexpr std::string_view pathText = R"(func @path() {
  table @0 = [0.5, 1.5]
  curve @0 samples 8 over 0 .. 13 {
    piece at 0 over 0 .. 10
    piece at 10 over 0 .. 3 spans 0 .. 1, 1 .. 2, 2 .. 3
    host 1, 3
  }
  curve @1 spacing 0.25 over -1 .. 1e+300 {
    piece at 0 over -1 .. 1e+300
    progress 0.25 share 0.5
    numbers
    chosen -1, 0.1, 1e+300
  }
  %0 = const 0
  %1 = const -1
  %2 = const 100
  %3 = curve.lap @0, %0, %1, %2 {
    curve.point %3, %0, %0
  } piece {
    %4 = const 10
    %5 = add %4, %3
    curve.point %5, %0, %0
  } piece {
    %6 = const 11
    %7 = add %6, %3
    curve.point %7, %0, %0
  } piece {
    %8 = const 12
    %9 = add %8, %3
    curve.point %9, %0, %0
  }
}
)";

inline Function parsed(std::string_view text) {
  ParseError error;
  std::optional<Function> function = parseFunction(text, error);
  EXPECT_TRUE(function) << error.line << ": " << error.message;
  return function ? std::move(*function) : Function{};
}

// The parser's complaint, as "line: message".
inline std::string parseComplaint(std::string_view text) {
  ParseError error;
  if (parseFunction(text, error)) {
    return "parsed";
  }
  return std::to_string(error.line) + ": " + error.message;
}

inline const Instruction& onlyLap(const Function& function) {
  for (const Instruction& instruction : function.instructions) {
    if (instruction.opcode == Opcode::CurveLap) {
      return instruction;
    }
  }
  ADD_FAILURE() << "no curve.lap";
  return function.instructions.front();
}

inline std::size_t countOf(const Function& function, Opcode opcode) {
  std::size_t count = 0;
  for (const Instruction& instruction : function.instructions) {
    count += instruction.opcode == opcode ? 1 : 0;
  }
  return count;
}

inline std::vector<MachineEvent> feedMoves(const ToolPath& path) {
  std::vector<MachineEvent> moves;
  for (const MachineEvent& event : path.events) {
    if (event.kind == MachineEvent::Kind::Feed) {
      moves.push_back(event);
    }
  }
  return moves;
}

inline void expectSamePath(const ToolPath& expected, const ToolPath& actual) {
  ASSERT_EQ(expected.events.size(), actual.events.size());
  for (std::size_t k = 0; k < expected.events.size(); ++k) {
    const MachineEvent& a = expected.events[k];
    const MachineEvent& b = actual.events[k];
    EXPECT_EQ(a.kind, b.kind) << k;
    EXPECT_EQ(a.x, b.x) << k;
    EXPECT_EQ(a.y, b.y) << k;
    EXPECT_EQ(a.z, b.z) << k;
    EXPECT_EQ(a.feed, b.feed) << k;
  }
}

// The feed and arc moves of a path.
inline std::vector<MachineEvent> movesOf(const ToolPath& path) {
  std::vector<MachineEvent> moves;
  for (const MachineEvent& event : path.events) {
    if (event.kind == MachineEvent::Kind::Feed || event.kind == MachineEvent::Kind::Arc) {
      moves.push_back(event);
    }
  }
  return moves;
}

// The same moves, bit for bit, arcs' centres and turns included.
inline void expectSameMoves(const ToolPath& expected, const ToolPath& actual) {
  std::vector<MachineEvent> a = movesOf(expected);
  std::vector<MachineEvent> b = movesOf(actual);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].kind, b[k].kind) << k;
    EXPECT_EQ(a[k].x, b[k].x) << k;
    EXPECT_EQ(a[k].y, b[k].y) << k;
    EXPECT_EQ(a[k].z, b[k].z) << k;
    EXPECT_EQ(a[k].centreX, b[k].centreX) << k;
    EXPECT_EQ(a[k].centreY, b[k].centreY) << k;
    EXPECT_EQ(a[k].clockwise, b[k].clockwise) << k;
  }
}

// A function cut in steps before and after expand-controller-loops: the
// same moves; the path after.
inline ToolPath expandedPath(Function& function, const InterpreterOptions& options = {}) {
  ToolPath before = interpret(function, options);
  EXPECT_TRUE(expandControllerLoops(function));
  EXPECT_TRUE(verifyFunction(function).empty());
  EXPECT_EQ(countOf(function, Opcode::CurveLap), 0u);
  ToolPath after = interpret(function, options);
  expectSameMoves(before, after);
  return after;
}

inline std::string replaced(std::string_view text, std::string_view from, std::string_view to) {
  std::string result(text);
  std::size_t at = result.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) {
    result.replace(at, from.size(), to);
  }
  return result;
}

// A function read from `text` (which it prints back) and verified, run,
// rewritten by a legalisation `pass` (which must change it, leaving no
// curve.lap and a function that verifies) and run again: the same path.
struct PassRun {
  Function function;
  ToolPath before; // the path before the pass
};
inline PassRun runThroughPass(std::string_view text, bool (*pass)(Function&)) {
  PassRun run{parsed(text), {}};
  EXPECT_EQ(printFunction(run.function), text);
  EXPECT_TRUE(verifyFunction(run.function).empty());
  run.before = interpret(run.function);
  EXPECT_TRUE(pass(run.function));
  EXPECT_TRUE(verifyFunction(run.function).empty());
  EXPECT_EQ(countOf(run.function, Opcode::CurveLap), 0u);
  expectSamePath(run.before, interpret(run.function));
  return run;
}

// The CurveLapError a legalisation `pass` throws on `function` (which
// verifies); a failure when it throws none.
inline CurveLapError passError(Function function, bool (*pass)(Function&)) {
  EXPECT_TRUE(verifyFunction(function).empty());
  try {
    pass(function);
  } catch (const CurveLapError& error) {
    return error;
  }
  ADD_FAILURE() << "the pass ran";
  return CurveLapError(CurveLapError::Kind::DegenerateCurve, {}, "none");
}

inline CurveLapError passError(std::string_view text, bool (*pass)(Function&)) {
  return passError(parsed(text), pass);
}

// The function of circleText's kind with its curve's geometry, the circle
// of radius 5 itself (as the lowering gives it): a search over it asks
// points of the circle, not of its region interpreted at each.
inline Function withCircleGeometry(Function function) {
  function.curves[0].geometry =
      std::make_shared<geom::ArcCurve>(Eigen::Vector2d(0, 0), 5.0, 0.0, 2 * pi);
  return function;
}

// The circle of radius r (its default 5) as blocks the pass fits: `sampling`
// within 0.001, on the grid 0.0001, no table; its curve is its region
// interpreted at r's default (IR read from text has no geometry).
inline std::string circleAsFittedBlocks(std::string_view sampling) {
  std::string text = replaced(circleText, "chords 0.01", std::string(sampling) + " 0.001");
  text = replaced(text, "    piece at 0 over 0 .. 6.283185307179586\n",
                  "    piece at 0 over 0 .. 6.283185307179586\n    grid 0.0001\n");
  // Down to the lap's height first: the blocks start where the machine is.
  return replaced(text, "  %4 = curve.lap", "  move.feed %0, %3, %2, %1\n  %4 = curve.lap");
}

// Every feed move's end within `tolerance` of the circle of radius 5.
inline void expectOnTheCircle(const ToolPath& path, double tolerance) {
  std::size_t feeds = 0;
  for (const MachineEvent& event : path.events) {
    if (event.kind == MachineEvent::Kind::Feed) {
      ++feeds;
      EXPECT_NEAR(std::hypot(event.x, event.y), 5, tolerance) << event.x << ", " << event.y;
    }
  }
  EXPECT_GT(feeds, 20u);
}

// A loop over three passes, each a lap around the circle at z = -pass.
// Each region computes what a pass could mishandle: `mul %t, %two` (the
// lap's parameter: nothing leaves the lap), `mul %r, %two` in both regions
// (equal expressions in sibling regions), an unused value.
inline Function passesAroundTwoPieces() {
  FunctionBuilder builder("passes");
  ValueId r = builder.parameter(builder.addParameter("r", 5));
  CurveTableEntry entry;
  entry.pieces = {{0, 0, 1}, {1, 0, pi}};
  entry.to = 1 + pi;
  entry.amount = 0.01;
  std::uint32_t curve = builder.addCurve(entry);
  ValueId zero = builder.constant(0);
  ValueId one = builder.constant(1);
  ValueId two = builder.constant(2);
  ValueId feed = builder.constant(300);
  ValueId pass = builder.beginLoop(one, builder.constant(3));
  ValueId depth = builder.unary(Opcode::Neg, pass);
  ValueId t = builder.beginCurveLap(curve, depth, depth, feed);
  ValueId diameter = builder.binary(Opcode::Mul, r, two);
  ValueId twice = builder.binary(Opcode::Mul, t, two);
  builder.binary(Opcode::Sub, twice, twice); // unused
  builder.curvePoint(builder.binary(Opcode::Mul, twice, diameter), zero, zero);
  diameter = builder.binary(Opcode::Mul, r, two);
  ValueId x = builder.binary(Opcode::Add, builder.binary(Opcode::Mul, two, diameter),
                             builder.binary(Opcode::Mul, r, builder.unary(Opcode::Sin, t)));
  ValueId y =
      builder.binary(Opcode::Sub, r, builder.binary(Opcode::Mul, r, builder.unary(Opcode::Cos, t)));
  builder.curvePoint(x, y, builder.binary(Opcode::Mul, t, zero));
  builder.endLoop();
  return builder.finish();
}

} // namespace cncc::ir::curve_lap_test
