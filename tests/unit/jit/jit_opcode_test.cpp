// Every IR operation, in hand-built functions, run by the interpreter and the
// JIT. The inputs come from tables indexed by loops whose bounds are part
// parameters, so that LLVM cannot fold the operations away at compile time:
// the native code itself computes them.
#include "jit_test_support.h"

#include "cncc/geom/nurbs_curve.h"
#include "cncc/ir/builder.h"
#include "cncc/ir/nurbs_move.h"
#include "cncc/ir/spline_move.h"
#include "cncc/ir/verifier.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

namespace cncc {
namespace {

using ir::FunctionBuilder;
using ir::Opcode;
using ir::ValueId;

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

const std::vector<double> kUnaryInputs = {
    -2.5, -1,  -0.75, -0.5,    -0.0,      0,          0.3,  0.5,  0.999, 1,         1.5, 2.5,
    3,    100, 1e300, -1e-300, kInfinity, -kInfinity, kNaN, 7.25, -7.25, 3.1415926, 1e-8};
const std::vector<double> kBinaryInputs = {-3, -1.5, -0.5, -0.0, 0,         0.5,        1,
                                           2,  2.5,  7,    1e10, kInfinity, -kInfinity, kNaN};

struct OpcodeCase {
  std::string name;
  ir::Function function;
};

// `for i in 0 .. count - 1 { a = table[i]; ... }` with count a parameter.
ValueId beginTableLoop(FunctionBuilder& builder, const std::vector<double>& values,
                       const std::string& countName) {
  std::uint32_t table = builder.addTable(values);
  std::uint32_t count = builder.addParameter(countName, static_cast<double>(values.size()));
  ValueId last = builder.binary(Opcode::Sub, builder.parameter(count), builder.constant(1));
  ValueId index = builder.beginLoop(builder.constant(0), last);
  return builder.tableLoad(table, index);
}

OpcodeCase unaryCase(Opcode opcode) {
  FunctionBuilder builder(std::string(ir::opcodeInfo(opcode).spelling));
  ValueId a = beginTableLoop(builder, kUnaryInputs, "count");
  builder.feed(builder.unary(opcode, a), a, builder.constant(0), builder.constant(0));
  builder.endLoop();
  return {builder.function().name, builder.finish()};
}

// (a, b) over every pair of inputs; `combine` makes the fed value.
template <typename Combine> OpcodeCase pairCase(const std::string& name, Combine combine) {
  FunctionBuilder builder(name);
  ValueId a = beginTableLoop(builder, kBinaryInputs, "rows");
  ValueId b = beginTableLoop(builder, kBinaryInputs, "columns");
  builder.feed(combine(builder, a, b), a, b, builder.constant(0));
  builder.endLoop();
  builder.endLoop();
  return {name, builder.finish()};
}

OpcodeCase binaryCase(Opcode opcode) {
  return pairCase(std::string(ir::opcodeInfo(opcode).spelling),
                  [opcode](FunctionBuilder& builder, ValueId a, ValueId b) {
                    return builder.binary(opcode, a, b);
                  });
}

// A comparison, through select (1 or 2) and through if (feed or rapid).
OpcodeCase comparisonCase(Opcode opcode) {
  FunctionBuilder builder(std::string(ir::opcodeInfo(opcode).spelling));
  ValueId a = beginTableLoop(builder, kBinaryInputs, "rows");
  ValueId b = beginTableLoop(builder, kBinaryInputs, "columns");
  ValueId holds = builder.binary(opcode, a, b);
  ValueId chosen =
      builder.operation(Opcode::Select, {holds, builder.constant(1), builder.constant(2)});
  builder.beginIf(holds);
  builder.feed(a, b, chosen, builder.constant(100));
  builder.beginElse();
  builder.rapid(a, b, chosen);
  builder.endIf();
  builder.endLoop();
  builder.endLoop();
  return {builder.function().name, builder.finish()};
}

// And, or, not on comparisons of the inputs with 1 and 0.
OpcodeCase logicCase(Opcode opcode) {
  return pairCase(std::string(ir::opcodeInfo(opcode).spelling),
                  [opcode](FunctionBuilder& builder, ValueId a, ValueId b) {
                    ValueId left = builder.binary(Opcode::Lt, a, builder.constant(1));
                    ValueId right = builder.binary(Opcode::Gt, b, builder.constant(0));
                    ValueId combined = opcode == Opcode::Not ? builder.unary(Opcode::Not, left)
                                                             : builder.binary(opcode, left, right);
                    return builder.operation(
                        Opcode::Select, {combined, builder.constant(10), builder.constant(20)});
                  });
}

// Constant bools, parameters, the effects without a computed position.
OpcodeCase effectsCase() {
  FunctionBuilder builder("effects");
  std::uint32_t diameter = builder.addParameter("diameter", 6.35);
  std::uint32_t speed = builder.addParameter("speed", 12000);
  builder.comment("a \"quoted\" comment");
  builder.origin(54.1, 3);
  builder.tool(7, builder.parameter(diameter), 12);
  builder.spindle(builder.parameter(speed));
  builder.coolant(ir::CoolantMode::Mist);
  builder.contouring(0.01);
  builder.compensation(-2.5, 4);
  builder.cornerArc(builder.constant(0.6), builder.parameter(speed));
  builder.cutBegin(0);
  ValueId never = builder.constantBool(false);
  ValueId always = builder.constantBool(true);
  ValueId pick =
      builder.operation(Opcode::Select, {always, builder.constant(1), builder.constant(2)});
  builder.beginIf(never);
  builder.comment("never");
  builder.beginElse();
  builder.comment("always");
  builder.rapid(pick, builder.constant(-2), builder.constant(5));
  builder.endIf();
  builder.climb(builder.parameter(diameter)); // Z alone, from (1, -2)
  ValueId pass = builder.beginLoop(builder.constant(1), builder.constant(3), ir::LoopRole::Passes);
  builder.passBegin(builder.binary(Opcode::Mul, pass, builder.constant(-0.1)));
  builder.endLoop();
  builder.cutBegin(3);
  builder.comment("");
  builder.contouring(0);
  builder.compensation(0, 0);
  builder.origin(59);
  builder.coolant(ir::CoolantMode::Off);
  builder.home();
  return {"effects", builder.finish()};
}

// Loops with fractional, negative, empty and nested bounds; an if in a loop.
OpcodeCase loopsCase() {
  FunctionBuilder builder("loops");
  std::uint32_t high = builder.addParameter("high", 3.7);
  ValueId outer = builder.beginLoop(builder.constant(-1.5), builder.parameter(high));
  ValueId inner = builder.beginLoop(outer, builder.constant(1));
  ValueId odd = builder.binary(
      Opcode::Ne,
      builder.binary(Opcode::Rem, builder.unary(Opcode::Abs, inner), builder.constant(2)),
      builder.constant(0.5));
  builder.beginIf(odd);
  builder.feed(outer, inner, builder.constant(-1), builder.constant(50));
  builder.endIf();
  builder.endLoop();
  builder.beginLoop(builder.constant(2), builder.constant(1)); // runs nothing
  builder.comment("unreachable");
  builder.endLoop();
  builder.endLoop();
  return {"loops", builder.finish()};
}

// A loop whose variable advances by a step computed in its body (loop.next):
// u = 0, 0.1, 0.3, 0.7 and then 1 (the step doubles, the last is cut short);
// a second one that starts at its bound runs nothing.
OpcodeCase advancingLoopCase() {
  FunctionBuilder builder("advancing_loop");
  ValueId start = builder.parameter(builder.addParameter("start", 0.1));
  ValueId one = builder.constant(1);
  ValueId u = builder.beginLoop(builder.constant(0), one, ir::LoopRole::Curve);
  ValueId step = builder.binary(Opcode::Max, start, u);
  ValueId next = builder.binary(Opcode::Min, builder.binary(Opcode::Add, u, step), one);
  builder.feed(next, u, builder.constant(0), builder.constant(100));
  builder.endLoopAdvancingTo(next);
  ValueId never = builder.beginLoop(one, one);
  builder.feed(never, never, never, builder.constant(100));
  builder.endLoopAdvancingTo(builder.binary(Opcode::Add, never, one));
  return {"advancing_loop", builder.finish()};
}

// Arcs from where the last move ended: a quarter counter-clockwise, a full
// clockwise turn, a helical half turn; the radius a parameter, an alarm
// when it is not positive.
OpcodeCase arcsCase() {
  FunctionBuilder builder("arcs");
  ValueId radius = builder.parameter(builder.addParameter("radius", 5));
  ValueId zero = builder.constant(0);
  ValueId feed = builder.constant(250);
  ValueId negated = builder.unary(Opcode::Neg, radius);
  builder.beginIf(builder.binary(Opcode::Le, radius, zero));
  builder.alarm("no radius");
  builder.endIf();
  builder.rapid(radius, zero, zero);
  builder.arc(ir::ArcTurn::CounterClockwise, zero, radius, zero, negated, zero, feed);
  builder.arc(ir::ArcTurn::Clockwise, zero, radius, zero, zero, negated, feed);
  builder.arc(ir::ArcTurn::CounterClockwise, zero, negated, builder.constant(-2), zero, negated,
              feed);
  return {"arcs", builder.finish()};
}

// A NURBS move whose middle weight is a parameter, from a plunge onto its
// first control point.
OpcodeCase nurbsCase() {
  FunctionBuilder builder("nurbs");
  ValueId weight = builder.parameter(builder.addParameter("w", 3));
  geom::NurbsCurve curve(geom::KnotVector({0, 0, 0, 1, 1, 1}, 2),
                         {{0, 0, 0}, {5, 8, 0}, {10, 0, 0}}, {1, 1, 1});
  std::uint32_t table = builder.addTable(ir::nurbsMoveTable(curve));
  ValueId zero = builder.constant(0);
  ValueId one = builder.constant(1);
  ValueId feed = builder.constant(200);
  ValueId depth = builder.constant(-0.5);
  builder.rapid(zero, zero, zero);
  builder.feed(zero, zero, depth, feed);
  builder.nurbs(table, depth, feed, {one, weight, one});
  return {"nurbs", builder.finish()};
}

// A C spline after a ramp's chord (a tangent start), then a B spline.
OpcodeCase splineCase() {
  FunctionBuilder builder("spline");
  ir::SplineBlockData cspline;
  cspline.kind = ir::SplineKind::CSpline;
  cspline.start = geom::SplineEndCondition::Tangent;
  cspline.points = {{5, 3, 0}, {10, 0, 0}, {15, 2, 0}};
  ir::SplineBlockData bspline;
  bspline.degree = 2;
  bspline.points = {{20, 5, 0}, {25, 0, 0}};
  bspline.weights = {2, 1};
  bspline.intervals = {0, 1};
  std::uint32_t first = builder.addTable(ir::splineMoveTable(cspline));
  std::uint32_t second = builder.addTable(ir::splineMoveTable(bspline));
  ValueId feed = builder.constant(250);
  ValueId depth = builder.parameter(builder.addParameter("depth", -0.5));
  builder.rapid(builder.constant(-4), builder.constant(0), builder.constant(1));
  builder.feed(builder.constant(0), builder.constant(0), depth, feed);
  builder.spline(first, depth, feed);
  builder.spline(second, depth, feed);
  return {"spline", builder.finish()};
}

// A cubic span (Heidenhain SPL) from a plunge onto its start, its end a
// parameter's value: x(t) = 3t^3 - 2t^2 + (9 - x) t + x, y(t) = t^2 - t.
OpcodeCase polynomialCase() {
  FunctionBuilder builder("polynomial");
  ValueId endX = builder.parameter(builder.addParameter("x", 1));
  ValueId zero = builder.constant(0);
  ValueId ten = builder.constant(10);
  ValueId feed = builder.constant(150);
  ValueId depth = builder.constant(-1);
  builder.rapid(ten, zero, zero);
  builder.feed(ten, zero, depth, feed);
  ValueId k1x = builder.binary(Opcode::Sub, builder.constant(9), endX);
  builder.operation(Opcode::Polynomial,
                    {endX, zero, depth, builder.constant(3), builder.constant(-2), k1x, zero,
                     builder.constant(1), builder.constant(-1), zero, zero, zero, feed});
  return {"polynomial", builder.finish()};
}

std::vector<OpcodeCase> opcodeCases() {
  std::vector<OpcodeCase> cases;
  for (Opcode opcode : {Opcode::Neg, Opcode::Abs, Opcode::Sqrt, Opcode::Sin, Opcode::Cos,
                        Opcode::Tan, Opcode::Asin, Opcode::Acos, Opcode::Atan, Opcode::Exp,
                        Opcode::Ln, Opcode::Floor, Opcode::Ceil, Opcode::Round}) {
    cases.push_back(unaryCase(opcode));
  }
  for (Opcode opcode : {Opcode::Add, Opcode::Sub, Opcode::Mul, Opcode::Div, Opcode::Rem,
                        Opcode::Pow, Opcode::Min, Opcode::Max, Opcode::Atan2}) {
    cases.push_back(binaryCase(opcode));
  }
  for (Opcode opcode : {Opcode::Lt, Opcode::Le, Opcode::Gt, Opcode::Ge, Opcode::Eq, Opcode::Ne}) {
    cases.push_back(comparisonCase(opcode));
  }
  for (Opcode opcode : {Opcode::And, Opcode::Or, Opcode::Not}) {
    cases.push_back(logicCase(opcode));
  }
  cases.push_back(effectsCase());
  cases.push_back(loopsCase());
  cases.push_back(advancingLoopCase());
  cases.push_back(arcsCase());
  cases.push_back(nurbsCase());
  cases.push_back(splineCase());
  cases.push_back(polynomialCase());
  return cases;
}

class JitOpcodeTest : public ::testing::TestWithParam<std::size_t> {};

TEST_P(JitOpcodeTest, MatchesTheInterpreter) {
  OpcodeCase opcodeCase = std::move(opcodeCases()[GetParam()]);
  SCOPED_TRACE(opcodeCase.name);
  ASSERT_TRUE(ir::verifyFunction(opcodeCase.function).empty());
  EXPECT_FALSE(ir::interpret(opcodeCase.function).events.empty());
  EXPECT_TRUE(jit_test::jitMatchesInterpreter(opcodeCase.function));
  // Streamed, the same events as stored.
  EXPECT_TRUE(jit_test::streamedMatchesStored(backends::CompiledFunction(opcodeCase.function)));
}

INSTANTIATE_TEST_SUITE_P(EveryOperation, JitOpcodeTest,
                         ::testing::Range<std::size_t>(0, opcodeCases().size()),
                         [](const ::testing::TestParamInfo<std::size_t>& info) {
                           return opcodeCases()[info.param].name;
                         });

// A new operation in ir_ops.def needs a case here (and code in the JIT);
// curve.lap and its regions' ends (curve.point, curve.arc, curve.walk) are
// expanded before the JIT and refused by it (jit_error_test.cpp).
TEST(JitOpcodes, EveryOperationOfTheIrIsTested) {
  std::set<Opcode> tested{Opcode::CurveLap, Opcode::CurvePoint, Opcode::CurveArc,
                          Opcode::CurveWalk};
  for (const OpcodeCase& opcodeCase : opcodeCases()) {
    for (const ir::Instruction& instruction : opcodeCase.function.instructions) {
      tested.insert(instruction.opcode);
    }
  }
  for (Opcode opcode : ir::allOpcodes()) {
    EXPECT_TRUE(tested.count(opcode)) << ir::opcodeInfo(opcode).spelling << " is not tested";
  }
}

TEST(JitOpcodes, UsesTheSameMathAsTheInterpreterBitForBit) {
  // Not only within the tolerance: the JIT calls the same C functions.
  for (Opcode opcode : {Opcode::Sin, Opcode::Exp, Opcode::Ln, Opcode::Atan}) {
    OpcodeCase opcodeCase = unaryCase(opcode);
    ir::ToolPath interpreted = ir::interpret(opcodeCase.function);
    ir::ToolPath compiled = backends::runJit(opcodeCase.function);
    ASSERT_EQ(interpreted.events.size(), compiled.events.size());
    for (std::size_t i = 0; i < interpreted.events.size(); ++i) {
      double expected = interpreted.events[i].x;
      double actual = compiled.events[i].x;
      EXPECT_TRUE((std::isnan(expected) && std::isnan(actual)) || expected == actual)
          << opcodeCase.name << "(" << interpreted.events[i].y << ")";
    }
  }
}

TEST(JitOpcodes, AnArcWithoutARadiusFailsAsInTheInterpreter) {
  OpcodeCase opcodeCase = arcsCase();
  for (double radius : {0.0, 1e-9, 2.5}) {
    ir::InterpreterOptions options;
    options.parameters["radius"] = radius;
    jit_test::RunOutcome interpreted =
        jit_test::outcomeOf([&] { return ir::interpret(opcodeCase.function, options); });
    EXPECT_EQ(interpreted.failed, radius < 1e-5) << "radius " << radius;
    EXPECT_EQ(interpreted.error == "alarm: no radius", radius == 0) << interpreted.error;
    EXPECT_TRUE(jit_test::jitMatchesInterpreter(opcodeCase.function, options)) << radius;
    EXPECT_TRUE(
        jit_test::streamedMatchesStored(backends::CompiledFunction(opcodeCase.function), options))
        << radius;
  }
}

TEST(JitOpcodes, ParametersTakeTheirGivenValues) {
  OpcodeCase opcodeCase = loopsCase();
  backends::CompiledFunction compiled(opcodeCase.function);
  for (double high : {-5.0, 0.0, 2.0, 6.5}) {
    ir::InterpreterOptions options;
    options.parameters["high"] = high;
    EXPECT_TRUE(jit_test::sameOutcome(
        jit_test::outcomeOf([&] { return ir::interpret(opcodeCase.function, options); }),
        jit_test::outcomeOf([&] { return compiled.run(options); })))
        << "high = " << high;
  }
  ir::InterpreterOptions empty;
  empty.parameters["high"] = -5;
  EXPECT_TRUE(compiled.run(empty).events.empty());
}

} // namespace
} // namespace cncc
