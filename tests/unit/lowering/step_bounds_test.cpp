// A count the controller would compute past the limit of one piece (a
// weight of 1e9 beside a weight that is a parameter): the lowering emits the
// steps lap as for any count, and the legalisation bound-controller-steps
// cuts it at points chosen when compiling; the IR before the legalisation
// runs the same path as after it, and the parameter is fixed.
#include "lowered_text.h"

#include "cncc/ir/curve_lap.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/passes.h"
#include "cncc/ir/verifier.h"

#include <gtest/gtest.h>

namespace cncc::ir {
namespace {

constexpr const char* heavyWeight = R"(part s_profile(depth = 3, step = 1, w6 = 3) {
  units mm
  tool 1 diameter=10 spindle=3000 feed=300
  safe z=5
  let P = [
    (25, 50), (42.8735, 24.1467), (70.5832, 72.3597), (86.608, 165.3624), (112.4532, 38.3852),
    (132.4671, 35.1148), (175, 150)
  ]
  curve nurbs(order=4, points=P, weights=[1, 1, 1e9, 1, 1, w6, 1]) sweep depth=depth step=step
    tolerance=0.01
}
)";

LoweringOptions fanucLike() {
  LoweringOptions options;
  options.controllerLoops = true;
  options.coordinateIncrement = 0.001;
  options.literalSignificantDigits = 8;
  options.expandCurveLaps = false;
  return options;
}

std::size_t lapsCutBy(const Function& function, CurveSampling sampling) {
  std::size_t laps = 0;
  for (const Instruction& instruction : function.instructions) {
    laps += instruction.opcode == Opcode::CurveLap &&
            function.curves[instruction.index].sampling == sampling;
  }
  return laps;
}

TEST(StepBounds, TheLoweringLeavesACountPastTheLimitToTheLegalisation) {
  auto lowered = test_support::lowerText(heavyWeight, fanucLike());
  ASSERT_TRUE(lowered->part);
  Function& function = lowered->part->function;
  EXPECT_EQ(lapsCutBy(function, CurveSampling::Steps), 1u);
  EXPECT_FALSE(function.parameters[2].fixed); // w6, before the legalisation
  ToolPath before = interpret(function);

  ASSERT_TRUE(legaliseCurves(function, lowered->diagnostics));
  EXPECT_TRUE(verifyFunction(function).empty());
  EXPECT_EQ(lapsCutBy(function, CurveSampling::Steps), 0u);
  EXPECT_TRUE(function.parameters[2].fixed);
  EXPECT_FALSE(function.parameters[0].fixed); // depth and step stay editable
  EXPECT_FALSE(function.parameters[1].fixed);
  const frontend::Diagnostic* fixed = nullptr;
  for (const frontend::Diagnostic& diagnostic : lowered->diagnostics.diagnostics()) {
    fixed = diagnostic.kind == frontend::DiagnosticKind::ParameterFixed ? &diagnostic : fixed;
  }
  ASSERT_NE(fixed, nullptr);
  EXPECT_NE(fixed->message.find("more than 100000 steps of one piece"), std::string::npos);

  ToolPath after = interpret(function);
  ASSERT_EQ(before.events.size(), after.events.size());
  for (std::size_t k = 0; k < before.events.size(); ++k) {
    EXPECT_EQ(before.events[k].kind, after.events[k].kind) << k;
    EXPECT_NEAR(before.events[k].x, after.events[k].x, 1e-9) << k;
    EXPECT_NEAR(before.events[k].y, after.events[k].y, 1e-9) << k;
    EXPECT_NEAR(before.events[k].z, after.events[k].z, 1e-9) << k;
  }
  // Three passes of the same points: tens, not a hundred million.
  std::size_t feeds = 0;
  for (const MachineEvent& event : after.events) {
    feeds += event.kind == MachineEvent::Kind::Feed;
  }
  EXPECT_GT(feeds, 3u * 20);
  EXPECT_LT(feeds, 3u * 200);
}

} // namespace
} // namespace cncc::ir
